// Chapter 3's reference mesh against CalculiX: the beam 0.03 x 0.06 x 0.2 m with a half-depth
// cut at z = 0.1, opened by split_mesh_along_cut (Schoch et al. section 6.1's "perfectly remeshed"
// cut), solved by Kerf and by ccx (C3D4 and C3D10) under gravity along x with the base clamped.
// The duplicated nodes are ordinary nodes to ccx, which knows nothing of the cut: agreement
// says the split mesh is an ordinary, valid FE mesh whose two sides are really disconnected.
//
// As in test_kerf_vs_calculix.cpp, to 1e-8 relative against CalculiX's own K and M solved in
// double precision (the matrix route of calculix_deck.hpp), and to ccx's printing precision
// (2e-6 of the largest displacement) against ccx's own static solve.
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/cut/split_mesh_along_cut.hpp"
#include "kerf/fem/assemble_loads.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/solve_linear_static.hpp"
#include "kerf/io/calculix_deck.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/node_region.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"

#include "support/calculix_path.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <string>

namespace {

double relative_max_difference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& reference) {
  return (a - reference).cwiseAbs().maxCoeff() / reference.cwiseAbs().maxCoeff();
}

} // namespace

TEST_CASE("A mesh split along a half-depth cut: Kerf agrees with CalculiX (C3D4, C3D10) under gravity") {
  const std::string ccx = support::ccx_path();
  const kerf::LinearMaterial material{300e3, 0.35, 1070};
  const Eigen::Vector3d gravity(9.81, 0, 0);
  // 2 x 4 x 8 cells: x step 0.015 (the front x = 0.015 is a node layer), z step 0.025 (the cut
  // plane z = 0.1 is one). The cut reaches from the face x = 0 to the front, across all of y.
  const kerf::TetMesh tet4 = kerf::make_box_mesh({0, 0, 0}, {0.03, 0.06, 0.2}, {2, 4, 8});
  const kerf::RectangleCut cut({0, 0, 0.1}, {0.015, 0, 0}, {0, 0.06, 0});

  for (int order : {1, 2}) {
    const std::string element = order == 1 ? "C3D4" : "C3D10";
    CAPTURE(element);
    const kerf::SplitMesh split = kerf::split_mesh_along_cut(order == 1 ? tet4 : kerf::tet10_from_tet4(tet4), cut, 1e-9);
    const kerf::TetMesh& mesh = split.mesh;
    // Tet4: x = 0 on the plane, 5 y values; Tet10: also the midpoints, 9 at x = 0 and 9 at
    // x = 0.0075 (5 on x-edges, 4 on the diagonals of the cells' faces in the plane).
    CHECK(split.duplicated_nodes == (order == 1 ? 5 : 18));

    kerf::NodeRegion base;
    base.box_max = {0.03, 0.06, 0};
    kerf::CalculixJob job;
    job.material = material;
    job.gravity = gravity;
    job.dirichlet = {{kerf::nodes_in_region(mesh, base), {0, 0, 0}}};

    const Eigen::VectorXd u_vector = kerf::solve_linear_static(mesh, material, kerf::make_dof_map(mesh.num_nodes(), job.dirichlet),
                                                               kerf::assemble_gravity(mesh, material.density, gravity), {});
    const Eigen::MatrixXd u_kerf = u_vector.reshaped(3, mesh.num_nodes()).transpose();
    const kerf::CalculixSolution s = kerf::solve_with_calculix(
        ccx, std::filesystem::path(KERF_BINARY_DIR) / "tests" / "calculix" / ("split_" + element), "split", mesh, job);

    // The cut is open in ccx's solution too: the two copies of a node move apart.
    const Eigen::Index original_nodes = mesh.num_nodes() - split.duplicated_nodes;
    double opening = 0.0;
    for (int k = 0; k < split.duplicated_nodes; ++k)
      opening = std::max(opening, (s.displacement.row(original_nodes + k) -
                                   s.displacement.row(split.duplicate_of[static_cast<std::size_t>(k)])).norm());
    const double max_u = s.displacement.cwiseAbs().maxCoeff();
    const double vs_matrices = relative_max_difference(u_kerf, s.displacement);
    const double vs_static = relative_max_difference(u_kerf, s.static_displacement);
    MESSAGE(element << ": " << split.duplicated_nodes << " duplicated nodes, max |u| = " << max_u << " m, opening " << opening
                    << " m; Kerf vs ccx matrices " << vs_matrices << ", vs ccx static " << vs_static);
    // A shared node would move as one; the opening is a fair fraction of max |u| (see
    // test_split_mesh_along_cut.cpp), far above the 1e-8 agreement asked for below.
    CHECK(opening > 1e-3 * max_u);
    // 1e-8: the matrix route is CalculiX's discrete solution to about cond(K_ff) 2e-16 (its K has
    // 14 digits; calculix_deck.hpp), Kerf's to round-off; a wrong connectivity at the cut would
    // change u in the first digits. 2e-6: ccx's .dat prints 7 significant digits.
    CHECK(vs_matrices < 1e-8);
    CHECK(vs_static < 2e-6);
  }
}
