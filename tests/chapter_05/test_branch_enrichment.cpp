// Which nodes a cut ending inside the mesh enriches with branch functions and which with the
// sign (xfem/branch_enrichment.hpp): the topological rule against the tets found by sampling the
// front, the geometric rule against the distances, the sets nested, a node never both, and a
// front through nodes, along edges and in faces classified without NaN, the same every time.
#include "kerf/cut/crack_front.hpp"
#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/point_locator.hpp"
#include "kerf/xfem/branch_enrichment.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <set>
#include <vector>

namespace {

struct Body {
  kerf::TetMesh mesh;
  kerf::CutSurfaces cuts;
  kerf::MeshPieces pieces;
  kerf::CrackFronts fronts;
  Body(kerf::TetMesh m, const kerf::RectangleCut& cut)
      : mesh(std::move(m)), cuts({kerf::rectangle_surface(cut)}), pieces(kerf::cut_mesh_into_pieces(mesh, cuts)),
        fronts(kerf::find_crack_fronts(mesh, cuts)) {}
};

std::set<int> nodes_of_kind(const kerf::BranchEnrichment& e, kerf::NodeEnrichmentKind k) {
  std::set<int> s;
  for (std::size_t i = 0; i < e.kind.size(); ++i)
    if (e.kind[i] == k) s.insert(static_cast<int>(i));
  return s;
}

void check_consistent(const kerf::TetMesh& mesh, const kerf::MeshPieces& pieces, const kerf::BranchEnrichment& e) {
  int branch = 0;
  for (Eigen::Index i = 0; i < mesh.num_nodes(); ++i) {
    const auto kind = e.kind[static_cast<std::size_t>(i)];
    // Never both: a branch node has no sign enrichment left, a sign node has at least one.
    if (kind == kerf::NodeEnrichmentKind::branch) {
      CHECK(e.sign.enrichments_of(i) == 0);
      const int slot = e.branch_slot[static_cast<std::size_t>(i)];
      REQUIRE(slot == branch);
      CHECK(e.branch_node[static_cast<std::size_t>(slot)] == i);
      CHECK(e.node_values[static_cast<std::size_t>(slot)].allFinite());
      ++branch;
    } else {
      CHECK(e.branch_slot[static_cast<std::size_t>(i)] == -1);
      CHECK((kind == kerf::NodeEnrichmentKind::sign) == (e.sign.enrichments_of(i) > 0));
    }
  }
  CHECK(branch == e.num_branch_nodes());
  // Paulus section 3.3: a node of a completely cut tet is sign enriched unless it is branch.
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    if (pieces.state(t) != kerf::SurfaceCutState::completely_cut) continue;
    for (int a = 0; a < 4; ++a) CHECK(e.kind[static_cast<std::size_t>(mesh.tets(t, a))] != kerf::NodeEnrichmentKind::none);
  }
  // The tet flags follow from the node kinds.
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    int n = 0;
    for (int a = 0; a < 4; ++a) n += e.kind[static_cast<std::size_t>(mesh.tets(t, a))] == kerf::NodeEnrichmentKind::branch;
    CHECK(static_cast<bool>(e.has_branch_nodes[static_cast<std::size_t>(t)]) == (n > 0));
    CHECK(static_cast<bool>(e.blending[static_cast<std::size_t>(t)]) == (n > 0 && n < 4));
  }
}

} // namespace

TEST_CASE("a rectangle ending mid-element: topological branch nodes are those of the tets the front crosses") {
  // Front x = 0.4, z = 0.55 (both inside cells of size 0.25), y from 0 to 1.
  const Body body(kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {4, 4, 4}), kerf::RectangleCut({-0.1, -0.1, 0.55}, {0.5, 0, 0}, {0, 1.2, 0}));
  const kerf::BranchEnrichment top = kerf::make_branch_enrichment(body.mesh, body.pieces, body.fronts, kerf::TipEnrichmentRule::topological);
  check_consistent(body.mesh, body.pieces, top);
  // Independently: the tets holding points sampled densely along the front.
  const kerf::PointLocator locator(body.mesh);
  std::set<int> expected_nodes, expected_tets;
  for (int k = 0; k <= 2000; ++k) {
    const kerf::PointLocation where = locator.locate({0.4, (k + 0.5) / 2001.0, 0.55});
    REQUIRE(where.tet >= 0);
    expected_tets.insert(static_cast<int>(where.tet));
    for (int a = 0; a < 4; ++a) expected_nodes.insert(body.mesh.tets(where.tet, a));
  }
  CHECK(nodes_of_kind(top, kerf::NodeEnrichmentKind::branch) == expected_nodes);
  std::set<int> front_tets;
  for (std::size_t t = 0; t < top.front_tet.size(); ++t)
    if (top.front_tet[t]) front_tets.insert(static_cast<int>(t));
  CHECK(front_tets == expected_tets);
  // Every front tet is partially cut (the front is inside it, it stays one piece).
  for (const int t : front_tets) CHECK(body.pieces.state(t) == kerf::SurfaceCutState::partially_cut);
  // The cut's nodes: those chapter 4 enriches (supports split), minus the branch ones.
  CHECK(top.count(kerf::NodeEnrichmentKind::sign) > 0);
  CHECK(top.count(kerf::NodeEnrichmentKind::branch) == static_cast<int>(expected_nodes.size()));
  MESSAGE("topological: " << top.num_branch_nodes() << " branch nodes, " << top.count(kerf::NodeEnrichmentKind::sign)
                          << " sign nodes, " << front_tets.size() << " front tets");
}

TEST_CASE("the geometric rule enriches every node within r_e, grows with r_e, and contains the topological set") {
  const Body body(kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {4, 4, 4}), kerf::RectangleCut({-0.1, -0.1, 0.55}, {0.5, 0, 0}, {0, 1.2, 0}));
  const std::set<int> top = nodes_of_kind(
      kerf::make_branch_enrichment(body.mesh, body.pieces, body.fronts, kerf::TipEnrichmentRule::topological), kerf::NodeEnrichmentKind::branch);
  std::set<int> previous = top;
  for (const double radius : {0.0, 0.1, 0.2, 0.3, 0.45, 0.7}) {
    const kerf::BranchEnrichment geo =
        kerf::make_branch_enrichment(body.mesh, body.pieces, body.fronts, kerf::TipEnrichmentRule::geometric, radius);
    check_consistent(body.mesh, body.pieces, geo);
    // Expected: the topological set and every node whose distance to the front line (every node
    // of the box projects onto the front's y-range) is at most r_e.
    std::set<int> expected = top;
    for (Eigen::Index i = 0; i < body.mesh.num_nodes(); ++i)
      if (std::hypot(body.mesh.nodes(i, 0) - 0.4, body.mesh.nodes(i, 2) - 0.55) <= radius) expected.insert(static_cast<int>(i));
    const std::set<int> got = nodes_of_kind(geo, kerf::NodeEnrichmentKind::branch);
    CHECK(got == expected);
    CHECK(std::includes(got.begin(), got.end(), previous.begin(), previous.end()));
    MESSAGE("geometric r_e = " << radius << ": " << got.size() << " branch nodes, " << geo.count(kerf::NodeEnrichmentKind::sign)
                               << " sign nodes");
    previous = got;
  }
  CHECK(previous.size() > top.size());
  CHECK_THROWS_AS(kerf::make_branch_enrichment(body.mesh, body.pieces, body.fronts, kerf::TipEnrichmentRule::geometric, -1.0),
                  std::invalid_argument);
}

TEST_CASE("fronts through nodes, along edges and in faces give a valid classification, the same every time") {
  struct Case {
    const char* name;
    kerf::RectangleCut cut;
  };
  // The cells are 0.25 wide: z = 0.5 is a plane of mesh faces and x = 0.5 one of nodes.
  const std::vector<Case> cases{
      {"front along mesh edges (x = 0.5, z = 0.5)", kerf::RectangleCut({-0.1, -0.1, 0.5}, {0.6, 0, 0}, {0, 1.2, 0})},
      {"front in mesh faces (x = 0.4, z = 0.5)", kerf::RectangleCut({-0.1, -0.1, 0.5}, {0.5, 0, 0}, {0, 1.2, 0})},
      {"front through nodes (x + y = 1 in z = 0.5)",
       kerf::RectangleCut({1.5, -0.5, 0.5}, Eigen::Vector3d(-1, -1, 0).normalized() * 2.0, Eigen::Vector3d(-1, 1, 0).normalized() * 3.0)},
  };
  for (const Case& c : cases) {
    INFO(c.name);
    const Body body(kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {4, 4, 4}), c.cut);
    REQUIRE_FALSE(body.fronts.empty());
    for (const auto rule : {kerf::TipEnrichmentRule::topological, kerf::TipEnrichmentRule::geometric}) {
      const kerf::BranchEnrichment e1 = kerf::make_branch_enrichment(body.mesh, body.pieces, body.fronts, rule, 0.2);
      const kerf::BranchEnrichment e2 = kerf::make_branch_enrichment(body.mesh, body.pieces, body.fronts, rule, 0.2);
      check_consistent(body.mesh, body.pieces, e1);
      CHECK(e1.num_branch_nodes() > 0);
      CHECK(e1.kind == e2.kind);
      CHECK(e1.branch_node == e2.branch_node);
      for (std::size_t k = 0; k < e1.node_values.size(); ++k) CHECK(e1.node_values[k] == e2.node_values[k]);
      // A branch node lying on the cut behind the front takes F_1 = +sqrt(r) (theta = +pi, the
      // side above, as chapter 4 homes such a node), one on the front F = 0.
      for (std::size_t k = 0; k < e1.branch_node.size(); ++k) {
        const int i = e1.branch_node[k];
        if (e1.cut_side[static_cast<std::size_t>(i)] == 0) continue;
        const kerf::FrontPolar p = body.fronts.polar(body.mesh.nodes.row(i).transpose(), 1);
        CHECK(std::abs(body.mesh.nodes(i, 2) - 0.5) < 1e-15);
        CHECK(e1.node_values[k](0) == kerf_test::relative(std::sqrt(p.r), 1e-12));
      }
    }
  }
}

TEST_CASE("a node on the cut behind the front is marked on the cut, and one off the cut is not") {
  // Cut in the plane of nodes z = 0.5, front at x = 0.4: nodes (0.25, y, 0.5) lie on the cut.
  const Body body(kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {4, 4, 4}), kerf::RectangleCut({-0.1, -0.1, 0.5}, {0.5, 0, 0}, {0, 1.2, 0}));
  const kerf::BranchEnrichment e = kerf::make_branch_enrichment(body.mesh, body.pieces, body.fronts, kerf::TipEnrichmentRule::topological);
  int on_cut = 0;
  for (const int i : e.branch_node) {
    const bool expected = std::abs(body.mesh.nodes(i, 2) - 0.5) < 1e-15 && body.mesh.nodes(i, 0) < 0.4;
    CHECK((e.cut_side[static_cast<std::size_t>(i)] == 1) == expected);
    on_cut += expected;
  }
  CHECK(on_cut == 5); // x = 0.25, z = 0.5, five values of y
}

TEST_CASE("Fries's correction: the ramp nodes are the other corners of the blending tets, keep their sign enrichments, and shift by 0") {
  const Body body(kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {4, 4, 4}), kerf::RectangleCut({-0.1, -0.1, 0.55}, {0.5, 0, 0}, {0, 1.2, 0}));
  for (const double radius : {0.0, 0.3}) {
    const kerf::TipEnrichmentRule rule = radius > 0.0 ? kerf::TipEnrichmentRule::geometric : kerf::TipEnrichmentRule::topological;
    const kerf::BranchEnrichment plain = kerf::make_branch_enrichment(body.mesh, body.pieces, body.fronts, rule, radius);
    const kerf::BranchEnrichment corrected =
        kerf::make_branch_enrichment(body.mesh, body.pieces, body.fronts, rule, radius, kerf::BlendingCorrection::corrected);
    // I* and the sign enrichment are the uncorrected ones: the correction only adds slots.
    CHECK(corrected.kind == plain.kind);
    CHECK(corrected.sign.num_enrichments() == plain.sign.num_enrichments());
    CHECK(corrected.blending == plain.blending);
    // Expected ramp nodes, from the uncorrected enrichment's blending flags alone.
    std::set<int> expected;
    for (Eigen::Index t = 0; t < body.mesh.num_tets(); ++t)
      if (plain.blending[static_cast<std::size_t>(t)])
        for (int a = 0; a < 4; ++a)
          if (plain.kind[static_cast<std::size_t>(body.mesh.tets(t, a))] != kerf::NodeEnrichmentKind::branch)
            expected.insert(body.mesh.tets(t, a));
    std::set<int> ramp, sign_and_ramp;
    for (int k = 0; k < corrected.num_branch_nodes(); ++k) {
      const int v = corrected.branch_node[static_cast<std::size_t>(k)];
      CHECK(corrected.branch_slot[static_cast<std::size_t>(v)] == k);
      if (corrected.kind[static_cast<std::size_t>(v)] == kerf::NodeEnrichmentKind::branch) {
        // A node of I*: its shift is F at the node, as without the correction (R(x_v) = 1).
        const int k_plain = plain.branch_slot[static_cast<std::size_t>(v)];
        REQUIRE(k_plain >= 0);
        CHECK((corrected.node_values[static_cast<std::size_t>(k)] - plain.node_values[static_cast<std::size_t>(k_plain)]).norm() == 0.0);
        continue;
      }
      ramp.insert(v);
      CHECK(corrected.node_values[static_cast<std::size_t>(k)].norm() == 0.0); // R(x_v) = 0
      if (corrected.sign.enrichments_of(v) > 0) sign_and_ramp.insert(v);
    }
    CHECK(ramp == expected);
    CHECK(corrected.num_ramp_nodes() == static_cast<int>(expected.size()));
    CHECK(corrected.num_branch_nodes() == plain.num_branch_nodes() + static_cast<int>(expected.size()));
    CHECK(plain.num_ramp_nodes() == 0);
    // Behind the front some ramp nodes' supports are split by the cut: they carry both.
    CHECK(!ramp.empty());
    CHECK(!sign_and_ramp.empty());
    MESSAGE("radius " << radius << ": " << plain.count(kerf::NodeEnrichmentKind::branch) << " nodes in I*, " << ramp.size()
                      << " ramp nodes, " << sign_and_ramp.size() << " of them sign enriched too");
  }
}
