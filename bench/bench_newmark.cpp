/* Kerf benchmark: chapter 6's time step of the corotational cut soft block, on one core.

   Build and run:   cmake --build --preset release --target bench
                    (runs bench_newmark with OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1)
   By hand:         OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 bench_newmark --out bench_newmark.md
                    bench_newmark --quick      (the smallest block, a few steps: does it run?)
                    bench_newmark --only 12    (the 10k-tet block alone)

   The block of the speed study: a 0.1 m cube of soft tissue (E = 5 kPa, nu = 0.45,
   rho = 1000 kg/m^3), corotational, per-piece lumped mass, Rayleigh damping C = 1 M + 0.005 K_R,
   gravity along -z switched on at t = 0, clamped on its face x = 0, and cut by a horizontal slit
   at z = 0.051 through its free half (x > 0.05), so that it sags as two flaps. Newmark's average
   acceleration, dt = 10 ms, rotations frozen at each step's start (one linear solve per step,
   chapter 6's default). Meshes of 6 n^3 Tet4 for n = 6, 8, 12, 17, 26 (about 1k, 3k, 10k, 30k
   and 100k tets).

   For each mesh and each solver strategy it runs the same `steps` steps and reports the wall time
   per step, split into the phases of a step: assembly (the corotated forces and warped tangent,
   CutXfemModel::assemble), energy (the strain energy at the step's end, for the energy
   account), matrix (M_ff + gamma dt C_ff + beta dt^2 K_ff into its fixed pattern), solve
   (factorisation or preconditioner, and the solve) and rest (predictor, residuals, the energy
   account's products). The strategies: CHOLMOD refactorised every step; conjugate gradients
   warm-started from the last step's acceleration (a step solves for its change), preconditioned
   by Jacobi, by an incomplete Cholesky, or by a CHOLMOD factor reused over the steps and refreshed
   when a solve needs more than 10 iterations (cg-cholmod); CG at relative residuals 1e-2 to 1e-8
   up to 10k tets, the fastest of them beyond.
   Accuracy: the relative error |u - u_ref| / |u_ref| of the whole displacement field after the
   last step, u_ref the same run with CHOLMOD (a direct solve, far below 1e-10). Times are
   processor time (std::clock) of one run of `steps` steps, long against the clock's resolution;
   the 1k block is run once before everything to warm the caches and the allocator. With --out FILE.md the rows also
   go to FILE.csv. */

#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/dynamics/nonlinear_newmark.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/scene/scene.hpp"
#include "kerf/scene/scene_cuts.hpp"
#include "kerf/scene/scene_dynamic_mass.hpp"
#include "kerf/scene/scene_mesh.hpp"
#include "kerf/scene/scene_prescribed_motion.hpp"
#include "kerf/scene/scene_quadrature.hpp"
#include "kerf/scene/scene_quasi_static.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"
#include "kerf/xfem/surface_enrichment.hpp"
#include "measure.hpp"

#include <cstdio>
#include <ctime>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace {

// Processor time, not wall time: the machine these numbers come from is shared, and with one
// BLAS thread the processor time of the program is what a step costs on one quiet core.
double processor_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

// The scene of the block with n cells per edge.
std::string block_scene(int n) {
  std::ostringstream text;
  text << R"({"name": "soft_block", "mesh": {"box": {"min": [0, 0, 0], "max": [0.1, 0.1, 0.1], "cells": [)" << n << ", " << n << ", " << n
       << R"(]}, "order": 1},
  "material": {"young": 5000, "poisson": 0.45, "density": 1000}, "model": "corotational", "gravity": [0, 0, -9.81],
  "dirichlet": [{"region": {"box": {"min": [0, 0, 0], "max": [0, 0.1, 0.1]}}}],
  "cuts": [{"rectangle": {"origin": [0.05, -0.01, 0.051], "edge1": [0.07, 0, 0], "edge2": [0, 0.12, 0]}}],
  "time": {"integrator": "newmark", "dt": 0.01, "steps": 20, "mass": "lumped", "rayleigh": [1, 0.005], "corotation": "frozen"}})";
  return text.str();
}

// One solver strategy: a name for the tables and the settings.
struct Strategy {
  std::string label;
  kerf::SolverSettings solver;
};

std::vector<Strategy> strategies(bool full_ladder) {
  std::vector<Strategy> list;
  list.push_back({"cholmod", {}});
  list.back().solver.type = "cholmod";
  // The big blocks take the fastest candidates only: the incomplete Cholesky is the slowest
  // of all from 3k tets on (its set-up, redone every step, costs more than a factorisation).
  const std::vector<double> ladder = full_ladder ? std::vector<double>{1e-2, 1e-3, 1e-4, 1e-6, 1e-8} : std::vector<double>{1e-2, 1e-3, 1e-4};
  for (const char* type : {"cg-jacobi", "cg-ichol", "cg-cholmod"}) {
    if (!full_ladder && std::string(type) == "cg-ichol") continue;
    for (double tolerance : ladder) {
      if (!full_ladder && std::string(type) == "cg-jacobi" && tolerance < 1e-3) continue;
      Strategy s;
      s.solver.type = type;
      s.solver.tolerance = tolerance;
      char label[64];
      std::snprintf(label, sizeof label, "%s %.0e", type, tolerance);
      s.label = label;
      list.push_back(s);
    }
  }
  return list;
}

// The cut block, built as chapter 6's program builds it (06_newmark's setup_system and
// setup_nonlinear_integrator), with timers around the internal force and the energy.
class Block {
public:
  explicit Block(int n) : scene_(kerf::parse_scene(block_scene(n), "soft_block.json", ".")) {
    mesh_ = kerf::make_scene_mesh(scene_, &std::cerr);
    boundary_ = kerf::boundary_faces(mesh_);
    cuts_ = std::make_unique<kerf::CutSurfaces>(kerf::scene_cut_surfaces(scene_, &std::cerr));
    pieces_ = kerf::scene_mesh_pieces(scene_, mesh_, *cuts_, &std::cerr);
    enrichment_ = kerf::make_surface_enrichment(mesh_, pieces_);
    rule_ = kerf::scene_piece_rule(scene_, mesh_.order());
    model_ = std::make_unique<kerf::CutXfemModel>(mesh_, scene_.material, pieces_, enrichment_, rule_);
    system_.dofs = kerf::make_cut_xfem_dof_map(*model_, kerf::scene_held_nodes(scene_, mesh_, &std::cerr));
    system_.M = kerf::scene_cut_xfem_mass(scene_, *model_, rule_);
    const kerf::DofMap all_free = kerf::make_dof_map(model_->num_dof_nodes(), {});
    assembler_ = std::make_unique<kerf::SparseAssembler>(model_->assembly_slots(), all_free);
    const Eigen::VectorXd f = kerf::scene_cut_xfem_dynamic_loads(scene_, *model_, boundary_, rule_);
    system_.rayleigh_alpha = scene_.time.rayleigh[0];
    system_.rayleigh_beta = scene_.time.rayleigh[1];
    system_.load = [f](double) { return f; };
    system_.motion = [this](double t) { return kerf::scene_prescribed_motion(scene_, mesh_, model_->num_dof_nodes(), t); };
    const kerf::RotationMethod rotation = kerf::scene_quasi_static_settings(scene_).rotation;
    system_.internal_force = [this, rotation](const Eigen::VectorXd& u, kerf::CorotationalTangent tangent, Eigen::VectorXd& f_int,
                                              const Eigen::SparseMatrix<double>** K) {
      const double start = processor_seconds();
      Eigen::VectorXd unused = Eigen::VectorXd::Zero(u.size());
      if (K) assembler_->set_zero();
      model_->assemble(u, rotation, tangent, f_int, K ? assembler_.get() : nullptr, K ? &unused : nullptr);
      if (K) *K = &assembler_->matrix();
      assembly_seconds += processor_seconds() - start;
    };
    system_.elastic_energy = [this, rotation](const Eigen::VectorXd& u) {
      const double start = processor_seconds();
      const double W = model_->energy(u, true, rotation);
      energy_seconds += processor_seconds() - start;
      return W;
    };
  }

  long tets() const { return static_cast<long>(mesh_.num_tets()); }
  long unknowns() const { return static_cast<long>(system_.dofs.num_free); }
  long nodes() const { return static_cast<long>(mesh_.num_nodes()); }

  // The run's result and its phases.
  struct Run {
    Eigen::VectorXd u;
    double total = 0, assembly = 0, energy = 0, matrix = 0, solve = 0;
    long iterations = 0;
    int factorisations = 0;
  };

  Run run(const kerf::SolverSettings& solver, int steps) {
    kerf::NonlinearNewmarkSettings settings;
    settings.solver = solver;
    kerf::NonlinearNewmarkIntegrator integrator(system_, scene_.time.dt, settings);
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(3 * model_->num_dof_nodes());
    kerf::DynamicState state = integrator.initial_state(zero, zero, 0.0);
    kerf::EnergyAccount account = integrator.start_account(state);
    assembly_seconds = energy_seconds = 0.0;
    Run result;
    const double start = processor_seconds();
    for (int s = 0; s < steps; ++s) {
      const kerf::NonlinearStepReport report = integrator.step(state);
      integrator.add_step(account, state, report);
      result.matrix += report.matrix_seconds;
      result.solve += report.solve_seconds;
      result.iterations += report.solver_iterations;
    }
    result.total = processor_seconds() - start;
    result.assembly = assembly_seconds;
    result.energy = energy_seconds;
    result.factorisations = integrator.factorisations();
    result.u = state.u;
    return result;
  }

private:
  kerf::Scene scene_;
  kerf::TetMesh mesh_;
  kerf::BoundaryFaces boundary_;
  std::unique_ptr<kerf::CutSurfaces> cuts_;
  kerf::MeshPieces pieces_;
  kerf::SurfaceEnrichment enrichment_;
  kerf::PieceRuleFunction rule_;
  std::unique_ptr<kerf::CutXfemModel> model_;
  std::unique_ptr<kerf::SparseAssembler> assembler_;
  kerf::NonlinearDynamicSystem system_;
  double assembly_seconds = 0.0, energy_seconds = 0.0;
};

} // namespace

int main(int argc, char** argv) {
  // --only picks blocks by their cells per edge (e.g. --only 12: the 10k block alone), for a
  // before/after comparison run back to back.
  const auto options =
      kerf_measure::parse_run_options(argc, argv, "bench_newmark [--quick] [--out FILE.md] [--only 6,8,12,17,26]", {}, {"6", "8", "12", "17", "26"});
  if (!options) return 2;
  std::vector<int> cells;
  for (const int n : options->quick ? std::vector<int>{4} : std::vector<int>{6, 8, 12, 17, 26})
    if (options->quick || options->runs(std::to_string(n))) cells.push_back(n);
  const int steps = options->quick ? 3 : 20;

  std::ostringstream table, csv;
  csv << "tets,nodes,unknowns,strategy,type,tolerance,steps,ms_per_step,assembly_ms,energy_ms,matrix_ms,solve_ms,rest_ms,"
         "iterations_per_step,factorisations,relative_error\n";
  table << "| tets | unknowns | strategy | ms/step | assembly | energy | matrix | solve | rest | CG it./step | factorisations | error |\n"
        << "|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  Block(options->quick ? 4 : 6).run({}, steps); // warm-up
  for (int n : cells) {
    Block block(n);
    std::cerr << "bench_newmark: " << block.tets() << " tets, " << block.unknowns() << " unknowns\n";
    Eigen::VectorXd reference;
    for (const Strategy& strategy : strategies(n <= 12)) {
      const Block::Run run = block.run(strategy.solver, steps);
      if (reference.size() == 0) reference = run.u;
      const double error = (run.u - reference).norm() / reference.norm();
      const double ms = 1e3 / steps, rest = run.total - run.assembly - run.energy - run.matrix - run.solve;
      const double iterations = strategy.solver.type == "cholmod" ? 0.0 : static_cast<double>(run.iterations) / steps;
      char row[512];
      std::snprintf(row, sizeof row, "| %ld | %ld | %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.1f | %d | %.1e |\n", block.tets(),
                    block.unknowns(), strategy.label.c_str(), ms * run.total, ms * run.assembly, ms * run.energy, ms * run.matrix,
                    ms * run.solve, ms * rest, iterations, run.factorisations, error);
      table << row;
      std::cerr << row;
      std::snprintf(row, sizeof row, "%ld,%ld,%ld,%s,%s,%.0e,%d,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.2f,%d,%.3e\n", block.tets(), block.nodes(),
                    block.unknowns(), strategy.label.c_str(), strategy.solver.type.c_str(), strategy.solver.tolerance, steps, ms * run.total,
                    ms * run.assembly, ms * run.energy, ms * run.matrix, ms * run.solve, ms * rest, iterations, run.factorisations, error);
      csv << row;
    }
  }

  std::ostringstream report;
  report << "# Chapter 6 benchmark: the Newmark step of the corotational cut soft block\n\n"
         << kerf_measure::machine_lines() << "- " << steps
         << " steps of 10 ms, rotations frozen per step; processor time in ms per step (one run each); error: |u - u_ref| / |u_ref| of "
            "the field after the last step, u_ref with CHOLMOD\n\n"
         << table.str();
  std::cout << report.str();
  kerf_measure::write_report(options->out, report.str(), csv.str());
  return 0;
}
