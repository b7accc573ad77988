// The scene's loads on [u; a] (xfem_scene_loads): gravity row by row against the piece
// integrals in closed form (no clipping, see side_moment in xfem_test_support.hpp), the work of gravity and of a traction in a
// translation of the piece above alone (closed-form volume and area above an oblique plane),
// and a traction on a face the cut runs into, solved against the split-mesh FEM.
#include "xfem_test_support.hpp"

#include "kerf/cut/split_mesh_along_cut.hpp"
#include "kerf/fem/solve_linear_static.hpp"
#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/scene/scene.hpp"
#include "kerf/scene/scene_mesh.hpp"
#include "kerf/scene/xfem_loads.hpp"
#include "kerf/xfem/xfem_field.hpp"
#include "kerf/xfem/xfem_model.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>

using namespace xfem_test;

namespace {

constexpr double beam_volume = 0.03 * 0.06 * 0.2;

kerf::Scene scene_from(const std::string& fields) {
  return kerf::parse_scene(R"({"mesh": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0.2], "cells": [2, 3, 8]}, "order": 1},
    "material": {"young": 300e3, "poisson": 0.35, "density": 1070},
    "dirichlet": [{"region": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0]}}}])" +
                               fields + "}",
                           "loads.json", ".");
}

// The vector that translates the piece above by t and leaves the piece below at rest (see
// test_xfem_mass.cpp): its dot product with a load vector is the work of the loads on the piece above.
Eigen::VectorXd above_translation(const kerf::XfemModel& model, const Eigen::Vector3d& t) {
  Eigen::VectorXd v = Eigen::VectorXd::Zero(3 * model.num_dof_nodes());
  for (Eigen::Index i = 0; i < model.mesh().num_nodes(); ++i) {
    if (model.enrichment().node_sign[static_cast<std::size_t>(i)] > 0) v.segment<3>(3 * i) = t;
    if (const int a_node = enriched_dof_node(model, static_cast<int>(i)); a_node >= 0) v.segment<3>(3 * a_node) = t;
  }
  return v;
}

} // namespace

TEST_CASE("xfem loads: gravity and a traction on an obliquely cut beam") {
  // Plane through the mid-section's centroid with normal (0.3, 0.2, 1): V_above = V / 2, and on
  // the face x = 0 it runs along z = 0.1045 - 0.2 (y - 0.03), leaving the area
  // 0.06 (0.2 - 0.1045) = 0.00573 m^2 of the face's 0.012 m^2 above it.
  const kerf::Scene scene = scene_from(R"(, "gravity": [9.81, 0, -9.81],
    "traction": [{"region": {"box": {"min": [0, 0, 0], "max": [0, 0.06, 0.2]}}, "total_force": [0.5, 0.2, -0.3]}])");
  const kerf::Scene gravity_only = scene_from(R"(, "gravity": [9.81, 0, -9.81])");
  const kerf::TetMesh mesh = kerf::make_scene_mesh(scene, nullptr);
  const kerf::BoundaryFaces boundary = kerf::boundary_faces(mesh);
  const kerf::Enrichment e = kerf::make_enrichment(mesh, plane_cut({0.015, 0.03, 0.1}, {0.3, 0.2, 1.0}));
  REQUIRE(e.snapped_nodes == 0);
  const kerf::XfemModel model(mesh, scene.material, e);
  const Eigen::Vector3d body_force = scene.material.density * scene.gravity;

  // Gravity, row by row, against closed forms that use no clipping: the u row of node i is
  // rho g int Phi_i over its support (V / 4 per tet), its a row rho g sum_t sum_s Psi_s,i
  // int_{T_s} Phi_i dV, with the piece integrals from the Dirichlet-moment formula
  // (side_shape_integral) and Psi_s,i = (s - H_i) / 2 from the sign of the plane's distance.
  const Eigen::Vector3d plane_point(0.015, 0.03, 0.1), plane_normal(0.3, 0.2, 1.0);
  const Eigen::VectorXd f_gravity = kerf::xfem_scene_loads(gravity_only, model, boundary);
  Eigen::VectorXd expected = Eigen::VectorXd::Zero(f_gravity.size());
  double worst_piece = 0.0;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    Eigen::Vector4d lambda;
    for (int a = 0; a < 4; ++a) {
      lambda[a] = plane_value(plane_point, plane_normal, node(mesh, mesh.tets(t, a)));
      REQUIRE(lambda[a] != 0.0);
    }
    const Eigen::Matrix<double, 4, 3> X = corners(mesh, t);
    const double V = std::abs(kerf::signed_tet_volume(X));
    for (int a = 0; a < 4; ++a) {
      const int v = mesh.tets(t, a);
      const int H = lambda[a] > 0 ? +1 : -1;
      expected.segment<3>(3 * v) += V / 4.0 * body_force;
      for (const int side : {+1, -1}) {
        const double piece = side_shape_integral(lambda, V, a, side);
        worst_piece = std::max(worst_piece, std::abs(piece - kerf::piece_shape_integrals(model, t, side)[a]) / V);
        if (const int a_node = enriched_dof_node(model, v); a_node >= 0) expected.segment<3>(3 * a_node) += psi_of(side, H) * piece * body_force;
      }
    }
  }
  // Sums of at most 24 products per row, each ~1e-15 relative (the divided differences of a cut
  // tet cost up to ~1e3 more): 1e-11 of the largest entry. The enriched rows are ~1/20 of the
  // largest; an error in a piece integral (e.g. a sub-tet's centroid misplaced) shows at O(1e-2).
  const double gravity_difference = (f_gravity - expected).cwiseAbs().maxCoeff() / expected.cwiseAbs().maxCoeff();
  CHECK(gravity_difference <= 1e-11);
  CHECK(worst_piece <= 1e-12);

  // Work in a translation of the piece above: rho g V / 2 for gravity, F * 0.00573 / 0.012 for
  // the traction. Sums of positive pieces: 1e-12 relative.
  const Eigen::VectorXd f_all = kerf::xfem_scene_loads(scene, model, boundary);
  const Eigen::VectorXd f_traction = f_all - f_gravity;
  const Eigen::Vector3d F(0.5, 0.2, -0.3);
  const double area_fraction = 0.06 * (0.2 - 0.1045) / 0.012;
  for (int d = 0; d < 3; ++d) {
    const Eigen::VectorXd v = above_translation(model, Eigen::Vector3d::Unit(d));
    CHECK(std::abs(v.dot(f_gravity) - 0.5 * beam_volume * body_force[d]) <= 1e-12 * beam_volume * body_force.norm());
    CHECK(std::abs(v.dot(f_traction) - area_fraction * F[d]) <= 1e-12 * F.norm());
  }
  MESSAGE("gravity rows vs closed form: " << gravity_difference << " of the largest entry, piece integrals " << worst_piece
                                            << " of V; traction work above "
                                                      << above_translation(model, Eigen::Vector3d::UnitX()).dot(f_traction)
                                                      << " N (expected " << area_fraction * F[0] << ")");
}

TEST_CASE("xfem loads: a traction on the face the cut runs into, solved against the split mesh") {
  // Half-depth cut along the node layer z = 0.1 from the face x = 0; the face x = 0 (cut in two
  // by the cut's edge) carries a traction, the beam hangs in gravity from z = 0.
  const kerf::Scene scene = scene_from(R"(, "gravity": [0, 9.81, 0],
    "traction": [{"region": {"box": {"min": [0, 0, 0], "max": [0, 0.06, 0.2]}}, "total_force": [0.4, 0.1, 0.3]}])");
  const kerf::TetMesh mesh = kerf::make_scene_mesh(scene, nullptr);
  const kerf::RectangleCut cut({0, 0, 0.1}, {0.015, 0, 0}, {0, 0.06, 0});
  const kerf::Enrichment e = kerf::make_enrichment(mesh, cut);
  const kerf::XfemModel model(mesh, scene.material, e);
  const Eigen::VectorXd u = kerf::solve_linear_xfem(model, kerf::make_xfem_dof_map(model, kerf::scene_dirichlet_nodes(scene, mesh)),
                                                    kerf::xfem_scene_loads(scene, model, kerf::boundary_faces(mesh)), scene.solver);
  REQUIRE(u.allFinite());

  const kerf::SplitMesh split = kerf::split_mesh_along_cut(mesh, cut, 1e-9);
  const Eigen::VectorXd u_split =
      kerf::solve_linear_static(split.mesh, scene.material, kerf::scene_dof_map(scene, split.mesh, nullptr),
                                kerf::scene_external_loads(scene, split.mesh, kerf::boundary_faces(split.mesh)), scene.solver);
  double worst = 0.0;
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v)
    worst = std::max(worst, (u.segment<3>(3 * v) - u_split.segment<3>(3 * v)).cwiseAbs().maxCoeff());
  for (std::size_t k = 0; k < split.duplicate_of.size(); ++k)
    worst = std::max(worst, (node_side_value(model, u, split.duplicate_of[k], -1) -
                             u_split.segment<3>(3 * (mesh.num_nodes() + static_cast<Eigen::Index>(k))))
                                .cwiseAbs()
                                .maxCoeff());
  const double scale = u_split.cwiseAbs().maxCoeff();
  // Same system in other variables (see test_xfem_reference_solutions.cpp): round-off only.
  MESSAGE("traction on the cut face: XFEM vs split mesh max difference " << worst << " m of " << scale << " m");
  CHECK(worst <= 1e-10 * scale);

  // Points outside the mesh get NaN and are counted; points inside do not.
  Eigen::MatrixXd points(3, 3);
  points << 0.01, 0.03, 0.05, 0.5, 0.5, 0.5, 0.0, 0.03, 0.1001;
  Eigen::Index outside = 0;
  const Eigen::MatrixXd values = kerf::xfem_displacement_at(model, u, points, outside);
  CHECK(outside == 1);
  CHECK(values.row(0).allFinite());
  CHECK(std::isnan(values(1, 0)));
  CHECK(values.row(2).allFinite());
}
