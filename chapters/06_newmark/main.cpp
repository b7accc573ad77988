/* Kerf, chapter 6: implicit Newmark dynamics of cut tissue.

   Build:   cmake --preset release && cmake --build --preset release --target 06_newmark

   Sample runs:
     06_newmark
     06_newmark --scene examples/06_free_fall_lumped.json --probes examples/06_free_fall_probes.csv --probes-history output/free_fall_history.csv --out output/free_fall
     06_newmark --scene examples/06_flap_linear.json --out output/flap_linear
     06_newmark --scene examples/06_beam_shaken.json --out output/beam_shaken

   Description: the beam of chapters 1-4 (0.03 x 0.06 x 0.2 m, E = 300 kPa, nu = 0.35,
   rho = 1070 kg/m^3), Tet4 elements, clamped at z = 0, lies on its side: gravity pulls along
   +x. A cut at z = 0.15 goes through the beam's whole width in y and through x up to 0.025,
   so the top 5 cm, the flap, hangs by a strip on the x = 0.03 side. At t = 0 the body is at
   rest, undeformed, and let go: the beam sags, the flap folds over its strip, the cut opens,
   and Rayleigh damping lets the whole settle.

        z = 0.2  +-----+            +-----+
                 | flap|             \ flap \    the flap folds about its strip
        z = 0.15 ~~~~~ |  cut         ~~~~  |
                 |     |             |      |
                 |     |  g -->      |     /   the beam sags along +x
        z = 0    +-----+             +-----+
                //////// clamped    //////// clamped

   What is new: a mass (consistent, or lumped piece by piece so that a freed piece falls
   exactly at g), damping, and a time integrator (Newmark, HHT-alpha, backward Euler, the
   central difference) instead of the static solve; for the corotated body a Newmark step that
   either freezes the rotations at the step's start (one linear solve, Mueller and Gross) or
   iterates Newton to convergence; clamps that move in time; and the energy account of the
   run. Read chapters 1-4 first. */

// @sect3{Include files}
//
// New since chapter 4: the dynamics area (masses, damping, integrators, the energy account)
// and the scene's time field turned into masses, loads and a prescribed motion.
#include "kerf/app/command_line.hpp"
#include "kerf/app/input_error.hpp"
#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/dynamics/backward_euler.hpp"
#include "kerf/dynamics/central_difference.hpp"
#include "kerf/dynamics/energy_account.hpp"
#include "kerf/dynamics/hht_alpha.hpp"
#include "kerf/dynamics/linear_dynamic_system.hpp"
#include "kerf/dynamics/newmark.hpp"
#include "kerf/dynamics/nonlinear_newmark.hpp"
#include "kerf/dynamics/part_basis.hpp"
#include "kerf/dynamics/rayleigh_damping.hpp"
#include "kerf/io/probes_csv.hpp"
#include "kerf/io/write_vtu.hpp"
#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/scene/scene.hpp"
#include "kerf/scene/scene_crack_tip.hpp"
#include "kerf/scene/scene_cuts.hpp"
#include "kerf/scene/scene_dynamic_mass.hpp"
#include "kerf/scene/scene_mesh.hpp"
#include "kerf/scene/scene_prescribed_motion.hpp"
#include "kerf/scene/scene_quadrature.hpp"
#include "kerf/scene/scene_quasi_static.hpp"
#include "kerf/xfem/cut_xfem_mass.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"
#include "kerf/xfem/cut_xfem_output.hpp"
#include "kerf/xfem/surface_enrichment.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace chapter06 {

// A corotated step freezes its rotations at the step's start unless the scene says otherwise
// (time.corotation): this chapter's bodies turn slowly. Chapter 7's blade sets pieces spinning,
// and checks the step instead.
constexpr kerf::RotationUpdate default_rotations = kerf::RotationUpdate::frozen;

// @sect3{The demo scene}
//
// Chapter 4's beam with Tet4 elements (a Tet10 beam works too, about eight times slower a
// step), the flap's cut as a rectangle, and the new "time" field: the average acceleration
// rule, 300 steps of 5 ms (1.5 s, nearly four of the beam's swings, whose period is 0.39 s in
// results.md's chart), the per-piece lumped mass, and Rayleigh damping C = 3 M + 0.002 K_R,
// which damps that swing (omega = 16 rad/s) by the ratio alpha / (2 omega) + beta omega / 2,
// about 11 %, and the mesh's fastest modes far more.
constexpr const char* demo_scene = R"({
  "name": "beam_flap",
  "mesh": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0.2], "cells": [3, 6, 19]}, "order": 1},
  "material": {"young": 300e3, "poisson": 0.35, "density": 1070},
  "model": "corotational",
  "gravity": [9.81, 0, 0],
  "dirichlet": [{"region": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0]}}}],
  "cuts": [{"rectangle": {"origin": [-0.005, -0.005, 0.15], "edge1": [0.03, 0, 0], "edge2": [0, 0.07, 0]}}],
  "time": {"integrator": "newmark", "dt": 0.005, "steps": 300, "mass": "lumped", "rayleigh": [3, 0.002],
           "corotation": "frozen"},
  "output": {"every": 10}
})";

// @sect3{The CutDynamics class}
//
// The skeleton of chapter 4 with DESIGN.md's do_timestep: setup_system now also builds the
// mass and the integrator, and solve becomes a loop of time steps.
class CutDynamics {
public:
  CutDynamics(kerf::Scene scene, kerf::CommandLine options) : scene_(std::move(scene)), options_(std::move(options)) {}
  void run();

private:
  void make_mesh();
  void apply_cut();
  void setup_system();
  void assemble_system();
  void setup_linear_integrator();
  void setup_nonlinear_integrator();
  void do_timestep(int step);
  void check_state(int step) const;
  void output_step(int step);
  void output_results() const;
  // The sign enrichment the model takes: chapter 5's classification's with a "crack_tip" field
  // (the model checks that it is the one its branch functions were built with), chapter 4's without.
  const kerf::SurfaceEnrichment& enrichment() const { return crack_tip_ ? crack_tip_->sign_enrichment() : enrichment_; }
  void report(const std::string& line) const {
    if (!options_.quiet) std::cout << line << '\n';
  }

  kerf::Scene scene_;
  kerf::CommandLine options_;
  kerf::TetMesh mesh_;
  kerf::BoundaryFaces boundary_;
  std::unique_ptr<kerf::CutSurfaces> cuts_;
  kerf::MeshPieces pieces_;
  kerf::SurfaceEnrichment enrichment_;
  std::unique_ptr<kerf::SceneCrackTip> crack_tip_; // chapter 5's functions, if the scene asks: the model refers to them
  kerf::PieceRuleFunction rule_;
  std::unique_ptr<kerf::CutXfemModel> model_;
  kerf::DofMap dofs_;
  Eigen::SparseMatrix<double> M_, K_; // mass and linear stiffness on all 3 (N + M) DOFs
  Eigen::VectorXd f_ext_;             // the loads that go with the mass

  // The two ways to step: the library's linear integrators on a LinearDynamicSystem (linear
  // model, still clamps), or the nonlinear Newmark step (corotated model, or moving clamps).
  kerf::LinearDynamicSystem linear_;
  kerf::NonlinearDynamicSystem nonlinear_;
  std::unique_ptr<kerf::NonlinearNewmarkIntegrator> nonlinear_newmark_;
  std::unique_ptr<kerf::SparseAssembler> tangent_assembler_; // all DOFs free: the full tangent
  std::function<void(kerf::DynamicState&)> step_;            // advances the state and books its energy
  kerf::DynamicState state_;
  kerf::EnergyAccount account_;
  double energy_scale_ = 0.0;    // E_0 + sum of |work| per step: the divergence bound's measure
  int newton_failures_ = 0;      // steps whose Newton iteration missed the tolerance
  long total_iterations_ = 0;    // linear solves of the nonlinear steps

  // Output along the run.
  Eigen::MatrixXd probe_points_;
  std::ofstream energy_csv_, history_csv_;
  std::vector<std::pair<double, std::filesystem::path>> frames_;
};

// @sect4{CutDynamics::make_mesh}
//
// As in chapter 4.
void CutDynamics::make_mesh() {
  mesh_ = kerf::make_scene_mesh(scene_, &std::cerr);
  boundary_ = kerf::boundary_faces(mesh_);
  report("mesh: " + std::to_string(mesh_.num_nodes()) + " nodes, " + std::to_string(mesh_.num_tets()) +
         (mesh_.order() == 1 ? " Tet4" : " Tet10") + ", model " + scene_.model);
}

// @sect4{CutDynamics::apply_cut}
//
// As in chapter 4: the surfaces, the pieces of every tet they cut, and the enrichment; with a
// "crack_tip" field, chapter 5's (scene_crack_tip.hpp): the sign enrichment of its node
// classification and the branch functions where a cut ends inside the body. Without the field
// chapter 4's enrichment, as before chapter 5 (chapter 5's default would be the branch
// functions).
void CutDynamics::apply_cut() {
  cuts_ = std::make_unique<kerf::CutSurfaces>(kerf::scene_cut_surfaces(scene_, &std::cerr));
  pieces_ = kerf::scene_mesh_pieces(scene_, mesh_, *cuts_, &std::cerr);
  if (scene_.crack_tip.given) {
    crack_tip_ = std::make_unique<kerf::SceneCrackTip>(scene_, mesh_, pieces_, *cuts_, &std::cerr);
    report("crack tip: " + std::to_string(crack_tip_->num_branch_nodes()) + " branch nodes");
  } else {
    enrichment_ = kerf::make_surface_enrichment(mesh_, pieces_);
  }
  report("cut: " + std::to_string(pieces_.count(kerf::SurfaceCutState::completely_cut)) + " tets completely cut, " +
         std::to_string(pieces_.count(kerf::SurfaceCutState::partially_cut)) + " partially cut; " +
         std::to_string(enrichment().num_enrichments()) + " enrichments");
}

// @sect4{CutDynamics::setup_system}
//
// Chapter 4's rule and model, and then what dynamics adds. The unknowns: chapter 4 refused a
// piece that no Dirichlet condition holds, because a static solve has no answer then; with a
// mass a freed piece simply moves (M_ff is positive definite whatever the clamps), so we build
// the DofMap without that check and say how many pieces fly free.
//
// The mass is the scene's choice (scene_dynamic_mass.hpp): the consistent XFEM mass of eqs.
// 76-80, or a lumped one, by default the per-piece "virtual tet" lumping (as in Song, Areias and
// Belytschko 2006) that cures eqs. 81-82, with the loads that go with it: with eqs. 81-82 a freed
// piece moves with the inertia of its whole element, with the per-piece lumping it falls at g.
// Crack-tip functions get their rows of the mass and of the body force (lumped_mass.hpp: the
// branch rows are the consistent ones).
void CutDynamics::setup_system() {
  rule_ = kerf::scene_piece_rule(scene_, mesh_.order());
  model_ = std::make_unique<kerf::CutXfemModel>(mesh_, scene_.material, pieces_, enrichment(), rule_,
                                                crack_tip_ ? crack_tip_->tip_functions() : nullptr);
  if (options_.moments_out) {
    kerf::write_piece_moments_csv(*options_.moments_out, mesh_, pieces_, rule_);
    report("wrote " + options_.moments_out->string());
  }
  dofs_ = kerf::make_cut_xfem_dof_map(*model_, kerf::scene_held_nodes(scene_, mesh_, &std::cerr));
  if (dofs_.num_free == 0) throw kerf::InputError(scene_.source.string(), "dirichlet", "every DOF is prescribed: nothing to solve");
  const std::size_t free_pieces = kerf::cut_xfem_unheld_pieces(*model_, dofs_).size();
  report("system: " + std::to_string(dofs_.num_free) + " unknowns (" + std::to_string(3 * enrichment().num_enrichments()) +
         " of them enriched); " + std::to_string(free_pieces) + " pieces held by no clamp");
  if (model_->num_branch_nodes() > 0 && scene_.time.mass == "schoch_eq_81_82")
    throw kerf::InputError(scene_.source.string(), "time.mass",
                           "eqs. 81-82 give the crack-tip functions no mass: use \"lumped\" or \"consistent\" with a crack_tip field");
  M_ = kerf::scene_cut_xfem_mass(scene_, *model_, rule_);
  // The body's mass as the mass matrix sees it: e^T M e for e a unit translation of the nodes
  // along x (the enriched DOFs at 0), rho V for every scheme of lumped_mass.hpp.
  report("mass: " + scene_.time.mass + ", " + std::to_string(kerf::translation_mass(M_, mesh_.num_nodes())) + " kg");
}

// @sect4{CutDynamics::assemble_system}
//
// The linear stiffness K^X on all DOFs (every DOF free, so that K_fc is there too: a moving
// clamp's velocity enters the damping force through it), and the loads that go with the mass.
void CutDynamics::assemble_system() {
  const kerf::DofMap all_free = kerf::make_dof_map(model_->num_dof_nodes(), {});
  tangent_assembler_ = std::make_unique<kerf::SparseAssembler>(model_->assembly_slots(), all_free);
  Eigen::VectorXd unused = Eigen::VectorXd::Zero(all_free.num_free);
  model_->assemble_linear_stiffness(*tangent_assembler_, unused);
  K_ = tangent_assembler_->matrix();
  f_ext_ = kerf::scene_cut_xfem_dynamic_loads(scene_, *model_, boundary_, rule_);
}

// @sect4{CutDynamics::setup_linear_integrator}
//
// Linear XFEM with still clamps is M a + C v + K u = f (Schoch et al. eq. 25) with constant
// matrices: the dynamics area's integrators take it as it is, each factorising its matrix
// once. The central difference is explicit: its step must stay below 2 / omega_max, which it
// estimates by power iteration; we report the estimate and refuse a larger step unless the
// scene says "allow_unstable".
void CutDynamics::setup_linear_integrator() {
  const kerf::TimeSpec& time = scene_.time;
  linear_.M = M_;
  linear_.K = K_;
  linear_.C = kerf::rayleigh_damping(M_, K_, time.rayleigh[0], time.rayleigh[1]);
  linear_.dofs = dofs_;
  linear_.load = [f = f_ext_](double) { return f; };
  const auto stepping = [this](auto integrator) {
    step_ = [this, integrator](kerf::DynamicState& state) { kerf::add_step(account_, linear_, state, integrator->step(state)); };
  };
  if (time.integrator == "newmark") {
    stepping(std::make_shared<kerf::NewmarkIntegrator>(linear_, time.dt, kerf::NewmarkParameters{time.beta, time.gamma}, scene_.solver));
  } else if (time.integrator == "hht_alpha") {
    stepping(std::make_shared<kerf::HhtAlphaIntegrator>(linear_, time.dt, time.alpha, scene_.solver));
  } else if (time.integrator == "backward_euler") {
    stepping(std::make_shared<kerf::BackwardEulerIntegrator>(linear_, time.dt, scene_.solver));
  } else {
    // The integrator refuses a step above its estimate, or an estimate whose power iteration did
    // not converge (it errs on the unsafe side), unless forced; we say which, with the estimate.
    std::shared_ptr<kerf::CentralDifferenceIntegrator> explicit_step;
    try {
      explicit_step = std::make_shared<kerf::CentralDifferenceIntegrator>(linear_, time.dt, time.allow_unstable, scene_.solver);
    } catch (const std::invalid_argument&) {
      const double critical = kerf::CentralDifferenceIntegrator(linear_, time.dt, true, scene_.solver).critical_step();
      std::ostringstream problem;
      if (time.dt > critical)
        problem << "dt = " << time.dt << " s is above the central difference's critical step 2 / omega_max = " << critical
                << " s (estimated): it would blow up; take a smaller dt or set \"allow_unstable\": true";
      else
        problem << "the power iteration for omega_max did not converge, so the critical step is unknown (estimated " << critical
                << " s, which errs large); set \"allow_unstable\": true to step anyway";
      throw kerf::InputError(scene_.source.string(), "time.dt", problem.str());
    }
    std::ostringstream line;
    line << "central difference: critical step 2 / omega_max = " << explicit_step->critical_step() << " s (estimated), dt = " << time.dt << " s";
    report(line.str());
    stepping(explicit_step);
  }
  Eigen::VectorXd v0 = Eigen::VectorXd::Zero(3 * model_->num_dof_nodes());
  for (Eigen::Index v = 0; v < mesh_.num_nodes(); ++v) v0.segment<3>(3 * v) = time.initial_velocity;
  state_ = kerf::consistent_initial_state(kerf::ReducedDynamicSystem(linear_), Eigen::VectorXd::Zero(v0.size()), v0, 0.0, scene_.solver);
  account_ = kerf::start_energy_account(linear_, state_);
}

// @sect4{CutDynamics::setup_nonlinear_integrator}
//
// The corotated body (Schoch et al. eq. 40), or any body whose clamps move: the internal force is
// CutXfemModel::assemble's f_int(u) with its tangent, the elastic energy the corotated strain
// energy whose gradient f_int is, and the clamps follow the scene's motion
// (scene_prescribed_motion.hpp), with u, v and a the derivatives of one smooth ramp. The step
// (nonlinear_newmark.hpp) freezes the rotations at its start or iterates Newton, as the scene's
// "corotation" says; the Rayleigh beta multiplies the warped stiffness R K R^T of the step's
// start, so it damps straining, not the flap's rigid swing.
void CutDynamics::setup_nonlinear_integrator() {
  const kerf::TimeSpec& time = scene_.time;
  if (time.integrator != "newmark")
    throw kerf::InputError(scene_.source.string(), "time.integrator",
                           "\"" + time.integrator + "\" is stepped here for the linear model with still clamps only; the corotational "
                           "model and moving clamps take \"newmark\"");
  const bool corotated = scene_.model == "corotational";
  const kerf::RotationMethod rotation = kerf::scene_quasi_static_settings(scene_).rotation;
  nonlinear_.M = M_;
  nonlinear_.rayleigh_alpha = time.rayleigh[0];
  nonlinear_.rayleigh_beta = time.rayleigh[1];
  nonlinear_.dofs = dofs_;
  // CG's Jacobi scaling in the part basis (part_basis.hpp): a piece the cut freed is never
  // moved by the corrections of the body, and a thin part never shares a scale with a thick one.
  if (scene_.solver.basis == "parts") nonlinear_.solver_basis = kerf::cut_body_preconditioner_basis(*model_, dofs_);
  nonlinear_.load = [f = f_ext_](double) { return f; };
  nonlinear_.motion = [this](double t) { return kerf::scene_prescribed_motion(scene_, mesh_, model_->num_dof_nodes(), t); };
  if (corotated) {
    nonlinear_.internal_force = [this, rotation](const Eigen::VectorXd& u, kerf::CorotationalTangent tangent, Eigen::VectorXd& f_int,
                                                 const Eigen::SparseMatrix<double>** K) {
      Eigen::VectorXd unused = Eigen::VectorXd::Zero(u.size());
      if (K) tangent_assembler_->set_zero();
      model_->assemble(u, rotation, tangent, f_int, K ? tangent_assembler_.get() : nullptr, K ? &unused : nullptr);
      if (K) *K = &tangent_assembler_->matrix();
    };
    nonlinear_.elastic_energy = [this, rotation](const Eigen::VectorXd& u) { return model_->energy(u, true, rotation); };
  } else {
    nonlinear_.internal_force = [this](const Eigen::VectorXd& u, kerf::CorotationalTangent, Eigen::VectorXd& f_int,
                                       const Eigen::SparseMatrix<double>** K) {
      f_int = K_ * u;
      if (K) *K = &K_;
    };
    nonlinear_.elastic_energy = [this](const Eigen::VectorXd& u) { return 0.5 * u.dot(K_ * u); };
  }
  kerf::NonlinearNewmarkSettings settings;
  settings.newmark = {time.beta, time.gamma};
  settings.update = kerf::rotation_update_named(time.corotation, default_rotations);
  settings.tolerance = time.tolerance;
  // The steps' solver: the scene's, or by default Jacobi-preconditioned conjugate gradients to
  // time.tolerance, started from the last step's acceleration. The mass term makes a step's matrix
  // M + gamma dt C + beta dt^2 K far better conditioned than K alone, so CG needs a few dozen
  // cheap iterations, fewer than any factorisation costs: on the cut soft block of
  // figures/06_newmark/bench_newmark.md it beats a CHOLMOD factorisation per step, and CG with a
  // reused CHOLMOD factor (whose triangular solves cost more than the iterations they save),
  // from 1k to 100k tets.
  settings.solver = scene_.solver;
  if (!scene_.solver_given) {
    settings.solver.type = "cg-jacobi";
    settings.solver.tolerance = time.tolerance;
  }
  nonlinear_newmark_ = std::make_unique<kerf::NonlinearNewmarkIntegrator>(nonlinear_, time.dt, settings);
  step_ = [this](kerf::DynamicState& state) {
    const kerf::NonlinearStepReport step = nonlinear_newmark_->step(state);
    nonlinear_newmark_->add_step(account_, state, step);
    total_iterations_ += step.iterations;
    if (!step.converged) ++newton_failures_;
  };
  Eigen::VectorXd v0 = Eigen::VectorXd::Zero(3 * model_->num_dof_nodes());
  for (Eigen::Index v = 0; v < mesh_.num_nodes(); ++v) v0.segment<3>(3 * v) = time.initial_velocity;
  state_ = nonlinear_newmark_->initial_state(Eigen::VectorXd::Zero(v0.size()), v0, 0.0);
  account_ = nonlinear_newmark_->start_account(state_);
}

// @sect4{CutDynamics::check_state}
//
// A run that diverges stops at once, with the step named, before anything of that step is
// written: no NaN reaches a file. Divergence is a state that is not finite, or an energy
// kinetic + elastic above 100 times E_0 + the sum over the steps of |work done on the body|:
// the balance says the energy can never exceed E_0 + the work put in, so only an unstable
// integrator (the central difference above its limit, a Newmark pair outside the stable range)
// gets there. Chapter 7 checks the same, so the test is the dynamics area's (energy_account.hpp).
void CutDynamics::check_state(int step) const { kerf::check_bounded_state(state_, account_, energy_scale_, step); }

// @sect4{CutDynamics::do_timestep}
//
// One step of the integrator, the divergence check, and the step's lines of output.
void CutDynamics::do_timestep(int step) {
  const double work_before = account_.external_work;
  try {
    step_(state_);
  } catch (const kerf::InputError&) {
    throw;
  } catch (const std::exception& error) { // a solver that fails (a matrix no longer positive definite): say where
    throw std::runtime_error("step " + std::to_string(step) + " (t = " + std::to_string(state_.t) + " s): " + error.what());
  }
  state_.t = step * scene_.time.dt; // n dt, not dt added n times (its round-off would show in the CSV)
  energy_scale_ += std::abs(account_.external_work - work_before);
  check_state(step);
  output_step(step);
}

// @sect4{CutDynamics::output_step}
//
// energy.csv and the probes' history get a row every step; the pieces, drawn as in chapter 4
// with the cut open, are written every output.every steps (and at the last) into a .pvd series
// that ParaView plays.
void CutDynamics::output_step(int step) {
  kerf::write_energy_row(energy_csv_, step, state_.t, account_);
  if (history_csv_.is_open()) {
    Eigen::Index outside = 0;
    const kerf::TetField field = [this](Eigen::Index t, const Eigen::Vector3d& x) { return model_->displacement_at(state_.u, t, x); };
    const Eigen::MatrixXd values = kerf::evaluate_tet_field_at(mesh_, field, probe_points_, outside);
    kerf::write_probe_history_rows(history_csv_, step, state_.t, values);
    if (step == 0 && outside > 0)
      std::cerr << "warning: " << outside << " probes lie outside the mesh; their history is nan\n";
  }
  if (step % scene_.output_every == 0 || step == scene_.time.steps) {
    char name[64];
    std::snprintf(name, sizeof name, "_pieces_%06d.vtu", step);
    const std::filesystem::path frame = options_.out_dir / (scene_.name + name);
    kerf::write_cut_xfem_vtu(frame, *model_, state_.u);
    frames_.emplace_back(state_.t, frame);
    kerf::write_pvd(options_.out_dir / (scene_.name + "_pieces.pvd"), frames_);
  }
}

// @sect4{CutDynamics::output_results}
//
// After the last step: the probes where the run ended. The last step's pieces are the series'
// last frame, so nothing else is written here.
void CutDynamics::output_results() const {
  report("wrote " + (options_.out_dir / (scene_.name + "_pieces.pvd")).string() + " (" + std::to_string(frames_.size()) +
         " frames) and " + (options_.out_dir / "energy.csv").string());
  if (options_.probes_out) {
    kerf::sample_cut_xfem_probes(*options_.probes_in, *options_.probes_out, *model_, state_.u, &std::cerr);
    report("wrote " + options_.probes_out->string());
  }
}

// @sect4{CutDynamics::run}
//
// Chapter 4's steps, then the choice of stepper and the loop over time, with a progress line
// about once a second on long runs.
void CutDynamics::run() {
  using clock = std::chrono::steady_clock;
  const auto seconds_since = [](clock::time_point start) { return std::chrono::duration<double>(clock::now() - start).count(); };
  auto start = clock::now();
  make_mesh();
  apply_cut();
  setup_system();
  assemble_system();
  const bool moves = kerf::scene_dirichlet_moves(scene_);
  if (scene_.model == "linear" && !moves) setup_linear_integrator();
  else setup_nonlinear_integrator();
  const std::string rotations = kerf::rotation_update_name(kerf::rotation_update_named(scene_.time.corotation, default_rotations));
  report("integrator: " + scene_.time.integrator + (scene_.model == "corotational" ? ", rotations " + rotations : "") +
         ", dt = " + std::to_string(scene_.time.dt) + " s, " + std::to_string(scene_.time.steps) + " steps");
  report("setup: " + std::to_string(seconds_since(start)) + " s");

  std::filesystem::create_directories(options_.out_dir);
  energy_csv_.open(options_.out_dir / "energy.csv");
  if (!energy_csv_) throw kerf::InputError((options_.out_dir / "energy.csv").string(), "write", "cannot open the file");
  energy_csv_ << kerf::energy_csv_header;
  if (options_.probes_history) {
    probe_points_ = kerf::read_probes_csv(*options_.probes_in);
    history_csv_.open(*options_.probes_history);
    if (!history_csv_) throw kerf::InputError(options_.probes_history->string(), "write", "cannot open the file");
    history_csv_ << "step,t,probe,ux,uy,uz\n";
  }
  energy_scale_ = account_.kinetic + account_.elastic;
  check_state(0);
  output_step(0);

  start = clock::now();
  auto last_line = start;
  const int steps = scene_.time.steps;
  for (int step = 1; step <= steps; ++step) {
    do_timestep(step);
    if (!options_.quiet && (seconds_since(last_line) >= 1.0 || (step == steps && seconds_since(start) >= 1.0))) {
      const double rate = step / seconds_since(start);
      std::ostringstream line;
      line.precision(3);
      line << "step " << step << "/" << steps << " (t = " << state_.t << " s), " << rate << " steps/s, about " << (steps - step) / rate
           << " s left";
      report(line.str());
      last_line = clock::now();
    }
  }
  std::ostringstream line;
  line << "stepped " << steps << " steps in " << seconds_since(start) << " s";
  if (total_iterations_ > 0) line << ", " << total_iterations_ << " linear solves";
  line << "; energy: kinetic " << account_.kinetic << " J, elastic " << account_.elastic << " J, work " << account_.external_work
       << " J, dissipated " << account_.dissipated() << " J = damping " << account_.damping << " J + numerical ";
  // A closed form of the scheme on the linear path; what closes the balance for HHT-alpha and the nonlinear step.
  if (nonlinear_newmark_ || scene_.time.integrator == "hht_alpha") line << "(the rest of the balance) ";
  line << account_.numerical << " J";
  report(line.str());
  if (newton_failures_ > 0)
    std::cerr << "warning: " << scene_.source.string() << ": time.tolerance: the Newton iteration missed " << scene_.time.tolerance
              << " in " << newton_failures_ << " steps\n";
  output_results();
}

} // namespace chapter06

// @sect3{The main function}
//
// As in chapter 4, with --probes-history, and a scene that must ask for a time integrator:
// the static solve is chapters 1-5's.
int main(int argc, char** argv) {
  const std::string usage =
      "usage: 06_newmark [--scene FILE.json] [--probes IN.csv [--probes-out OUT.csv] [--probes-history FILE.csv]]\n"
      "                  [--moments-out FILE.csv] [--out DIR] [--quiet]\n"
      "Steps a cut elastic body in time (Newmark, HHT-alpha, backward Euler or the central difference), linear or\n"
      "corotational XFEM, consistent or lumped mass, Rayleigh damping, clamps that may move (Kerf, chapter 6).\n"
      "  --scene FILE.json         the scene, with a \"time\" field (default: the demo, a beam whose cut flap swings)\n"
      "  --probes IN.csv           points (header x,y,z) at which to write the displacement ...\n"
      "  --probes-out OUT.csv      ... at the last step (header x,y,z,ux,uy,uz)\n"
      "  --probes-history FILE.csv ... at every step from 0 (header step,t,probe,ux,uy,uz; probe 0-based)\n"
      "  --moments-out FILE.csv    the moments of every piece of every cut tet, as in chapter 4\n"
      "  --out DIR                 where energy.csv, the .vtu frames and their .pvd go (default: output)\n"
      "  --quiet                   no progress lines\n"
      "  --help                    this text\n";
  return kerf::run_guarded(
      argc, argv, "06_newmark", usage,
      [](const kerf::CommandLine& options) {
        const kerf::Scene scene = options.scene ? kerf::read_scene_file(*options.scene)
                                                : kerf::parse_scene(chapter06::demo_scene, "demo scene", ".");
        kerf::require_features(scene, kerf::SceneFeatures{.corotational = true, .cuts = true, .dynamics = true, .cut_quadrature = true, .crack_tip = true});
        if (scene.time.integrator == "static")
          throw kerf::InputError(scene.source.string(), "time.integrator",
                                 "\"static\" (or no \"time\" field) is the solve of chapters 1-5 (04_cut_quadrature); 06_newmark "
                                 "steps in time: give \"newmark\", \"hht_alpha\", \"backward_euler\" or \"central_difference\"");
        if (!(scene.material.density > 0.0))
          throw kerf::InputError(scene.source.string(), "material.density", "dynamics needs a positive density (kg/m^3): without mass there is no inertia");
        chapter06::CutDynamics problem(scene, options);
        problem.run();
      },
      kerf::CommandLineFeatures{.moments_out = true, .probes_history = true});
}
