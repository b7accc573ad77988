// A partial cut whose front is made of many short segments, through the scene path with the
// default "crack_tip" settings: a wavy sheet of 840 small triangles ends inside a box of 2592
// tets, so its front is 60 segments of 1 to 1.4 mm through tets of 10 mm, and the tets the sheet
// cuts split into dozens of cells. The collapsed rule of a fixed grading (12 halvings near every
// cell's faces) gave the 24 front tets 1.16 million points, 101 000 in the largest, and a tet of
// a box cut by a finer sheet 4.9 million: chapter 5's program died with std::bad_alloc. The rules
// now stop at an error estimate and a budget (front_quadrature.hpp). The test asserts the budget
// per front tet and per tet with branch functions, and that the cut opens behind its front and
// stays closed ahead of it.
#include "kerf/cut/crack_front.hpp"
#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/height_field_surface.hpp"
#include "kerf/cut/tet_pieces.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/mesh/point_locator.hpp"
#include "kerf/quadrature/front_quadrature.hpp"
#include "kerf/scene/cut_xfem_loads.hpp"
#include "kerf/scene/scene.hpp"
#include "kerf/scene/scene_crack_tip.hpp"
#include "kerf/scene/scene_cuts.hpp"
#include "kerf/scene/scene_mesh.hpp"
#include "kerf/scene/scene_quadrature.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

namespace {

// The box [0, 0.06]^2 x [0, 0.12] m in 6 x 6 x 12 cells of 10 mm, held at z = 0 and pulled up by
// 2 mm at z = 0.12; no "crack_tip" field: branch functions on the nodes within the default
// radius of the front.
constexpr const char* scene_text = R"({
  "name": "many_segment_front",
  "mesh": {"box": {"min": [0, 0, 0], "max": [0.06, 0.06, 0.12], "cells": [6, 6, 12]}, "order": 1},
  "material": {"young": 300e3, "poisson": 0.35, "density": 1070},
  "model": "linear",
  "dirichlet": [{"region": {"box": {"min": [0, 0, 0], "max": [0.06, 0.06, 0]}}},
                {"region": {"box": {"min": [0, 0, 0.12], "max": [0.06, 0.06, 0.12]}}, "displacement": [0, 0, 0.002]}]
})";

// The sheet z = 0.064 + 3 mm sin(2 pi x / 20 mm) over x in [-5, 65] mm (70 columns of 1 mm) and
// y in [-5, 33] mm (6 rows): it leaves the box through x = 0, x = 0.06 and y = 0, and ends inside
// it along y = 0.033, the middle of a layer of cells. Its front is the chain of the 60 edges
// (chords of the sine, 1 to 1.4 mm long) between x = 0 and x = 0.06.
constexpr double z0 = 0.064, amplitude = 0.003, wavelength = 0.02, y_front = 0.033;
double height(double x) { return amplitude * std::sin(2.0 * std::numbers::pi * x / wavelength); }
kerf::TriangleSurface wavy_sheet() {
  const auto h = [](double x, double) { return height(x); };
  return kerf::height_field_surface(h, z0, {-0.005, -0.005}, {0.065, y_front}, {70, 6});
}

} // namespace

TEST_CASE("a front of 60 short segments with the default crack_tip settings: bounded quadrature, and the cut opens behind it") {
  const kerf::Scene scene = kerf::parse_scene(scene_text, "many_segment_front.json", ".");
  const kerf::TetMesh mesh = kerf::make_scene_mesh(scene, nullptr);
  const kerf::CutSurfaces cuts({wavy_sheet()});
  const kerf::MeshPieces pieces = kerf::scene_mesh_pieces(scene, mesh, cuts, nullptr);
  const kerf::SceneCrackTip tip(scene, mesh, pieces, cuts, nullptr);
  REQUIRE(mesh.num_tets() == 2592);
  REQUIRE(tip.fronts().polylines.size() == 1);
  CHECK(tip.fronts().num_segments() == 60);
  const kerf::CrackTipFunctions* functions = tip.tip_functions();
  REQUIRE(functions != nullptr);

  // The collapsed rule of every tet the front crosses, as the model builds it (4 points per
  // direction on a Tet4, the default grading). The bound: the budget the grading may not pass,
  // 192 collapsed sub-tets of 64 points (measured: 12 288 in the largest), and 4096 more for a
  // piece whose unsplit sub-tets and Gauss cells alone exceed it (none here). The rule of a fixed
  // grading fails it in the first front tet (32 128 points).
  const kerf::BranchEnrichment& branch = *tip.branch_enrichment();
  std::size_t largest = 0, front_points = 0;
  int front_tets = 0;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    if (!branch.front_tet[static_cast<std::size_t>(t)] || pieces.entry[static_cast<std::size_t>(t)] < 0) continue;
    const Eigen::Matrix<double, 4, 3> X = kerf::tet_corners(mesh, t);
    const kerf::TetPieces& tet = pieces.tets[static_cast<std::size_t>(pieces.entry[static_cast<std::size_t>(t)])];
    std::size_t points = 0;
    for (int p = 0; p < tet.num_pieces(); ++p)
      points += kerf::front_collapsed_rule(X, tet, p, functions->fronts, 4, functions->front_grading).points.size();
    ++front_tets;
    front_points += points;
    largest = std::max(largest, points);
    REQUIRE(points <= 192 * 64 + 4096);
  }
  MESSAGE(front_tets << " front tets: " << front_points << " points, " << largest << " in the largest");
  CHECK(front_tets > 20);

  // The model: every point of every tet with branch functions (and of the pieces of the other
  // cut tets). The blending tets' rules are held to 1e-5 of V / h, so that the many small
  // sub-tets of a cut tet take few points each: at most 2000 points per tet with branch functions
  // on average (measured 835); the fixed rules put 1000 per tet into the front tets alone.
  const kerf::CutXfemModel model(mesh, scene.material, pieces, tip.sign_enrichment(), kerf::scene_piece_rule(scene, 1),
                                 functions);
  int branch_tets = 0;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) branch_tets += model.has_branch_functions(t) ? 1 : 0;
  MESSAGE(branch_tets << " tets with branch functions, " << model.num_piece_points() << " points on pieces");
  CHECK(model.num_piece_points() <= 2000 * branch_tets);

  const kerf::DofMap dofs = kerf::make_cut_xfem_dof_map(model, kerf::scene_held_nodes(scene, mesh, nullptr));
  const Eigen::VectorXd f = kerf::cut_xfem_scene_loads(scene, model, kerf::boundary_faces(mesh));
  const Eigen::VectorXd u = kerf::solve_linear_cut_xfem(model, dofs, f, scene.solver);
  REQUIRE(u.allFinite());

  // The opening [u] = u(p + d n) - u(p - d n), d = 1e-7 m, across the sheet at x = 30 mm, where a
  // vertex column makes the chords the sine itself (z = z0, slope -2 pi A / wavelength), behind
  // the front (y = 15 and 30 mm) and ahead of it (y = 40 mm, the plane z = z0 uncut).
  const kerf::PointLocator locator(mesh);
  const auto at = [&](const Eigen::Vector3d& x) {
    const kerf::PointLocation where = locator.locate(x);
    REQUIRE(where.tet >= 0);
    return model.displacement_at(u, where.tet, x);
  };
  const double x = 0.03, k = 2.0 * std::numbers::pi / wavelength, slope = k * amplitude * std::cos(k * x);
  const Eigen::Vector3d n = Eigen::Vector3d(-slope, 0.0, 1.0).normalized();
  const auto opening = [&](double y) {
    const Eigen::Vector3d p(x, y, z0 + height(x));
    return (at(p + 1e-7 * n) - at(p - 1e-7 * n)).norm();
  };
  const double behind = opening(0.015), near_front = opening(0.030), ahead = opening(0.040);
  MESSAGE("opening 18 mm and 3 mm behind the front " << behind << ", " << near_front << " m; 7 mm ahead " << ahead << " m");
  // The pull stretches the box by 2 mm; the cut, through half its depth, opens by a good part of
  // it behind the front: a tenth is asked for. Ahead of the front the field is continuous, and
  // what is left is 2 d |grad u| with |grad u| of a few percent (the stretch is 1.7 %): 1e-7 m
  // allows |grad u| up to 0.5.
  CHECK(behind > 2e-4);
  CHECK(near_front > 0.0);
  CHECK(near_front < behind);
  CHECK(ahead < 1e-7);
}
