/* Kerf, chapter 2: corotation, large rotations without ghost forces.

   Build:   cmake --preset release && cmake --build --preset release --target 02_corotation

   Sample runs:
     02_corotation
     02_corotation --scene examples/02_beam_twisted_ends_tet4.json --out output/twisted
     02_corotation --scene examples/02_beam_tip_load_tet10.json --probes examples/01_beam_probes.csv --probes-out output/tip_probes.csv

   Description: the beam of chapter 1 (0.03 x 0.06 x 0.2 m, E = 300 kPa, nu = 0.35) is clamped
   at z = 0 while its top face is carried rigidly to the end of a quarter circle of length
   0.2 m: turned by 90 degrees about the x axis and moved by (0, R, R - 0.2), R = 0.4 / pi.
   The beam bends into that quarter circle (pure bending). Linear FEM would stretch and swell
   it (ghost forces); corotated FEM keeps it the beam it was:

        z = 0.2 +----+                     ______+
                |    |                   /       | top face, turned 90 degrees
                |    |     becomes      |   _____+
                |    |                  |  /
        z = 0   +----+                  +--+
               //////// clamped        //////// clamped

   Read chapter 1 first. */

// @sect3{Include files}
//
// New since chapter 1: the corotation area of the library. Its model precomputes the element
// data, and the quasi-static solver finds equilibrium by load steps and Newton iterations.
#include "kerf/app/command_line.hpp"
#include "kerf/app/input_error.hpp"
#include "kerf/corotation/corotational_model.hpp"
#include "kerf/corotation/quasi_static_solver.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/solve_linear_static.hpp"
#include "kerf/io/probes_csv.hpp"
#include "kerf/io/newton_history_csv.hpp"
#include "kerf/io/write_vtu.hpp"
#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/scene/scene.hpp"
#include "kerf/scene/scene_mesh.hpp"
#include "kerf/scene/scene_quasi_static.hpp"

#include <chrono>
#include <filesystem>
#include <iostream>
#include <memory>

namespace chapter02 {

// @sect3{The demo scene}
//
// New fields since chapter 1: "model": "corotational", a Dirichlet condition that turns its
// region rigidly ("rotation": axis, angle in degrees, a point on the axis), and the settings of
// the quasi-static solver. The turn (and the move of the top face with it) is applied in 10
// load steps.
constexpr const char* demo_scene = R"({
  "name": "beam_bent_90",
  "mesh": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0.2], "cells": [2, 4, 14]}, "order": 2},
  "material": {"young": 300e3, "poisson": 0.35, "density": 1070},
  "model": "corotational",
  "dirichlet": [
    {"region": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0]}}},
    {"region": {"box": {"min": [0, 0, 0.2], "max": [0.03, 0.06, 0.2]}},
     "rotation": {"axis": [1, 0, 0], "degrees": -90, "center": [0.015, 0.03, 0.2]},
     "displacement": [0, 0.127323954, -0.072676046]}],
  "quasi_static": {"load_steps": 10, "tangent": "consistent", "rotation": "automatic"}
})";

// @sect3{The CorotationalElasticity class}
//
// The skeleton of chapter 1, with one change in meaning: assemble_system no longer builds a
// matrix once. The corotated forces and their tangent depend on the current shape, so they are
// assembled inside every Newton iteration, by the quasi-static solver; what assemble_system
// keeps is the external load. The linear model of chapter 1 is still available ("model":
// "linear"), so that a scene can be run both ways and compared.
class CorotationalElasticity {
public:
  CorotationalElasticity(kerf::Scene scene, kerf::CommandLine options) : scene_(std::move(scene)), options_(std::move(options)) {}
  void run();

private:
  void make_mesh();
  void setup_system();
  void assemble_system();
  void solve();
  void output_results() const;
  void report(const std::string& line) const {
    if (!options_.quiet) std::cout << line << '\n';
  }

  kerf::Scene scene_;
  kerf::CommandLine options_;
  kerf::TetMesh mesh_;
  kerf::BoundaryFaces boundary_;
  kerf::DofMap dofs_;
  std::unique_ptr<kerf::CorotationalModel> model_;
  Eigen::VectorXd f_ext_;  // the full external load (3#V), reached at the last load step
  Eigen::VectorXd u_;      // all 3#V nodal displacements
  kerf::QuasiStaticResult result_;
};

// @sect4{CorotationalElasticity::make_mesh}
//
// As in chapter 1.
void CorotationalElasticity::make_mesh() {
  mesh_ = kerf::make_scene_mesh(scene_, &std::cerr);
  boundary_ = kerf::boundary_faces(mesh_);
  report("mesh: " + std::to_string(mesh_.num_nodes()) + " nodes, " + std::to_string(mesh_.num_tets()) + " Tet" +
         std::to_string(mesh_.nodes_per_tet()) + ", model " + scene_.model);
}

// @sect4{CorotationalElasticity::setup_system}
//
// The unknowns and the Dirichlet conditions are those of chapter 1; a rotated region gives
// each of its nodes the displacement \f$(Q - I)(X - c)\f$ of the rigid turn. New is the model:
// for every element (every quadrature point of a Tet10) it stores what never changes, the
// shape gradients and the linear stiffness of chapter 1, so that a Newton iteration only has
// to find the rotations and turn the stored matrices with them.
void CorotationalElasticity::setup_system() {
  dofs_ = kerf::scene_dof_map(scene_, mesh_, &std::cerr);
  model_ = std::make_unique<kerf::CorotationalModel>(mesh_, scene_.material);
  report("system: " + std::to_string(dofs_.num_free) + " unknowns");
}

// @sect4{CorotationalElasticity::assemble_system}
//
// The external loads are those of chapter 1: gravity and tractions, here as the full load that
// the last load step reaches. They stay attached to the reference configuration ("dead"
// loads): a traction keeps its direction while the face it acts on turns. That is the
// simplest model, and the one the comparison with CalculiX in the results uses.
void CorotationalElasticity::assemble_system() {
  f_ext_ = kerf::scene_external_loads(scene_, mesh_, boundary_);
}

// @sect4{CorotationalElasticity::solve}
//
// For the linear model, one solve as in chapter 1. For the corotational one we look for the
// displacement at which the corotated internal forces balance the loads, eq. (40) without
// inertia:
// \f[ f_{\rm int}(u) = \sum_e R_e K_e (R_e^T x_e - X_e) = \lambda f_{\rm ext},
//     \qquad F_e = R_e S_e , \f]
// with the rotation \f$R_e\f$ of each element's deformation gradient (eq. 31; for a Tet10 one
// rotation per quadrature point). The equation is nonlinear in \f$u\f$ through \f$R_e\f$, so
// kerf::solve_quasi_static ramps loads and prescribed displacements over the load steps
// (\f$\lambda = 1/N, \dots, 1\f$) and runs Newton's method in each. Its tangent is, by default,
// the *consistent* one: the warped stiffness \f$R K R^T\f$ of eq. (38) plus the terms that come
// from \f$\partial R / \partial x\f$. With the polar rotation the corotated force is the
// gradient of an energy, so this tangent is symmetric, and Newton converges quadratically;
// the warped stiffness alone, which the paper uses, makes it converge only linearly (the
// results measure both). Where the consistent tangent is not positive definite (strong
// compression), that iteration falls back to the warped one.
void CorotationalElasticity::solve() {
  if (scene_.model == "linear") {
    u_ = kerf::solve_linear_static(mesh_, scene_.material, dofs_, f_ext_, scene_.solver);
    return;
  }
  const kerf::QuasiStaticSettings settings = kerf::scene_quasi_static_settings(scene_);
  // The prescribed displacements follow the scene's path: a turned region turns by lambda times
  // its angle at load factor lambda, instead of sliding along the chord.
  const auto path = [this](double lambda) { return kerf::scene_prescribed_displacements(scene_, mesh_, lambda); };
  result_ = kerf::solve_quasi_static(*model_, dofs_, f_ext_, settings, path);
  u_ = result_.u;
  int fallbacks = 0;
  for (const auto& iteration : result_.history) fallbacks += iteration.warped_fallback;
  report("newton: " + std::to_string(result_.total_iterations) + " iterations over " + std::to_string(settings.load_steps) +
         " load steps, final relative residual " + std::to_string(result_.history.back().relative_residual) + ", " +
         std::to_string(fallbacks) + " warped fallbacks, " + std::to_string(result_.last_statistics.inverted_points) +
         " inverted points");
  if (!result_.converged)
    std::cerr << "warning: " << scene_.source.string() << ": the Newton iteration did not reach the tolerance "
              << settings.tolerance << " in every load step (see newton.csv)\n";
}

// @sect4{CorotationalElasticity::output_results}
//
// As in chapter 1, plus the convergence history of Newton's method (newton.csv: step,
// iteration, relative residual), which is how we know what the solver reached.
void CorotationalElasticity::output_results() const {
  Eigen::MatrixXd displacement(mesh_.num_nodes(), 3);
  for (Eigen::Index v = 0; v < mesh_.num_nodes(); ++v) displacement.row(v) = u_.segment<3>(3 * v).transpose();
  const std::filesystem::path vtu = options_.out_dir / (scene_.name + ".vtu");
  kerf::write_vtu(vtu, mesh_, {{"displacement", displacement}}, {});
  report("wrote " + vtu.string() + "; max |u| = " + std::to_string(displacement.rowwise().norm().maxCoeff()) + " m");

  if (!result_.history.empty()) {
    const std::filesystem::path csv = options_.out_dir / (scene_.name + "_newton.csv");
    kerf::write_newton_history_csv(csv, result_.history);
  }

  if (options_.probes_in) {
    kerf::sample_probes(*options_.probes_in, *options_.probes_out, mesh_, u_, &std::cerr);
    report("wrote " + options_.probes_out->string());
  }
}

// @sect4{CorotationalElasticity::run}
//
// As in chapter 1.
void CorotationalElasticity::run() {
  using clock = std::chrono::steady_clock;
  const auto seconds_since = [](clock::time_point start) { return std::chrono::duration<double>(clock::now() - start).count(); };
  auto start = clock::now();
  make_mesh();
  setup_system();
  assemble_system();
  report("setup: " + std::to_string(seconds_since(start)) + " s");
  start = clock::now();
  solve();
  report("solve: " + std::to_string(seconds_since(start)) + " s");
  std::filesystem::create_directories(options_.out_dir);
  output_results();
}

} // namespace chapter02

// @sect3{The main function}
//
// As in chapter 1; the chapter now teaches the corotational model too.
int main(int argc, char** argv) {
  const std::string usage =
      "usage: 02_corotation [--scene FILE.json] [--probes IN.csv --probes-out OUT.csv] [--out DIR] [--quiet]\n"
      "Solves a static elasticity problem, linear or corotational, on Tet4 or Tet10 elements (Kerf, chapter 2).\n";
  return kerf::run_guarded(argc, argv, "02_corotation", usage, [](const kerf::CommandLine& options) {
    const kerf::Scene scene = options.scene ? kerf::read_scene_file(*options.scene)
                                            : kerf::parse_scene(chapter02::demo_scene, "demo scene", ".");
    kerf::require_features(scene, kerf::SceneFeatures{.corotational = true});
    chapter02::CorotationalElasticity problem(scene, options);
    problem.run();
  });
}
