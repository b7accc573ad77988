// Chapter 3's front sweep again: the tip deflection of the cut beam against
// the position x1 of the cut's front. Chapters 3 and 4 end the cut at the last row of enriched
// nodes, so the answer is a step function of x1 and jumps where the front crosses a node row;
// with branch functions the cut ends where it ends, and the answer moves continuously.
#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/node_region.hpp"
#include "kerf/mesh/point_locator.hpp"
#include "kerf/xfem/crack_tip_body.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace {

// The beam of chapters 1-4 under gravity along +x, clamped at z = 0, cut by [0, x1] x [0, 0.06]
// x {0.1003} (chapter 3's sweep plane, off every node layer), as a rectangle overhanging the
// beam on three sides so that its only edge inside is the front x = x1.
double tip_deflection(const kerf::TetMesh& mesh, double x1, kerf::TipTreatment treatment) {
  const kerf::LinearMaterial material{};
  // The study's sweep rules (examples/05_paulus_study.cpp): refined sub-tets on the front
  // tets, degree 3 graded once towards the front on the blending tets. Without the grading
  // (blending_depth 0) this test fails: the answer jumps by 1.6 % at the node row.
  const kerf::BranchRules rules{kerf::FrontRule::refined_subtets, 2, 3, 1};
  const kerf::CrackTipBody body(mesh, {kerf::rectangle_surface(kerf::RectangleCut({-0.01, -0.01, 0.1003}, {x1 + 0.01, 0, 0}, {0, 0.08, 0}))},
                                material, treatment, 0.0, rules);
  kerf::NodeRegion base;
  base.box_max = {0.03, 0.06, 0.0};
  const kerf::DofMap dofs = kerf::make_cut_xfem_dof_map(body.model(), {{kerf::nodes_in_region(mesh, base), {0, 0, 0}}});
  const Eigen::VectorXd f = body.model().gravity_load(material.density, {9.81, 0, 0});
  const Eigen::VectorXd u = kerf::solve_linear_cut_xfem(body.model(), dofs, f, kerf::SolverSettings{});
  const Eigen::Vector3d tip(0.03, 0.03, 0.2);
  const kerf::PointLocation where = kerf::PointLocator(mesh).locate(tip);
  REQUIRE(where.tet >= 0);
  return body.model().displacement_at(u, where.tet, tip)[0];
}

// The largest |u(x_{i+1}) - u(x_i)| / |u(x_i)| along a sweep.
double largest_relative_jump(const std::vector<double>& u) {
  double jump = 0.0;
  for (std::size_t i = 0; i + 1 < u.size(); ++i) jump = std::max(jump, std::abs(u[i + 1] - u[i]) / std::abs(u[i]));
  return jump;
}

} // namespace

TEST_CASE("with branch functions the tip deflection moves continuously as the front crosses a node row") {
  // Chapter 3's coarse sweep mesh, 3 x 4 x 11 cells: node rows at x = 0.01 and 0.02.
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {0.03, 0.06, 0.2}, {3, 4, 11});
  // 0.1 mm steps across the node row x = 0.01, never on it.
  const std::vector<double> x1{0.00985, 0.00995, 0.01005, 0.01015};
  std::vector<double> heaviside, geometric;
  for (double x : x1) {
    heaviside.push_back(tip_deflection(mesh, x, kerf::TipTreatment::heaviside_only));
    geometric.push_back(tip_deflection(mesh, x, kerf::TipTreatment::geometric));
  }
  for (std::size_t i = 0; i < x1.size(); ++i)
    MESSAGE("x1 = " << x1[i] << ": tip u_x Heaviside-only " << heaviside[i] << ", geometric branch " << geometric[i]);
  const double heaviside_jump = largest_relative_jump(heaviside), branch_jump = largest_relative_jump(geometric);
  MESSAGE("largest relative jump per 0.1 mm: Heaviside-only " << heaviside_jump << ", geometric branch " << branch_jump);
  REQUIRE(std::all_of(geometric.begin(), geometric.end(), [](double u) { return std::isfinite(u) && u > 0.0; }));
  // The bound: the true tip deflection is a smooth function of x1; chapter 3's conforming Tet10
  // sweep (figures/03_xfem_heaviside/front_sweep.csv, fitted meshes) changes by 1.5 % per mm
  // near x1 = 0.01, 0.15 % per 0.1 mm step. A continuous discrete answer may move by a few times
  // that (the set of branch nodes within the radius changes with x1): 1 % per step is allowed.
  // Measured: 0.24 % (Heaviside-only 3.2 %).
  CHECK(branch_jump < 1e-2);
  // And the test can fail: on the same sweep Heaviside-only jumps where the front crosses the
  // node row (the last enriched row moves by a whole element), by much more than the bound.
  CHECK(heaviside_jump > 2e-2);
  CHECK(heaviside_jump > 5.0 * branch_jump);
}
