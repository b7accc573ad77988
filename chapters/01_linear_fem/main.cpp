/* Kerf, chapter 1: linear elasticity with Tet4 and Tet10 elements.

   Build:   cmake --preset release && cmake --build --preset release --target 01_linear_fem

   Sample runs:
     01_linear_fem
     01_linear_fem --scene examples/01_beam_traction_tet4.json --out output/traction
     01_linear_fem --scene examples/01_beam_gravity_tet10.json --probes examples/01_beam_probes.csv --probes-out output/probes.csv

   Description: a soft beam (0.03 x 0.06 x 0.2 m, E = 300 kPa, nu = 0.35, rho = 1070 kg/m^3)
   is clamped at z = 0 and bends under its own weight, gravity pointing along +x as in the test
   case 1 of Schoch et al.:

                 z = 0.2 +----+
                         |    |
                         |    |   g = (9.81, 0, 0) m/s^2  -->
                         |    |
                         |    |
                 z = 0   +----+
                        ////////  clamped: u = 0

   This is the first chapter: read the conventions page first, nothing else. */

// @sect3{Include files}
//
// Every piece of machinery this program uses lives in the kerf library, one idea per header.
// The chapter only strings the pieces together, in the order a finite element program always
// has: make a mesh, set up the unknowns, assemble, solve, write the results.
#include "kerf/app/command_line.hpp"
#include "kerf/app/input_error.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/assemble_stiffness.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/io/probes_csv.hpp"
#include "kerf/io/write_vtu.hpp"
#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/scene/scene.hpp"
#include "kerf/scene/scene_mesh.hpp"
#include "kerf/solve/linear_solver.hpp"

#include <chrono>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace chapter01 {

// @sect3{The demo scene}
//
// Run without arguments, the program solves this scene. It is an ordinary scene file, kept
// inside the program so that the demo runs from any folder; the scene reference page of the
// book lists every field. The mesh is a box of 3 x 6 x 20 hexahedral cells, each split into six
// tetrahedra, promoted to quadratic Tet10 elements ("order": 2).
constexpr const char* demo_scene = R"({
  "name": "beam_gravity",
  "mesh": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0.2], "cells": [3, 6, 20]}, "order": 2},
  "material": {"young": 300e3, "poisson": 0.35, "density": 1070},
  "dirichlet": [{"region": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0]}}, "displacement": [0, 0, 0]}],
  "gravity": [9.81, 0, 0]
})";

// @sect3{The LinearElasticity class}
//
// The class has the skeleton every chapter keeps (make_mesh, setup_system, assemble_system,
// solve, output_results, run), so that the next chapter's program differs from this one only
// where the method does.
class LinearElasticity {
public:
  LinearElasticity(kerf::Scene scene, kerf::CommandLine options) : scene_(std::move(scene)), options_(std::move(options)) {}
  void run();

private:
  void make_mesh();
  void setup_system();
  void assemble_system();
  void solve();
  void output_results();
  void report(const std::string& line) const {
    if (!options_.quiet) std::cout << line << '\n';
  }
  // The profile of a run: each call reports the wall time since the previous one, labelled
  // with the work it covered, and the book's results compare these across meshes.
  void lap(const std::string& work) {
    const auto now = std::chrono::steady_clock::now();
    laps_.emplace_back(work, std::chrono::duration<double>(now - lap_start_).count());
    lap_start_ = now;
  }

  kerf::Scene scene_;
  kerf::CommandLine options_;
  kerf::TetMesh mesh_;
  kerf::BoundaryFaces boundary_;
  kerf::DofMap dofs_;
  std::unique_ptr<kerf::SparseAssembler> assembler_;
  std::unique_ptr<kerf::LinearSolver> solver_;
  Eigen::VectorXd rhs_;  // f_f - K_fc u_c, on the free DOFs
  Eigen::VectorXd u_;    // all 3#V nodal displacements
  std::chrono::steady_clock::time_point lap_start_ = std::chrono::steady_clock::now();
  std::vector<std::pair<std::string, double>> laps_; // (work, seconds), in order
};

// @sect4{LinearElasticity::make_mesh}
//
// The mesh comes from the box mesher or from a file (Gmsh, VTK, Medit). A file is checked on
// the way in: a flat tet is rejected by its index, an inverted one is turned around with a
// warning. For "order": 2 every edge gets a mid-edge node and every tet becomes a Tet10. We
// also collect the boundary faces, on which tractions act.
void LinearElasticity::make_mesh() {
  mesh_ = kerf::make_scene_mesh(scene_, &std::cerr);
  boundary_ = kerf::boundary_faces(mesh_);
  lap("mesh");
  report("mesh: " + std::to_string(mesh_.num_nodes()) + " nodes, " + std::to_string(mesh_.num_tets()) + " Tet" +
         std::to_string(mesh_.nodes_per_tet()) + ", " + std::to_string(boundary_.faces.rows()) + " boundary faces");
}

// @sect4{LinearElasticity::setup_system}
//
// The unknowns are the three displacement components of every node, numbered node by node
// (DOF \f$3v+p\f$ is component \f$p\f$ of node \f$v\f$). Dirichlet conditions fix some of
// them. We eliminate those from the system instead of penalising them: writing
// \f$u = (u_f, u_c)\f$ for the free and the prescribed DOFs, the equations of the free ones are
// \f[ K_{ff}\, u_f = f_f - K_{fc}\, u_c , \f]
// a smaller system that is still symmetric positive definite, provided the conditions hold
// every rigid motion of the body: kerf::scene_dof_map counts the motions they leave free
// (kerf::count_free_rigid_motions) and refuses the scene if there are any, before any
// factorisation, because a factorisation of a singular matrix may "succeed" with round-off
// pivots and return a huge, finite, wrong answer. The assembler builds the
// sparsity pattern of \f$K_{ff}\f$ here, once, together with the position of every element
// entry in it; the solver analyses that pattern (fill-reducing ordering, symbolic
// factorisation) once too. The ordering decides what the factorisation costs; CHOLMOD computes
// it here on the graph of the nodes rather than of the unknowns, three times smaller and as
// good (kerf::CholmodSolver; the results page measures the difference).
void LinearElasticity::setup_system() {
  dofs_ = kerf::scene_dof_map(scene_, mesh_, &std::cerr);
  lap("unknowns");
  assembler_ = std::make_unique<kerf::SparseAssembler>(mesh_.tets, dofs_);
  lap("pattern");
  solver_ = kerf::make_linear_solver(scene_.solver);
  solver_->analyze_pattern(assembler_->matrix());
  lap("ordering");
  report("system: " + std::to_string(dofs_.num_free) + " unknowns, " + std::to_string(assembler_->num_stored_entries()) +
         " stored entries, solver " + solver_->name());
}

// @sect4{LinearElasticity::assemble_system}
//
// The element stiffness matrix is eq. (30) of Schoch et al. integrated over the element,
// \f[ \frac{\partial \mathcal{F}_{ip}}{\partial \tilde{\mathcal{P}}_{jq}}
//     = \int_T \mu\, \nabla\Phi_{iq} \nabla\Phi_{jp}
//       + \mu\, \delta_{pq} \sum_{l} \nabla\Phi_{il} \nabla\Phi_{jl}
//       + \lambda\, \nabla\Phi_{ip} \nabla\Phi_{jq} \, dV . \f]
// For a Tet4 the gradients are constant and the integral is the integrand times the volume.
// For a Tet10 with straight edges the gradients are linear, the integrand quadratic, and the
// four-point rule of degree 2 integrates it exactly (kerf::tet4_stiffness, kerf::tet10_stiffness).
// kerf::assemble_linear_stiffness loops over the elements and adds each matrix into the fixed
// pattern through the scatter map; the columns of prescribed DOFs go to the right-hand side.
//
// The loads are the two external terms of eq. (22): gravity, \f$\int \rho\, g\, \Phi_a\, dV\f$,
// and a traction spread uniformly by area over the boundary faces of a region,
// \f$\int t\, \Phi_a\, dA\f$ with \f$t = F_{\rm total} / A\f$.
void LinearElasticity::assemble_system() {
  assembler_->set_zero();
  const Eigen::VectorXd f = kerf::scene_external_loads(scene_, mesh_, boundary_);
  rhs_ = dofs_.restrict_to_free(f);
  kerf::assemble_linear_stiffness(mesh_, scene_.material, *assembler_, rhs_);
  lap("assembly");
}

// @sect4{LinearElasticity::solve}
//
// The default solver is CHOLMOD's supernodal Cholesky factorisation; the scene may choose
// Eigen's SimplicialLDLT or conjugate gradients instead. setup_system has already made sure
// that \f$K_{ff}\f$ is positive definite.
void LinearElasticity::solve() {
  solver_->factorize(assembler_->matrix());
  lap("factorisation");
  Eigen::VectorXd u_free = Eigen::VectorXd::Zero(dofs_.num_free);
  solver_->solve(rhs_, u_free);
  u_ = dofs_.expand(u_free);
  lap("solve");
}

// @sect4{LinearElasticity::output_results}
//
// The displacement goes to a .vtu file that ParaView opens as it is, and, if asked, to the
// probe file: the discrete field \f$u(x) = \sum_a \Phi_a(x)\, u_a\f$ (eq. 14) at every probe
// point, NaN for points outside the mesh.
void LinearElasticity::output_results() {
  Eigen::MatrixXd displacement(mesh_.num_nodes(), 3);
  for (Eigen::Index v = 0; v < mesh_.num_nodes(); ++v) displacement.row(v) = u_.segment<3>(3 * v).transpose();
  const std::filesystem::path vtu = options_.out_dir / (scene_.name + ".vtu");
  kerf::write_vtu(vtu, mesh_, {{"displacement", displacement}}, {});
  report("wrote " + vtu.string() + "; max |u| = " + std::to_string(displacement.rowwise().norm().maxCoeff()) + " m");

  if (options_.probes_in) {
    kerf::sample_probes(*options_.probes_in, *options_.probes_out, mesh_, u_, &std::cerr);
    report("wrote " + options_.probes_out->string());
  }
  lap("output");
}

// @sect4{LinearElasticity::run}
//
// The steps in order. Each one's wall time (lap) is printed at the end as a profile: mesh,
// unknowns (the DOF map and the rigid-motion check), pattern (the sparsity pattern and the
// scatter map), ordering (the fill-reducing ordering and the symbolic factorisation), assembly,
// factorisation, solve (the triangular solves) and output.
void LinearElasticity::run() {
  make_mesh();
  setup_system();
  assemble_system();
  solve();
  output_results();
  std::ostringstream profile;
  profile << "time (s):";
  for (const auto& [work, seconds] : laps_) profile << ' ' << work << ' ' << std::fixed << std::setprecision(3) << seconds;
  report(profile.str());
}

} // namespace chapter01

// @sect3{The main function}
//
// The command line is the same in every chapter: without arguments the demo scene runs,
// `--scene` runs another one with what this chapter has taught (linear, static, uncut: a scene
// asking for more is refused with a message naming the chapter that teaches it). Every error
// ends as one line on stderr and a non-zero exit status, in one place: kerf::run_guarded.
int main(int argc, char** argv) {
  const std::string usage =
      "usage: 01_linear_fem [--scene FILE.json] [--probes IN.csv --probes-out OUT.csv] [--out DIR] [--quiet]\n"
      "Solves a static linear elasticity problem on Tet4 or Tet10 elements (Kerf, chapter 1).\n";
  return kerf::run_guarded(argc, argv, "01_linear_fem", usage, [](const kerf::CommandLine& options) {
    const kerf::Scene scene = options.scene ? kerf::read_scene_file(*options.scene)
                                            : kerf::parse_scene(chapter01::demo_scene, "demo scene", ".");
    kerf::require_features(scene, kerf::SceneFeatures{});
    chapter01::LinearElasticity problem(scene, options);
    problem.run();
  });
}
