// The quasi-static solver of chapter 2 (load steps of Newton iterations on the corotated
// forces) where its answer is known:
//  - tiny loads: the corotational solution is chapter 1's linear one, up to terms of second
//    order in the rotation;
//  - both end faces of the beam turned rigidly by 90 degrees: the whole beam must turn rigidly,
//    with zero strain energy, whatever the tangent; Newton with the consistent tangent gets
//    there in fewer iterations, and quadratically;
// and the scene-file fields that ask for all this.
#include "kerf/app/input_error.hpp"
#include "kerf/corotation/corotational_model.hpp"
#include "kerf/corotation/quasi_static_solver.hpp"
#include "kerf/fem/assemble_loads.hpp"
#include "kerf/fem/solve_linear_static.hpp"
#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/node_region.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"
#include "kerf/scene/scene.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace {

constexpr double pi = 3.14159265358979323846;
constexpr double beam_length = 0.2;

kerf::TetMesh beam_mesh(int order) {
  const kerf::TetMesh tet4 = kerf::make_box_mesh({0, 0, 0}, {0.03, 0.06, beam_length}, {2, 3, 8});
  return order == 1 ? tet4 : kerf::tet10_from_tet4(tet4);
}

// The nodes of the end face z = z_face.
kerf::NodeRegion end_face(double z_face) {
  kerf::NodeRegion face;
  face.box_min = {0, 0, z_face};
  face.box_max = {0.03, 0.06, z_face};
  return face;
}

// Each node of `nodes` held at the displacement (Q - I)(X - c) of the rigid rotation Q about c.
void add_rotated_nodes(const kerf::TetMesh& mesh, const std::vector<int>& nodes, const Eigen::Matrix3d& Q, const Eigen::Vector3d& c,
                       std::vector<kerf::DirichletNodes>& conditions) {
  for (int v : nodes) {
    const Eigen::Vector3d X = mesh.nodes.row(v).transpose();
    conditions.push_back({{v}, (Q - Eigen::Matrix3d::Identity()) * (X - c)});
  }
}

// The largest nodal displacement |u_v| (3#V vector).
double max_nodal_norm(const Eigen::VectorXd& u) { return u.reshaped(3, u.size() / 3).colwise().norm().maxCoeff(); }

} // namespace

TEST_CASE("under tiny loads the corotational solution is chapter 1's linear solution") {
  const kerf::LinearMaterial material{300e3, 0.35, 1070};
  for (const int order : {1, 2}) {
    CAPTURE(order);
    const kerf::TetMesh mesh = beam_mesh(order);
    const kerf::DofMap dofs = kerf::make_dof_map(mesh.num_nodes(), {{kerf::nodes_in_region(mesh, end_face(0.0)), {0, 0, 0}}});
    // A transverse tip traction of 1 N, scaled below so that the largest displacement is |u|.
    Eigen::VectorXd unit_load = Eigen::VectorXd::Zero(3 * mesh.num_nodes());
    kerf::add_uniform_traction(mesh, kerf::boundary_faces(mesh), kerf::node_mask(mesh, end_face(beam_length)), {1.0, 0.5, 0.0}, unit_load);
    const Eigen::VectorXd u_unit = kerf::solve_linear_static(mesh, material, dofs, unit_load, kerf::SolverSettings{});
    const kerf::CorotationalModel model(mesh, material);

    // Corotation changes the response only through the rotation, which is ~|u| / L: the
    // difference u_corotational - u_linear is of second order (~|u|^2 / L, e.g. the tip's
    // shortening), so relative to |u| it is ~|u| / L. We measure it at two sizes.
    std::vector<double> relative_differences;
    for (const double max_displacement : {1e-6, 1e-7}) {
      const double scale = max_displacement / max_nodal_norm(u_unit);
      const Eigen::VectorXd u_linear = scale * u_unit;
      kerf::QuasiStaticSettings settings;
      settings.load_steps = 1;
      settings.max_iterations = 6; // Newton needs 2 here: the first iterate is u_linear itself
      const kerf::QuasiStaticResult result = kerf::solve_quasi_static(model, dofs, scale * unit_load, settings);
      std::ostringstream residuals;
      for (const kerf::NewtonIteration& it : result.history) residuals << " " << it.relative_residual;
      relative_differences.push_back(max_nodal_norm(result.u - u_linear) / max_nodal_norm(u_linear));
      MESSAGE("order " << order << ", max |u| = " << max_displacement << " m: max |u_corotational - u_linear| / max |u| = "
                       << relative_differences.back() << " (|u| / L = " << max_displacement / beam_length << "); converged "
                       << result.converged << ", relative residuals" << residuals.str());
      // f_int = R K (R^T x - X) is computed from positions x = X + u of ~0.2 m, so it carries a
      // round-off floor of ~1e-16 |K| |X| while the forces in play are only ~|K| |u|. The
      // solver measures its residual against that floor (position_force_norm), so Newton must
      // report convergence at both sizes, not stall on round-off.
      CHECK(result.converged);
    }
    // |u| / L = 5e-6 at |u| = 1e-6 m; the difference is a fraction of it (measured 2.9e-6 Tet4,
    // 3.0e-6 Tet10: about 0.6 |u| / L).
    CHECK(relative_differences[0] < 5e-6);
    // At |u| = 1e-7 m it is ten times smaller (measured 2.9e-7, 3.0e-7): below 1e-6.
    CHECK(relative_differences[1] < 1e-6);
    // And it is the geometry, not noise: shrinking the load tenfold shrinks it tenfold
    // (measured 9.99 and 9.99), as a second-order term must.
    CHECK(relative_differences[0] / relative_differences[1] == kerf_test::relative(10.0, 0.2));
  }
}

TEST_CASE("both end faces turned by 90 degrees: the whole beam turns rigidly, with either tangent") {
  const kerf::LinearMaterial material{300e3, 0.35, 1070};
  // A quarter turn about the y axis through the beam's centre.
  const Eigen::Vector3d center(0.015, 0.03, 0.1);
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(pi / 2.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
  for (const int order : {1, 2}) {
    CAPTURE(order);
    const kerf::TetMesh mesh = beam_mesh(order);
    std::vector<kerf::DirichletNodes> conditions;
    add_rotated_nodes(mesh, kerf::nodes_in_region(mesh, end_face(0.0)), Q, center, conditions);
    add_rotated_nodes(mesh, kerf::nodes_in_region(mesh, end_face(beam_length)), Q, center, conditions);
    const kerf::DofMap dofs = kerf::make_dof_map(mesh.num_nodes(), conditions);
    const kerf::CorotationalModel model(mesh, material);
    const Eigen::VectorXd no_load = Eigen::VectorXd::Zero(3 * mesh.num_nodes());

    // The answer: every node on the rigid rotation, u = (Q - I)(X - c).
    Eigen::VectorXd u_rigid(3 * mesh.num_nodes()), unit_strain(3 * mesh.num_nodes());
    for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) {
      const Eigen::Vector3d X = mesh.nodes.row(v).transpose();
      u_rigid.segment<3>(3 * v) = (Q - Eigen::Matrix3d::Identity()) * (X - center);
      unit_strain.segment<3>(3 * v) = X; // x = 2X: the energy scale of a unit strain
    }
    const double energy_scale = model.energy(unit_strain, kerf::RotationMethod::svd);

    // One load step. The solver ramps prescribed displacements along the straight chord
    // lambda (Q - I)(X - c), which at lambda = 1/2 squeezes the end faces to 71% of their
    // width; measured: with 2 or 3 steps those intermediate steps do not converge in 40
    // iterations (either tangent), while the last step still lands on the rotation. In one
    // step, the first iterate is chapter 1's linear answer and the rest is corotation's work.
    kerf::QuasiStaticSettings settings;
    settings.load_steps = 1;
    for (const kerf::CorotationalTangent tangent : {kerf::CorotationalTangent::consistent, kerf::CorotationalTangent::warped}) {
      const bool consistent = tangent == kerf::CorotationalTangent::consistent;
      CAPTURE(consistent);
      settings.tangent = tangent;
      const kerf::QuasiStaticResult result = kerf::solve_quasi_static(model, dofs, no_load, settings);
      const double error = max_nodal_norm(result.u - u_rigid);
      const double energy = model.energy(result.u, kerf::RotationMethod::svd) / energy_scale;
      MESSAGE("order " << order << std::string(consistent ? ", consistent" : ", warped") << " tangent: converged "
                       << result.converged << ", " << result.total_iterations << " Newton iterations, max |u - (Q - I)(X - c)| = "
                       << error << " m, energy / (X^T K X / 2) = " << energy);
      CHECK(result.converged);
      // The solver stops at a residual of 1e-9 of the forces in play, converging fast at the
      // end, so the nodes are left ~1e-9 of a cell (2 cm) or much less off the rotation
      // (measured 5e-15 to 3e-10 m).
      CHECK(error < 1e-8);
      // The strain is that error over a cell and the energy its square.
      CHECK(energy < 1e-12);
      // At the stress-free answer the warped tangent equals the consistent one (see
      // test_corotated_forces.cpp), so both end quadratically here: measured 8 and 6 (Tet4),
      // 8 and 7 (Tet10) iterations. The tangents differ where the answer carries stress: below.
      CHECK(result.total_iterations <= 12);
    }
  }
}

TEST_CASE("a tip-loaded cantilever: the consistent tangent converges quadratically, the warped one linearly") {
  const kerf::LinearMaterial material{300e3, 0.35, 1070};
  for (const int order : {1, 2}) {
    CAPTURE(order);
    const kerf::TetMesh mesh = beam_mesh(order);
    const kerf::DofMap dofs = kerf::make_dof_map(mesh.num_nodes(), {{kerf::nodes_in_region(mesh, end_face(0.0)), {0, 0, 0}}});
    // 0.5 N along x on the top face turns the tip by ~10 to 20 degrees: a stressed equilibrium.
    Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * mesh.num_nodes());
    kerf::add_uniform_traction(mesh, kerf::boundary_faces(mesh), kerf::node_mask(mesh, end_face(beam_length)), {0.5, 0.0, 0.0}, f);
    const kerf::CorotationalModel model(mesh, material);
    kerf::QuasiStaticSettings settings;
    settings.load_steps = 4;

    // Quadratic convergence: r_{k+1} <= C r_k^2 for the relative residuals of the last step,
    // between 1e-3 (near enough) and 1e-11 (above the round-off floor). C is the curvature of
    // f_int over its slope in these units; we measured C up to ~1e3 and allow 1e4. Linear
    // convergence, r_{k+1} ~ rho r_k, breaks this bound as soon as r_k < rho / C.
    const auto quadratic = [](const std::vector<double>& r) {
      bool ok = true;
      for (std::size_t k = 1; k + 1 < r.size(); ++k)
        if (r[k] < 1e-3 && r[k + 1] > 1e-11) ok = ok && r[k + 1] <= 1e4 * r[k] * r[k];
      return ok;
    };
    std::vector<double> last_step[2];
    int iterations[2] = {0, 0};
    Eigen::VectorXd u[2];
    for (const int t : {0, 1}) {
      settings.tangent = t == 0 ? kerf::CorotationalTangent::consistent : kerf::CorotationalTangent::warped;
      const kerf::QuasiStaticResult result = kerf::solve_quasi_static(model, dofs, f, settings);
      REQUIRE(result.converged);
      for (const kerf::NewtonIteration& it : result.history) {
        if (it.step == settings.load_steps) last_step[t].push_back(it.relative_residual);
        CHECK_FALSE(it.warped_fallback);
      }
      iterations[t] = result.total_iterations;
      u[t] = result.u;
      std::ostringstream residuals;
      for (double r : last_step[t]) residuals << " " << r;
      MESSAGE("order " << order << std::string(t == 0 ? ", consistent" : ", warped") << " tangent: " << result.total_iterations
                       << " Newton iterations in 4 steps; last step residuals" << residuals.str());
    }
    // The same equilibrium (both stop at a residual of 1e-9).
    CHECK(max_nodal_norm(u[0] - u[1]) < 1e-6 * max_nodal_norm(u[0]));
    // Measured 14 vs 20 (Tet4), 16 vs 31 (Tet10).
    CHECK(iterations[0] < iterations[1]);
    // Consistent: from the step's first correction to below 1e-9 in at most 4 more iterations,
    // quadratically. Warped: the bound fails, so the check can tell the two apart.
    CHECK(last_step[0].size() <= 6);
    CHECK(quadratic(last_step[0]));
    CHECK_FALSE(quadratic(last_step[1]));
  }
}

TEST_CASE("a corotational scene with a rotated support and quasi-static settings parses; bad values are named") {
  const std::string mesh = R"("mesh": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0.2], "cells": [2, 3, 8]}, "order": 2})";
  const std::string good = "{" + mesh + R"(, "model": "corotational",
    "dirichlet": [{"region": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0]}}},
                  {"region": {"box": {"min": [0, 0, 0.2], "max": [0.03, 0.06, 0.2]}},
                   "rotation": {"axis": [0, 2, 0], "degrees": 90, "center": [0.015, 0.03, 0.1]}}],
    "quasi_static": {"load_steps": 12, "max_iterations": 25, "tolerance": 1e-8, "tangent": "warped", "rotation": "svd"}})";
  const kerf::Scene scene = kerf::parse_scene(good, "bend.json", ".");
  CHECK(scene.model == "corotational");
  REQUIRE(scene.dirichlet.size() == 2);
  CHECK_FALSE(scene.dirichlet[0].has_rotation);
  const kerf::DirichletSpec& turned = scene.dirichlet[1];
  CHECK(turned.has_rotation);
  CHECK((turned.axis - Eigen::Vector3d::UnitY()).norm() < 1e-15); // normalised when read
  CHECK(turned.degrees == 90.0);
  CHECK((turned.center - Eigen::Vector3d(0.015, 0.03, 0.1)).norm() < 1e-15);
  // A quarter turn about +y takes +x to -z: the point c + 0.01 e_x moves by 0.01 (-1, 0, -1).
  const Eigen::Vector3d moved = turned.displacement_at(turned.center + Eigen::Vector3d(0.01, 0, 0));
  CHECK((moved - Eigen::Vector3d(-0.01, 0, -0.01)).norm() < 1e-15);
  CHECK(scene.quasi_static.load_steps == 12);
  CHECK(scene.quasi_static.max_iterations == 25);
  CHECK(scene.quasi_static.tolerance == 1e-8);
  CHECK(scene.quasi_static.tangent == "warped");
  CHECK(scene.quasi_static.rotation == "svd");

  // Each bad value must be an InputError whose message names the field.
  const auto rejects = [&](const std::string& body, const std::string& field) {
    CAPTURE(body);
    CHECK_THROWS_WITH_AS(kerf::parse_scene("{" + mesh + ", " + body + "}", "bad.json", "."), doctest::Contains(field.c_str()), kerf::InputError);
  };
  const std::string support = R"("region": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0]}})";
  rejects(R"("quasi_static": {"tangent": "exact"})", "quasi_static.tangent");
  rejects(R"("quasi_static": {"load_steps": 0})", "quasi_static.load_steps");
  rejects(R"("quasi_static": {"rotation": "euler"})", "quasi_static.rotation");
  rejects(R"("quasi_static": {"tolerance": 0})", "quasi_static.tolerance");
  rejects(R"("dirichlet": [{)" + support + R"(, "rotation": {"degrees": 90}}])", "dirichlet[0].rotation.axis");
  rejects(R"("dirichlet": [{)" + support + R"(, "rotation": {"axis": [0, 0, 0], "degrees": 90}}])", "dirichlet[0].rotation.axis");
  rejects(R"("dirichlet": [{)" + support + R"(, "rotation": {"axis": [0, 1, 0]}}])", "dirichlet[0].rotation.degrees");
  rejects(R"("model": "hyperelastic")", "model");
}

/// The Tet4 cantilever under 0.5 N on its top face, in 10 load steps: a gentle load path.
struct GentleCantilever {
  kerf::TetMesh mesh = beam_mesh(1);
  kerf::DofMap dofs = kerf::make_dof_map(mesh.num_nodes(), {{kerf::nodes_in_region(mesh, end_face(0.0)), {0, 0, 0}}});
  Eigen::VectorXd f = tip_traction();
  kerf::CorotationalModel model{mesh, kerf::LinearMaterial{300e3, 0.35, 1070}};

  Eigen::VectorXd tip_traction() const {
    Eigen::VectorXd load = Eigen::VectorXd::Zero(3 * mesh.num_nodes());
    kerf::add_uniform_traction(mesh, kerf::boundary_faces(mesh), kerf::node_mask(mesh, end_face(beam_length)), {0.5, 0.0, 0.0},
                               load);
    return load;
  }
  kerf::QuasiStaticResult solve(const kerf::QuasiStaticSettings& settings) const {
    return kerf::solve_quasi_static(model, dofs, f, settings);
  }
};

TEST_CASE("the secant predictor saves Newton iterations on a gently loaded cantilever, to the same equilibrium") {
  const GentleCantilever cantilever;
  kerf::QuasiStaticSettings settings;
  settings.load_steps = 10;
  int iterations[2] = {0, 0};
  Eigen::VectorXd u[2];
  for (const int p : {0, 1}) {
    settings.predictor = p == 0 ? kerf::LoadStepPredictor::previous_state : kerf::LoadStepPredictor::secant;
    const kerf::QuasiStaticResult result = cantilever.solve(settings);
    REQUIRE(result.converged);
    iterations[p] = result.total_iterations;
    u[p] = result.u;
    CHECK(result.factorisations == result.total_iterations); // CHOLMOD: one factorisation per solve
  }
  MESSAGE("Newton iterations, 10 load steps: " << iterations[0] << " from the last equilibrium, " << iterations[1]
                                                << " with the secant predictor");
  // Both stop at a relative residual of 1e-9: the same equilibrium to ~1e-8.
  CHECK(max_nodal_norm(u[0] - u[1]) < 1e-7 * max_nodal_norm(u[0]));
  CHECK(iterations[1] < iterations[0]);
}

TEST_CASE("cg-cholmod reaches the same equilibrium as CHOLMOD with fewer factorisations") {
  const GentleCantilever cantilever;
  kerf::QuasiStaticSettings settings;
  settings.load_steps = 10;
  const kerf::QuasiStaticResult direct = cantilever.solve(settings);
  settings.solver.type = "cg-cholmod";
  settings.solver.tolerance = 1e-8;
  const kerf::QuasiStaticResult reused = cantilever.solve(settings);
  REQUIRE(direct.converged);
  REQUIRE(reused.converged);
  MESSAGE("cg-cholmod: " << reused.total_iterations << " Newton iterations, " << reused.factorisations << " factorisations, "
                         << reused.linear_iterations << " CG iterations; CHOLMOD: " << direct.total_iterations << " iterations");
  CHECK(max_nodal_norm(direct.u - reused.u) < 1e-7 * max_nodal_norm(direct.u));
  CHECK(reused.factorisations < reused.total_iterations);
}
