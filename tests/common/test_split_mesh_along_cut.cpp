// The pre-cut reference mesh of chapter 3 (Schoch et al. section 6.1): a box whose node layer
// z = 0.1 follows a rectangular cut, opened by duplicating the nodes on the cut. Counts of
// duplicated nodes (the front stays single), two components for a cut through the whole
// section, a static solve in which the cut opens, and the rejection of a mesh that does not
// conform to the cut.
#include "kerf/cut/clip_tet.hpp"
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/cut/split_mesh_along_cut.hpp"
#include "kerf/fem/assemble_loads.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/solve_linear_static.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/node_region.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

// The box's nodes are at i / n times the side lengths, exact to a few ulps (1e-17 m); the
// closest nodes off the plane z = 0.1 or off the front x = 0.015 are 0.0075 m away (Tet10 on
// the 2 x 2 x 4 box). Any tolerance in between gives the same answer; 1e-9 m sits in the middle.
constexpr double tol = 1e-9;
constexpr double box_volume = 0.03 * 0.06 * 0.2; // m^3

kerf::TetMesh box(const Eigen::Vector3i& cells, int order) {
  const kerf::TetMesh tet4 = kerf::make_box_mesh({0, 0, 0}, {0.03, 0.06, 0.2}, cells);
  return order == 1 ? tet4 : kerf::tet10_from_tet4(tet4);
}

// A cut from the face x = 0 to x = 0.015 (half the depth), over the whole width y in [0, 0.06],
// in the plane z = 0.1. normal = edge1 x edge2 = (0, 0, 0.0009) / |.|: "above" is z > 0.1. Its
// front is the edge x = 0.015; its other three edges lie on the body's surface.
kerf::RectangleCut half_depth_cut() { return kerf::RectangleCut({0, 0, 0.1}, {0.015, 0, 0}, {0, 0.06, 0}); }

// A rectangle larger than the cross-section: it cuts the box in two.
kerf::RectangleCut full_depth_cut() { return kerf::RectangleCut({-0.01, -0.01, 0.1}, {0.05, 0, 0}, {0, 0.08, 0}); }

bool on_cut_plane(const kerf::TetMesh& mesh, Eigen::Index v) { return std::abs(mesh.nodes(v, 2) - 0.1) <= tol; }

Eigen::Matrix<double, 4, 3> corners(const kerf::TetMesh& mesh, Eigen::Index t) {
  Eigen::Matrix<double, 4, 3> X;
  for (int c = 0; c < 4; ++c) X.row(c) = mesh.nodes.row(mesh.tets(t, c));
  return X;
}

double centroid_z(const kerf::TetMesh& mesh, Eigen::Index t) { return corners(mesh, t).col(2).mean(); }

// Union-find over nodes: two tets are connected when they share a node.
struct Components {
  std::vector<int> tet_component; // 0..count-1 for each tet
  int count = 0;
};

Components tet_components(const kerf::TetMesh& mesh) {
  std::vector<int> parent(static_cast<std::size_t>(mesh.num_nodes()));
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int v) {
    while (parent[static_cast<std::size_t>(v)] != v) v = parent[static_cast<std::size_t>(v)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(v)])];
    return v;
  };
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    for (int a = 1; a < mesh.nodes_per_tet(); ++a) parent[static_cast<std::size_t>(find(mesh.tets(t, a)))] = find(mesh.tets(t, 0));
  Components result;
  std::map<int, int> label;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const auto [it, inserted] = label.try_emplace(find(mesh.tets(t, 0)), result.count);
    if (inserted) ++result.count;
    result.tet_component.push_back(it->second);
  }
  return result;
}

// The invariants of any split: nodes appended as copies, tets reordered nowhere, the tets below
// using only the duplicates and the tets above only the originals of the split nodes.
void check_split_structure(const kerf::TetMesh& mesh, const kerf::SplitMesh& split) {
  const Eigen::Index V = mesh.num_nodes();
  REQUIRE(split.duplicated_nodes == static_cast<int>(split.duplicate_of.size()));
  REQUIRE(split.mesh.num_nodes() == V + split.duplicated_nodes);
  REQUIRE(split.mesh.num_tets() == mesh.num_tets());
  REQUIRE(split.mesh.nodes_per_tet() == mesh.nodes_per_tet());
  CHECK(split.mesh.nodes.topRows(V) == mesh.nodes);
  std::vector<int> is_split(static_cast<std::size_t>(V), 0);
  for (int k = 0; k < split.duplicated_nodes; ++k) {
    const int original = split.duplicate_of[static_cast<std::size_t>(k)];
    CHECK(split.mesh.nodes.row(V + k) == mesh.nodes.row(original));
    CHECK(on_cut_plane(mesh, original));
    is_split[static_cast<std::size_t>(original)] = 1;
  }
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    // Same nodes at the same places in the same order: the same orientation and volume.
    CHECK(kerf::signed_tet_volume(corners(split.mesh, t)) == kerf::signed_tet_volume(corners(mesh, t)));
    const bool below = centroid_z(mesh, t) < 0.1;
    for (int a = 0; a < mesh.nodes_per_tet(); ++a) {
      const int original = mesh.tets(t, a), used = split.mesh.tets(t, a);
      if (!is_split[static_cast<std::size_t>(original)]) {
        CHECK(used == original);
      } else if (below) {
        REQUIRE(used >= V);
        CHECK(split.duplicate_of[static_cast<std::size_t>(used - V)] == original);
      } else {
        CHECK(used == original);
      }
    }
  }
}

} // namespace

TEST_CASE("split_mesh_along_cut: a half-depth cut duplicates the nodes on it, not those on its front") {
  for (int order : {1, 2})
    for (const Eigen::Vector3i& cells : {Eigen::Vector3i(2, 2, 4), Eigen::Vector3i(4, 4, 20)}) {
      CAPTURE(order);
      CAPTURE(cells.transpose());
      const kerf::TetMesh mesh = box(cells, order);
      const kerf::SplitMesh split = kerf::split_mesh_along_cut(mesh, half_depth_cut(), tol);
      check_split_structure(mesh, split);

      // Expected: the nodes of the layer z = 0.1 strictly before the front x = 0.015 (every y:
      // the cut's edges y = 0, y = 0.06 and x = 0 lie on the body's surface).
      int expected = 0;
      for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v)
        if (on_cut_plane(mesh, v) && mesh.nodes(v, 0) < 0.015 - tol) ++expected;
      MESSAGE("order " << order << ", cells " << cells.transpose() << ": " << split.duplicated_nodes
                       << " duplicated nodes (expected " << expected << ") of " << mesh.num_nodes());
      CHECK(split.duplicated_nodes == expected);
      if (order == 1) // by hand: x in {0} (3 y values), or x in {0, 0.0075} (2 x 5)
        CHECK(split.duplicated_nodes == (cells[0] == 2 ? 3 : 10));
      for (int original : split.duplicate_of) CHECK(mesh.nodes(original, 0) < 0.015 - tol);

      // The material beyond the front is whole: one piece.
      CHECK(tet_components(split.mesh).count == 1);
    }
}

TEST_CASE("split_mesh_along_cut: a cut through the whole section leaves two pieces that add up to the box") {
  for (int order : {1, 2}) {
    CAPTURE(order);
    const kerf::TetMesh mesh = box({2, 3, 4}, order);
    CHECK(tet_components(mesh).count == 1); // the check below can tell one piece from two
    const kerf::SplitMesh split = kerf::split_mesh_along_cut(mesh, full_depth_cut(), tol);
    check_split_structure(mesh, split);
    int on_plane = 0;
    for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) on_plane += on_cut_plane(mesh, v) ? 1 : 0;
    CHECK(split.duplicated_nodes == on_plane); // all of the layer: the cut has no front

    const Components components = tet_components(split.mesh);
    REQUIRE(components.count == 2);
    double volume[2] = {0.0, 0.0};
    int side_component[2] = {-1, -1}; // the component of the tets below (0) and above (1)
    for (Eigen::Index t = 0; t < split.mesh.num_tets(); ++t) {
      const int c = components.tet_component[static_cast<std::size_t>(t)];
      volume[c] += kerf::signed_tet_volume(corners(split.mesh, t));
      // Each piece is one side of the cut.
      int& side = side_component[centroid_z(mesh, t) < 0.1 ? 0 : 1];
      if (side < 0) side = c;
      CHECK(c == side);
    }
    CHECK(side_component[0] != side_component[1]);
    // Sums of a few hundred tet volumes: round-off is ~1e-15 relative, 1e-12 leaves a margin
    // and still catches a single missing tet (1/144 of the box).
    CHECK(volume[0] + volume[1] == kerf_test::relative(box_volume, 1e-12));
    CHECK(volume[0] == kerf_test::relative(box_volume / 2, 1e-12));
    CHECK(volume[1] == kerf_test::relative(box_volume / 2, 1e-12));
  }
}

TEST_CASE("split_mesh_along_cut: under gravity the cut opens, and the front holds the two sides together") {
  const kerf::LinearMaterial material{300e3, 0.35, 1070};
  const Eigen::Vector3d gravity(9.81, 0, 0);
  for (int order : {1, 2}) {
    CAPTURE(order);
    const kerf::TetMesh mesh = box(order == 1 ? Eigen::Vector3i(4, 4, 20) : Eigen::Vector3i(2, 2, 4), order);
    const kerf::SplitMesh split = kerf::split_mesh_along_cut(mesh, half_depth_cut(), tol);
    REQUIRE(split.duplicated_nodes > 0);

    const auto solve = [&](const kerf::TetMesh& m) {
      kerf::NodeRegion base;
      base.box_max = {0.03, 0.06, 0};
      const kerf::DofMap dofs = kerf::make_dof_map(m.num_nodes(), {{kerf::nodes_in_region(m, base), {0, 0, 0}}});
      const Eigen::VectorXd u = kerf::solve_linear_static(m, material, dofs, kerf::assemble_gravity(m, material.density, gravity), {});
      return Eigen::MatrixXd(u.reshaped(3, m.num_nodes()).transpose());
    };
    const Eigen::MatrixXd u = solve(split.mesh);
    const Eigen::MatrixXd u_whole = solve(mesh);
    const Eigen::Index V = mesh.num_nodes();

    double opening = 0.0;
    for (int k = 0; k < split.duplicated_nodes; ++k)
      opening = std::max(opening, (u.row(V + k) - u.row(split.duplicate_of[static_cast<std::size_t>(k)])).norm());
    const double max_u = u.cwiseAbs().maxCoeff();
    MESSAGE("order " << order << ": max |u| = " << max_u << " m (uncut " << u_whole.cwiseAbs().maxCoeff()
                     << " m), largest opening of the cut " << opening << " m");
    // A shared node would give exactly 0. The opening is a lever effect of the whole beam
    // bending about the front, so it is a fair fraction of max |u|; 1e-3 of it rules out
    // round-off (1e-12 relative) by nine orders of magnitude.
    CHECK(opening > 1e-9);
    CHECK(opening > 1e-3 * max_u);
    // Cutting half the section away makes the beam softer.
    CHECK(max_u > u_whole.cwiseAbs().maxCoeff());

    // The front x = 0.015 is single: its nodes are not duplicated and both sides use them.
    int front_nodes = 0;
    for (Eigen::Index v = 0; v < V; ++v) {
      if (!on_cut_plane(mesh, v) || std::abs(mesh.nodes(v, 0) - 0.015) > tol) continue;
      ++front_nodes;
      CHECK(std::find(split.duplicate_of.begin(), split.duplicate_of.end(), static_cast<int>(v)) == split.duplicate_of.end());
      bool used_above = false, used_below = false;
      for (Eigen::Index t = 0; t < split.mesh.num_tets(); ++t)
        for (int a = 0; a < split.mesh.nodes_per_tet(); ++a)
          if (split.mesh.tets(t, a) == v) (centroid_z(split.mesh, t) < 0.1 ? used_below : used_above) = true;
      CHECK(used_above);
      CHECK(used_below);
    }
    CHECK(front_nodes == 5); // y = 0, 0.015, ..., 0.06: 4 cells (Tet4), or 2 cells and their midpoints (Tet10)
  }
}

TEST_CASE("split_mesh_along_cut: a mesh without a node layer on the cut is rejected") {
  for (int order : {1, 2}) {
    CAPTURE(order);
    const kerf::TetMesh mesh = box({1, 1, 3}, order); // layers z = 0, 0.0667, 0.1333, 0.2
    try {
      (void)kerf::split_mesh_along_cut(mesh, half_depth_cut(), tol);
      FAIL("a mesh whose tets straddle the cut was accepted");
    } catch (const std::invalid_argument& e) {
      const std::string message = e.what();
      MESSAGE(message);
      CHECK(message.find("tet ") != std::string::npos);
      CHECK(message.find("does not conform") != std::string::npos);
    }
    // The same plane with its rectangle beside the body: tets straddle the plane but not the
    // rectangle, so the mesh conforms to that cut and nothing is split.
    const kerf::RectangleCut beside({0.05, 0, 0.1}, {0.015, 0, 0}, {0, 0.06, 0});
    const kerf::SplitMesh split = kerf::split_mesh_along_cut(mesh, beside, tol);
    CHECK(split.duplicated_nodes == 0);
    CHECK(split.mesh.tets == mesh.tets);
  }
}

TEST_CASE("split_mesh_along_cut: tets straddling the plane beyond the front are allowed, and hold the front") {
  // A node layer that follows the cut only up to its front: the box's layer z = 0.0667 moved
  // up to z = 0.1 for x <= 0.015, so beyond the front x = 0.015 the tets straddle the plane.
  for (int order : {1, 2}) {
    CAPTURE(order);
    kerf::TetMesh tet4 = box({2, 2, 3}, 1); // z layers 0, 0.0667, 0.1333, 0.2; x layers 0, 0.015, 0.03
    for (Eigen::Index v = 0; v < tet4.num_nodes(); ++v)
      if (std::abs(tet4.nodes(v, 2) - 0.2 / 3) < tol && tet4.nodes(v, 0) < 0.015 + tol) tet4.nodes(v, 2) = 0.1;
    const kerf::TetMesh mesh = order == 1 ? tet4 : kerf::tet10_from_tet4(tet4);
    const kerf::SplitMesh split = kerf::split_mesh_along_cut(mesh, half_depth_cut(), tol);
    check_split_structure(mesh, split);
    // On the plane: the corners at x = 0 (3 y values) and, for Tet10, the midpoints at x = 0
    // (2) and x = 0.0075 (3 on x-edges, 2 on diagonals of the faces z = 0.1) are split; the
    // front x = 0.015 is not, though every plane face it touches lies in the rectangle: the
    // straddling tets beyond it put it on the front.
    int expected = 0;
    for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v)
      if (on_cut_plane(mesh, v) && mesh.nodes(v, 0) < 0.015 - tol) ++expected;
    MESSAGE("order " << order << ", layer up to the front only: " << split.duplicated_nodes << " duplicated nodes (expected "
                     << expected << ")");
    CHECK(split.duplicated_nodes == expected);
    CHECK(split.duplicated_nodes == (order == 1 ? 3 : 10));
    CHECK(tet_components(split.mesh).count == 1);
  }
}
