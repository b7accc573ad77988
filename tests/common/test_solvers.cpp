// The four solvers give the same answer; a body held by nothing is reported, not solved.
#include "kerf/fem/assemble_loads.hpp"
#include "kerf/fem/rigid_motion_check.hpp"
#include "kerf/mesh/check_tet_mesh.hpp"
#include "kerf/fem/solve_linear_static.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/node_region.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"

#include <doctest/doctest.h>

TEST_CASE("CHOLMOD, SimplicialLDLT and both PCGs agree on the beam under gravity") {
  const kerf::TetMesh mesh = kerf::tet10_from_tet4(kerf::make_box_mesh({0, 0, 0}, {0.03, 0.06, 0.2}, {2, 3, 8}));
  const kerf::LinearMaterial material{300e3, 0.35, 1070};
  kerf::NodeRegion bottom;
  bottom.box_max = {0.03, 0.06, 0.0};
  const kerf::DofMap dofs = kerf::make_dof_map(mesh.num_nodes(), {{kerf::nodes_in_region(mesh, bottom), {0, 0, 0}}});
  const Eigen::VectorXd f = kerf::assemble_gravity(mesh, material.density, {9.81, 0, 0});
  const Eigen::VectorXd reference = kerf::solve_linear_static(mesh, material, dofs, f, {"cholmod"});
  CHECK(reference.norm() > 0.0);
  // Direct solvers: round-off times cond(K) ~ 1e6; CG stops at 1e-12 relative residual, so its
  // error is below cond(K) 1e-12 ~ 1e-6 relative.
  CHECK((kerf::solve_linear_static(mesh, material, dofs, f, {"ldlt"}) - reference).norm() < 1e-9 * reference.norm());
  for (const char* cg : {"cg-jacobi", "cg-ichol"}) {
    const Eigen::VectorXd u = kerf::solve_linear_static(mesh, material, dofs, f, {cg, 1e-12, 100000});
    CHECK((u - reference).norm() < 1e-5 * reference.norm());
  }
}

TEST_CASE("a body with no Dirichlet condition is reported as singular") {
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {2, 2, 2});
  const kerf::DofMap dofs = kerf::make_dof_map(mesh.num_nodes(), {});
  const Eigen::VectorXd f = kerf::assemble_gravity(mesh, 1.0, {0, 0, -1});
  for (const char* type : {"cholmod", "ldlt"}) CHECK_THROWS_AS(kerf::solve_linear_static(mesh, {}, dofs, f, {type}), std::runtime_error);
  CHECK_THROWS_AS(kerf::make_linear_solver({"umfpack"}), std::invalid_argument);
}

TEST_CASE("free rigid motions are counted exactly") {
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {2, 2, 2});
  const auto count = [&](const std::vector<kerf::DirichletNodes>& conditions) {
    return kerf::count_free_rigid_motions(mesh, kerf::make_dof_map(mesh.num_nodes(), conditions));
  };
  CHECK(count({}) == 6);
  CHECK(count({{{0}, {0, 0, 0}}}) == 3);          // one fixed node: the body turns about it
  CHECK(count({{{0, 2}, {0, 0, 0}}}) == 1);       // two: it turns about the line through them
  CHECK(count({{{0, 2, 6}, {0, 0, 0}}}) == 0);    // three non-collinear: held
  kerf::NodeRegion bottom;
  bottom.box_max = {1, 1, 0};
  CHECK(count({{kerf::nodes_in_region(mesh, bottom), {0, 0, 0}}}) == 0);

  // Two disjoint cubes, only one of them fixed: the other keeps its six motions.
  kerf::TetMesh two = mesh;
  const kerf::TetMesh shifted = kerf::make_box_mesh({2, 0, 0}, {3, 1, 1}, {2, 2, 2});
  two.nodes.conservativeResize(mesh.num_nodes() + shifted.num_nodes(), 3);
  two.nodes.bottomRows(shifted.num_nodes()) = shifted.nodes;
  two.tets.conservativeResize(mesh.num_tets() + shifted.num_tets(), 4);
  two.tets.bottomRows(shifted.num_tets()) = shifted.tets.array() + static_cast<int>(mesh.num_nodes());
  CHECK(kerf::count_free_rigid_motions(two, kerf::make_dof_map(two.num_nodes(), {{kerf::nodes_in_region(mesh, bottom), {0, 0, 0}}})) == 6);
}

TEST_CASE("a node in no tet is a free motion until it is held") {
  kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {1, 1, 1});
  mesh.nodes.conservativeResize(mesh.num_nodes() + 1, 3);
  mesh.nodes.bottomRows<1>() << 5, 5, 5;
  kerf::NodeRegion bottom;
  bottom.box_max = {1, 1, 0};
  const std::vector<int> stray = kerf::nodes_without_tets(mesh);
  CHECK(stray == std::vector<int>{8});
  CHECK(kerf::count_free_rigid_motions(mesh, kerf::make_dof_map(mesh.num_nodes(), {{kerf::nodes_in_region(mesh, bottom), {0, 0, 0}}})) == 3);
  CHECK(kerf::count_free_rigid_motions(
            mesh, kerf::make_dof_map(mesh.num_nodes(), {{kerf::nodes_in_region(mesh, bottom), {0, 0, 0}}, {stray, {0, 0, 0}}})) == 0);
}
