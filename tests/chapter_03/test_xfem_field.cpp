// The enriched field: two traction-free constant-strain states, one on each side of an oblique
// cut, reproduced exactly (a patch test for the cut body), also for cuts through a node and
// along an edge; the field against eq. 42 written out independently, and the Kronecker
// property u(x_i) = u_i of the shifted enrichment.
#include "xfem_test_support.hpp"

#include "kerf/mesh/point_locator.hpp"
#include "kerf/xfem/xfem_field.hpp"
#include "kerf/xfem/xfem_model.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <optional>
#include <random>
#include <string>

using namespace xfem_test;

namespace {

const kerf::LinearMaterial material{1000.0, 0.3, 1000.0};

struct PatchOutcome {
  double worst_point = 0.0, worst_node = 0.0, scale = 0.0;
  int points[2] = {0, 0}; // above, below
};

// Solves linear XFEM on the unit cube cut by `cut` with every surface DOF held at the two affine
// fields (see affine_conditions), then compares the field at random points and the side values
// at the interior nodes with the fields.
PatchOutcome affine_patch(const kerf::TetMesh& mesh, const kerf::RectangleCut& cut, const kerf::Enrichment& e) {
  const Eigen::Vector3d n = cut.normal();
  // Two different states: uniaxial stresses along two directions in the cut plane, different
  // rotations and translations. Strains about 1e-2.
  const AffineField above = traction_free_field(material, n, {1.0, 0.2, -0.4}, 12.0, {0.01, -0.02, 0.005}, {0.001, 0.002, -0.003});
  const AffineField below = traction_free_field(material, n, {-0.3, 1.0, 0.5}, -7.0, {-0.015, 0.004, 0.02}, {-0.002, 0.0, 0.004});
  const kerf::XfemModel model(mesh, material, e);
  const Eigen::Vector3d lo(0, 0, 0), hi(1, 1, 1);
  const auto conditions = affine_conditions(model, above, below, lo, hi);
  const Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * model.num_dof_nodes());
  const Eigen::VectorXd u = kerf::solve_linear_xfem(model, kerf::make_xfem_dof_map(model, conditions), f, {});
  PatchOutcome out;
  REQUIRE(u.allFinite());
  out.scale = std::max((above.G.cwiseAbs().maxCoeff() + above.c.cwiseAbs().maxCoeff()),
                       (below.G.cwiseAbs().maxCoeff() + below.c.cwiseAbs().maxCoeff()));

  const kerf::PointLocator locator(mesh);
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> coordinate(0.01, 0.99);
  for (int p = 0; p < 400; ++p) {
    const Eigen::Vector3d x(coordinate(rng), coordinate(rng), coordinate(rng));
    const double distance = cut.signed_distance_to_plane(x);
    if (std::abs(distance) < 1e-9) continue; // on the cut the field is double-valued
    const kerf::PointLocation location = locator.locate(x);
    REQUIRE(location.tet >= 0);
    const int side = distance > 0 ? +1 : -1;
    CHECK(kerf::side_of_point(model, location.tet, x) == side);
    const Eigen::Vector3d expected = side > 0 ? above(x) : below(x);
    out.worst_point = std::max(out.worst_point, (kerf::xfem_displacement(model, u, location.tet, x) - expected).cwiseAbs().maxCoeff());
    ++out.points[side > 0 ? 0 : 1];
  }
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v)
    for (const int side : {+1, -1}) {
      const auto k = static_cast<std::size_t>(v);
      if (e.node_sign[k] != side && e.enriched_index[k] < 0) continue;
      const Eigen::Vector3d x = node(mesh, v);
      out.worst_node = std::max(out.worst_node, (node_side_value(model, u, static_cast<int>(v), side) - (side > 0 ? above(x) : below(x)))
                                                    .cwiseAbs()
                                                    .maxCoeff());
    }
  return out;
}

// The patch test's tolerance: the fields are of size ~1e-2 and the systems are well conditioned
// (no piece below 1e-4 of its tet): round-off is ~1e-15, so 1e-10 relative is loose yet would
// catch any consistency error, which shows at the size of the strains (1e-2).
void check_patch(const PatchOutcome& out, const char* what) {
  MESSAGE(std::string(what) << ": max error at " << out.points[0] << " points above and " << out.points[1] << " below " << out.worst_point
               << ", at nodes " << out.worst_node << " (field scale " << out.scale << ")");
  CHECK(out.points[0] > 50);
  CHECK(out.points[1] > 50);
  CHECK(out.worst_point <= 1e-10 * out.scale);
  CHECK(out.worst_node <= 1e-10 * out.scale);
}

// The enriched field against eq. 42 written out here, and the Kronecker property u(x_i) = u_i.
// For a random [u; a] (not a solution) we evaluate, in every tet, at its four corners and at
// three random points,
//   u(x) = sum_i Phi_i(x) u_i + sum_{i enriched} Phi_i(x) Psi_i(x) a_i,  Psi_i(x) = (H(x) - H_i) / 2,
// with Phi from barycentric coordinates solved from the corners, H(x) the sign of the cut
// plane's distance at x and H_i the sign of node i's level-set value (>= 0 counts as above,
// eqs. 58-59): nothing of the library's side operator, side_of_point or shape functions.
// At a corner x_i eq. 42 gives u_i (Phi_j(x_i) = delta_ij, Psi_i(x_i) = 0); the library must
// give the same there and everywhere else. A corner on the cut (Lambda_i = 0) counts as above,
// and so must the point x_i for side_of_point in a cut tet. Returns the number of (tet, corner)
// pairs on the cut checked, for the report.
int check_eq42_and_kronecker(const kerf::XfemModel& model, const kerf::RectangleCut& cut, const char* what) {
  const kerf::TetMesh& mesh = model.mesh();
  const kerf::Enrichment& e = model.enrichment();
  REQUIRE(e.snapped_nodes == 0); // the level set is then the plane's distance, and H(x) its sign
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> value(-1.0, 1.0), unit(0.0, 1.0);
  Eigen::VectorXd u(3 * model.num_dof_nodes());
  for (Eigen::Index i = 0; i < u.size(); ++i) u[i] = value(rng);
  const auto node_sign = [&](int v) { return e.level_set.lambda[v] >= 0.0 ? +1 : -1; };
  double worst_field = 0.0, worst_node = 0.0, worst_on_cut = 0.0;
  int checked = 0, on_cut = 0, on_cut_wrong_side = 0, enriched_points = 0;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const Eigen::Matrix<double, 4, 3> X = corners(mesh, t);
    const kerf::TetSide tet_side = e.tet_side[static_cast<std::size_t>(t)];
    // The points: three random ones inside (barycentric weights from sorted uniforms), then
    // the corners, with the side a corner is read on: its own unless the tet lies on the other.
    std::vector<Eigen::Vector3d> points;
    for (int p = 0; p < 3; ++p) {
      std::array<double, 5> cuts{0.0, unit(rng), unit(rng), unit(rng), 1.0};
      std::sort(cuts.begin() + 1, cuts.end() - 1);
      Eigen::Vector3d x = Eigen::Vector3d::Zero();
      for (int a = 0; a < 4; ++a) x += (cuts[static_cast<std::size_t>(a + 1)] - cuts[static_cast<std::size_t>(a)]) * X.row(a).transpose();
      points.push_back(x);
    }
    for (int c = 0; c < 4; ++c) points.push_back(X.row(c).transpose());
    for (std::size_t p = 0; p < points.size(); ++p) {
      const Eigen::Vector3d& x = points[p];
      const bool corner = p >= 3;
      const int c = corner ? static_cast<int>(p) - 3 : -1;
      // A corner is on the other side of a tet wholly above or below it only when it lies on
      // the cut (a tet below with a corner at Lambda = 0): that tet reads it as below.
      if (corner && ((tet_side == kerf::TetSide::above && node_sign(mesh.tets(t, c)) < 0) ||
                     (tet_side == kerf::TetSide::below && node_sign(mesh.tets(t, c)) > 0)))
        continue;
      const double distance = cut.signed_distance_to_plane(x);
      if (!corner && std::abs(distance) < 1e-12) continue; // on the cut the field is double-valued
      int H = distance >= 0.0 ? +1 : -1;
      if (corner) H = node_sign(mesh.tets(t, c)); // the node's own side, exactly (no round-off in the distance)
      const Eigen::Vector4d phi = barycentric(X, x);
      Eigen::Vector3d expected = Eigen::Vector3d::Zero();
      bool enriched_term = false;
      for (int i = 0; i < 4; ++i) {
        const int v = mesh.tets(t, i);
        expected += phi[i] * u.segment<3>(3 * v);
        if (const int a_node = enriched_dof_node(model, v); a_node >= 0) {
          const double psi = 0.5 * (H - node_sign(v));
          expected += phi[i] * psi * u.segment<3>(3 * a_node);
          enriched_term = enriched_term || psi != 0.0;
        }
      }
      enriched_points += enriched_term;
      const double error = (kerf::xfem_displacement(model, u, t, x) - expected).cwiseAbs().maxCoeff();
      if (!corner) {
        worst_field = std::max(worst_field, error);
        continue;
      }
      const int v = mesh.tets(t, c);
      // Eq. 42 at the node is u_v (the Kronecker property), and the library must agree.
      CHECK((expected - u.segment<3>(3 * v)).cwiseAbs().maxCoeff() <= 1e-14);
      const double node_error = (kerf::xfem_displacement(model, u, t, x) - u.segment<3>(3 * v)).cwiseAbs().maxCoeff();
      if (tet_side == kerf::TetSide::cut && e.level_set.lambda[v] == 0.0) {
        ++on_cut;
        if (kerf::side_of_point(model, t, x) != +1) ++on_cut_wrong_side;
        worst_on_cut = std::max(worst_on_cut, node_error);
      } else {
        worst_node = std::max(worst_node, std::max(node_error, error));
      }
      ++checked;
    }
  }
  // Values are sums of 8 terms Phi_i (u_i or Psi a_i) with |Phi| <= 1 recovered to ~1e-16 and
  // |u|, |a| <= 1: 1e-14 absolute. A wrong sign of Psi, a wrong side or a missed enriched DOF
  // errs by O(1).
  MESSAGE(std::string(what) << ": eq. 42 at " << 3 * mesh.num_tets() << " random points (" << enriched_points
               << " with an enriched term): max error " << worst_field << "; Kronecker property over " << checked
               << " (tet, corner) pairs: max error " << worst_node << "; " << on_cut << " corners on the cut in cut tets, "
               << on_cut_wrong_side << " of them read on the wrong side, max error " << worst_on_cut);
  CHECK(enriched_points > 0);
  CHECK(worst_field <= 1e-14);
  CHECK(worst_node <= 1e-14);
  CHECK(worst_on_cut <= 1e-14);
  CHECK(on_cut_wrong_side == 0);
  return on_cut;
}

kerf::TetMesh unit_cube(int cells) { return kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {cells, cells, cells}); }

} // namespace

TEST_CASE("xfem field: a traction-free constant strain on each side of an oblique cut is reproduced exactly") {
  const kerf::TetMesh mesh = unit_cube(3);
  // The discrete cut must be the plane itself: a snapped node would bend it, and then the
  // uniaxial stresses would no longer be traction-free on it. So we take the first of a few
  // heights at which no piece is below the minimum volume fraction.
  std::optional<kerf::RectangleCut> chosen;
  for (const double z : {0.5, 0.52, 0.55, 0.47, 0.58, 0.44}) {
    const kerf::RectangleCut candidate = plane_cut({0.5, 0.45, z}, {0.4, -0.3, 1.0});
    if (kerf::make_enrichment(mesh, candidate).snapped_nodes == 0) {
      chosen = candidate;
      MESSAGE("oblique patch cut through (0.5, 0.45, " << z << ")");
      break;
    }
  }
  REQUIRE(chosen.has_value());
  const kerf::RectangleCut cut = *chosen;
  const kerf::Enrichment e = kerf::make_enrichment(mesh, cut);
  REQUIRE(e.snapped_nodes == 0);
  CHECK(e.front_nodes == 0);
  CHECK(e.cut_tets > 0);
  check_patch(affine_patch(mesh, cut, e), "oblique cut");
}

TEST_CASE("xfem field: cuts through a single node and along an edge: no NaN, solvable, and exact for the patch") {
  const kerf::TetMesh mesh = unit_cube(4); // nodes every 0.25
  SUBCASE("through the node (0.5, 0.5, 0.5) only") {
    // n = (1, 0.3, 0.11): i + 0.3 j + 0.11 k = 0 has no integer solution but 0 for |j|, |k| <= 2.
    const kerf::RectangleCut cut = plane_cut({0.5, 0.5, 0.5}, {1.0, 0.3, 0.11});
    const kerf::Enrichment e = kerf::make_enrichment(mesh, cut);
    int zeros = 0;
    for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) zeros += e.level_set.lambda[v] == 0.0;
    CHECK(zeros == 1);
    CHECK(e.classification.count(kerf::TetCutCase::cut_through_vertex) > 0);
    CHECK(e.level_set.lambda.allFinite());
    REQUIRE(e.snapped_nodes == 0);
    check_patch(affine_patch(mesh, cut, e), "cut through a node");
    check_eq42_and_kronecker(kerf::XfemModel(mesh, material, e), cut, "cut through a node");
  }
  SUBCASE("along the diagonal edges (t, t, t)") {
    // n = (1, 0.3, -1.3) is perpendicular to (1, 1, 1): the plane holds the five nodes of the
    // cube's diagonal, along which every cell's Kuhn subdivision has an edge.
    const kerf::RectangleCut cut = plane_cut({0.5, 0.5, 0.5}, {1.0, 0.3, -1.3});
    const kerf::Enrichment e = kerf::make_enrichment(mesh, cut);
    int zeros = 0;
    for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) zeros += e.level_set.lambda[v] == 0.0;
    CHECK(zeros == 5);
    CHECK(e.classification.count(kerf::TetCutCase::cut_through_edge) > 0);
    CHECK(e.level_set.lambda.allFinite());
    REQUIRE(e.snapped_nodes == 0);
    check_patch(affine_patch(mesh, cut, e), "cut along an edge");
    check_eq42_and_kronecker(kerf::XfemModel(mesh, material, e), cut, "cut along an edge");
  }
}

TEST_CASE("xfem field: the field is eq. 42 written out independently, and keeps the Kronecker property u(x_i) = u_i") {
  const kerf::TetMesh mesh = beam({2, 3, 8});
  // An oblique full cut, and a half-depth one whose front runs through elements (front nodes,
  // tets beyond the front).
  const kerf::RectangleCut full_cut = plane_cut({0.015, 0.03, 0.1}, {0.3, 0.2, 1.0});
  const kerf::RectangleCut half_cut({0, 0, 0.11}, {0.02, 0, 0}, {0, 0.06, 0});
  const kerf::Enrichment full = kerf::make_enrichment(mesh, full_cut);
  const kerf::Enrichment half = kerf::make_enrichment(mesh, half_cut);
  CHECK(half.front_nodes > 0);
  check_eq42_and_kronecker(kerf::XfemModel(mesh, material, full), full_cut, "oblique full cut");
  check_eq42_and_kronecker(kerf::XfemModel(mesh, material, half), half_cut, "half-depth cut");
}
