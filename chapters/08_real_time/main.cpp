/* Kerf, chapter 8: the liver cut in real time.

   Build:   cmake --preset release && cmake --build --preset release --target 08_real_time

   Sample runs:
     xvfb-run -a 08_real_time                    (the demo: frames need a display, xvfb-run gives one)
     08_real_time --scene examples/07_liver_cut.json --out output/liver_08
     08_real_time --tets 3000 --out output/real_time_3k
     xvfb-run -a 08_real_time --interactive      (hold Shift and drag with the left button to cut)

   Description: chapter 7's liver and blade, stepped by chapter 8's time step
   (dynamics/quasi_newton_newmark.hpp): Newmark's step for the corotated body written as the
   minimum of one energy, minimised by a few quasi-Newton (L-BFGS) iterations whose matrix, mass
   plus a scalar Laplacian, is factorised once and only grows when the blade adds enrichments.
   Chapter 7's scene files run unchanged; their "time.corotation" and "solver" are chapter 7's and
   are ignored here, and "time.iterations" (4 by default) sets the iterations a step.

          the simulation thread                 the window (this thread)
          ---------------------                 ------------------------
          step n: blade -> cut -> step          the mouse -> the blade's edge ------+
          sleep until n dt of wall time         draw the newest state published     |
          publish the state -------+            caption: step time, real-time factor|
                 ^                 |                                                 |
                 +-----------------)------ the edge, read at each step's start <----+
                                   +------> the newest frame (the window never waits)

   What is new:
   - the step: no tangent is assembled and no rotation is found from scratch; each of a few
     iterations is one pass over the pieces (corotation/corotated_pieces.hpp: forces, energy and
     warm-started rotations, four pieces at a time with vector instructions) and one solve with a
     factor made once (solve/growing_cholesky.hpp); a step that would create energy is solved on;
   - a cut grows the factor instead of redoing it (QuasiNewtonNewmark::set_body);
   - the model of one cut is one immutable object, CutBody, shared between the thread that steps
     and the thread that draws: the window draws the body it was handed while the next is built;
   - real time: the simulation runs on its own thread at a fixed dt, paced by the wall clock,
     and publishes each state; the window draws the newest at whatever rate the display allows.
     Behind (a mesh too large for the machine), the physics keeps its dt and the window skips
     frames, and the program says so.
   Read chapter 7 first. */

// @sect3{Include files}
//
// New since chapter 7: the quasi-Newton step, its pieces and its growing factor, the threads.
#include "kerf/app/command_line.hpp"
#include "kerf/app/cut_run_log.hpp"
#include "kerf/app/input_error.hpp"
#include "kerf/app/organ.hpp"
#include "kerf/corotation/corotated_pieces.hpp"
#include "kerf/cut/blade_path.hpp"
#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/dynamics/energy_account.hpp"
#include "kerf/dynamics/quasi_newton_newmark.hpp"
#include "kerf/io/events_csv.hpp"
#include "kerf/render/cutting_window.hpp"
#include "kerf/render/organ_view.hpp"
#include "kerf/scene/scene.hpp"
#include "kerf/scene/scene_dynamic_mass.hpp"
#include "kerf/scene/scene_quadrature.hpp"
#include "kerf/scene/scene_quasi_static.hpp"
#include "kerf/xfem/blade_cut.hpp"
#include "kerf/xfem/cut_faces.hpp"
#include "kerf/xfem/cut_state_transfer.hpp"
#include "kerf/xfem/cut_xfem_mass.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"
#include "kerf/xfem/cut_xfem_output.hpp"
#include "kerf/xfem/hinged_fragments.hpp"
#include "kerf/xfem/split_tet_masses.hpp"
#include "kerf/xfem/surface_enrichment.hpp"
#include "kerf/xfem/visual_surface.hpp"

#include <vtkRenderWindow.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <thread>

namespace chapter08 {

using clock = std::chrono::steady_clock;

double seconds_since(clock::time_point start) { return std::chrono::duration<double>(clock::now() - start).count(); }

// @sect3{The demo scene}
//
// Chapter 7's tissue, support and damping (chapters/07_liver/main.cpp says where each number
// comes from) on the wedge-shaped liver (mesh/liver_wedge.hpp), whose right lobe lies at -x, on
// the left as an atlas shows it from the front; held at its back and its floor as chapter 7's,
// and under the left lobe, which rests on the stomach. The scalpel enters the right lobe from the
// side at 0.5 s, curves across both lobes, 8 to 9 cm deep, and leaves the left lobe's tip at
// 2.1 s; 3 s at 10 ms a step, a frame every 4 steps (25 a simulated second). Newmark's
// gamma = 0.55 with beta = (gamma + 1/2)^2 / 4 damps the modes of small tets and slivers that a
// step of four iterations cannot follow (the intro's "Modes the step cannot follow", (8.9)).
constexpr const char* demo_scene = R"({
  "name": "liver_real_time",
  "mesh": {"liver": {"tets": 10000, "shape": "wedge"}, "order": 1},
  "material": {"young": 4000, "poisson": 0.45, "density": 1060},
  "model": "corotational",
  "gravity": [0, 0, -9.81],
  "dirichlet": [{"region": {"box": {"min": [-1, 0.045, -0.01], "max": [1, 1, 1]}}},
                {"region": {"box": {"min": [-1, -0.01, -1], "max": [1, 1, -0.03]}}},
                {"region": {"box": {"min": [0, -1, -1], "max": [1, 1, -0.01]}}}],
  "blade": {"path": [{"time": 0.5, "edge": [[-0.12, -0.005, 0.09], [-0.12, -0.005, 0.0]]},
                     {"time": 1.3, "edge": [[0.0, 0.002, 0.09], [0.0, 0.002, 0.005]]},
                     {"time": 2.1, "edge": [[0.14, -0.012, 0.09], [0.14, -0.012, 0.012]]}]},
  "time": {"integrator": "newmark", "dt": 0.01, "steps": 300, "mass": "lumped", "rayleigh": [2, 0.01],
           "beta": 0.275625, "gamma": 0.55, "iterations": 4},
  "output": {"every": 20},
  "render": {"every": 4, "width": 960, "height": 720, "camera": {"azimuth": -110, "elevation": 25, "zoom": 1.3}}
})";

// @sect3{The body of one cut}
//
// Everything the model of the cut as it stands refers to, built together and never changed
// after: the cut surfaces, their pieces and enrichments, chapter 4's model (integrated anew only
// where the cut changed), the DOFs it holds, its mass and weight, and chapter 8's flat list of
// corotated linear pieces. The thread that draws keeps the body of the state it draws while the
// thread that steps builds the next one.
struct RebuildTimes {
  double pieces = 0.0, enrichment = 0.0, model = 0.0, mass = 0.0, corotated = 0.0; // seconds
};

struct CutBody {
  std::unique_ptr<kerf::CutSurfaces> cuts;
  std::unique_ptr<kerf::MeshPieces> pieces;
  std::unique_ptr<kerf::SurfaceEnrichment> enrichment;
  std::unique_ptr<kerf::CutXfemModel> model;
  kerf::DofMap dofs;
  std::unique_ptr<kerf::SplitTetMasses> masses;
  Eigen::SparseMatrix<double> M;
  Eigen::VectorXd weight;
  std::unique_ptr<kerf::CorotatedPieces> corotated;
  RebuildTimes times;

  // The body cut by `sheets`; `before` (the body of the shorter cut, or nullptr) lends the
  // pieces, quadrature and masses of every tet outside `grown`, the box of the sheets' new
  // triangles.
  CutBody(const kerf::Organ& organ, const kerf::Scene& scene, const kerf::PieceRuleFunction& rule, std::vector<kerf::TriangleSurface> sheets,
          const CutBody* before, const Eigen::AlignedBox3d& grown) {
    auto lap = clock::now();
    const auto take_lap = [&lap] {
      const double seconds = seconds_since(lap);
      lap = clock::now();
      return seconds;
    };
    cuts = std::make_unique<kerf::CutSurfaces>(std::move(sheets));
    pieces = std::make_unique<kerf::MeshPieces>(before ? kerf::recut_mesh_into_pieces(organ.mesh, *cuts, *before->pieces, grown)
                                                       : kerf::cut_mesh_into_pieces(organ.mesh, *cuts, organ.neighbours));
    times.pieces = take_lap();
    enrichment = std::make_unique<kerf::SurfaceEnrichment>(kerf::make_surface_enrichment(organ.mesh, *pieces));
    times.enrichment = take_lap();
    model = before ? std::make_unique<kerf::CutXfemModel>(*before->model, *pieces, *enrichment)
                   : std::make_unique<kerf::CutXfemModel>(organ.mesh, scene.material, *pieces, *enrichment, rule);
    // Chapter 7's rule for fragments that a held enrichment pins at a node or a line: let go.
    dofs = kerf::release_hinged_fragments(*model, kerf::make_cut_xfem_dof_map(*model, organ.held));
    times.model = take_lap();
    masses = std::make_unique<kerf::SplitTetMasses>(*model, rule, before ? before->masses.get() : nullptr);
    M = kerf::scene_cut_xfem_mass(scene, *model, *masses);
    // Gravity is the mass times a unit translation along g, as in chapter 7 (its setup_system
    // says why that is each lumping's own load).
    Eigen::VectorXd e_g = Eigen::VectorXd::Zero(M.rows());
    for (Eigen::Index v = 0; v < organ.mesh.num_nodes(); ++v) e_g.segment<3>(3 * v) = scene.gravity;
    weight = M * e_g;
    times.mass = take_lap();
    // The whole tets' data are the body before's, shared: only the special tets are built.
    corotated = std::make_unique<kerf::CorotatedPieces>(*model, scene.material, kerf::scene_quasi_static_settings(scene).rotation,
                                                        before ? before->corotated.get() : nullptr);
    times.corotated = take_lap();
  }

  // What the time step moves.
  kerf::QuasiNewtonBody step_body(const kerf::Scene& scene) const {
    return {corotated.get(), M, dofs, weight, model->mesh().num_nodes(), scene.time.rayleigh[0], scene.time.rayleigh[1]};
  }
};

// @sect3{What one step spent its time on}
//
// timings.csv's columns, in milliseconds: the blade (pull-back, sheet, crossing), the topology
// (a new CutBody, the state carried over, the step's factor grown), the step's passes over the
// pieces (local: forces, energies, rotations) and its solves (global), the rest of the step
// (vectors, the mass's products, the energy account), and what is not simulation: the files and
// the frames.
struct StepTimes {
  double blade = 0.0, topology = 0.0, local = 0.0, global = 0.0, other = 0.0, output = 0.0, render = 0.0;
  double simulate() const { return blade + topology + local + global + other; }
};

// @sect3{The newest state, handed from one thread to the other}
//
// What the window needs to draw a state: its body and its DOFs (a copy), and the numbers its
// caption shows. The simulation publishes a new one after every step; the window takes the
// newest when it is ready to draw and never waits for one.
struct Frame {
  std::shared_ptr<const CutBody> body;
  Eigen::VectorXd u;
  int step = 0;
  double t = 0.0;
  double step_ms = 0.0;           // the last second's mean simulate time of a step
  double real_time_factor = 1.0;  // simulated over wall-clock time, over the last second
  std::size_t crossed_tets = 0;
  std::optional<kerf::BladeEdge> blade; // the edge the step's cut used, if the hand held it
};

class Mailbox {
public:
  void post_blade(std::optional<kerf::BladeEdge> edge) {
    const std::lock_guard lock(mutex_);
    blade_ = std::move(edge);
  }
  std::optional<kerf::BladeEdge> blade() const {
    const std::lock_guard lock(mutex_);
    return blade_;
  }
  void publish(std::shared_ptr<const Frame> frame) {
    const std::lock_guard lock(mutex_);
    newest_ = std::move(frame);
  }
  std::shared_ptr<const Frame> newest() const {
    const std::lock_guard lock(mutex_);
    return newest_;
  }
  // The simulation's failure, handed to the window's thread, which reports it.
  void fail(std::exception_ptr error) {
    const std::lock_guard lock(mutex_);
    error_ = error;
    stop = true;
  }
  std::exception_ptr error() const {
    const std::lock_guard lock(mutex_);
    return error_;
  }
  std::atomic<bool> stop{false};

private:
  mutable std::mutex mutex_;
  std::optional<kerf::BladeEdge> blade_;
  std::shared_ptr<const Frame> newest_;
  std::exception_ptr error_;
};

// The real-time factor over the last second of wall-clock time: simulated seconds over wall
// seconds between the oldest and the newest step it remembers, and the mean simulate time.
class RealTimeMeter {
public:
  void add(double wall, double t, double simulate_ms) {
    samples_.push_back({wall, t, simulate_ms});
    while (samples_.size() > 2 && wall - samples_.front().wall > 1.0) samples_.pop_front();
  }
  double factor() const {
    if (samples_.size() < 2) return 1.0;
    const double wall = samples_.back().wall - samples_.front().wall;
    return wall > 0.0 ? (samples_.back().t - samples_.front().t) / wall : 1.0;
  }
  double mean_step_ms() const {
    double sum = 0.0;
    for (const Sample& s : samples_) sum += s.simulate_ms;
    return samples_.empty() ? 0.0 : sum / static_cast<double>(samples_.size());
  }

private:
  struct Sample {
    double wall, t, simulate_ms;
  };
  std::deque<Sample> samples_;
};

// @sect3{The RealTimeCut class}
//
// Chapter 7's LiverCut with chapter 8's step: a step is the blade's frame (which may rebuild
// the body) and one QuasiNewtonNewmark step; run() steps as fast as it can and writes every
// file, run_interactive() steps on a thread of its own, paced by the wall clock.
class RealTimeCut {
public:
  RealTimeCut(kerf::Scene scene, kerf::CommandLine options) : scene_(std::move(scene)), options_(std::move(options)) {}
  void run();
  void run_interactive();

private:
  void setup(bool need_view, bool on_screen);
  void setup_visual(bool need_view, bool on_screen);
  void rebuild();
  void step(int n, const kerf::BladeEdge* blade, bool blade_last);
  void simulate_in_real_time(Mailbox& mailbox, clock::time_point opened);
  void draw(const std::shared_ptr<const CutBody>& body, const Eigen::VectorXd& u, const std::optional<kerf::BladeEdge>& blade);
  void write_timings_row(int n, double wall);
  void report(const std::string& line) const {
    if (!options_.quiet) std::cout << line << '\n';
  }
  std::size_t crossed_tets() const { return blade_cut_->crossing().crossed_tets().size(); }

  kerf::Scene scene_;
  kerf::CommandLine options_;
  std::unique_ptr<kerf::Organ> organ_;
  kerf::PieceRuleFunction rule_;
  std::unique_ptr<kerf::BladePath> path_;
  std::unique_ptr<kerf::BladeCut> blade_cut_;
  int topology_changes_ = 0;

  // The body of the cut as it stands, the step, and the state.
  std::shared_ptr<const CutBody> body_;
  std::unique_ptr<kerf::QuasiNewtonNewmark> newmark_;
  kerf::DynamicState state_;
  kerf::EnergyAccount account_;
  double energy_scale_ = 0.0;
  kerf::QuasiNewtonStepReport last_report_;

  // Pictures: the fine visual surface, the view, and the skin split along the body's cut (once
  // per body, by the thread that draws).
  std::unique_ptr<kerf::VisualSurface> visual_;
  std::unique_ptr<kerf::OrganView> view_;
  std::shared_ptr<const CutBody> skin_body_; // the body skin_ was split for
  std::unique_ptr<kerf::CutSkin> skin_;
  std::vector<std::filesystem::path> png_frames_;

  // Output along the run.
  std::unique_ptr<kerf::CutRunLog> log_;
  std::ofstream timings_csv_, cuts_csv_, rebuilds_csv_, energy_csv_;
  StepTimes times_, total_;
  double slowest_step_ = 0.0, slowest_topology_step_ = 0.0;
  int iterations_ = 0;
};

// @sect4{RealTimeCut::setup}
//
// Chapter 7's organ, blade and pictures, the uncut body, and the step on it, from rest.
void RealTimeCut::setup(bool need_view, bool on_screen) {
  organ_ = std::make_unique<kerf::Organ>(scene_, options_.tets, &std::cerr);
  report(organ_->summary);
  blade_cut_ = std::make_unique<kerf::BladeCut>(organ_->mesh, scene_.blade.given ? scene_.blade.quad_length : 0.002, scene_.blade.samples);
  if (scene_.blade.given) path_ = std::make_unique<kerf::BladePath>(scene_.blade.path);
  setup_visual(need_view, on_screen);
  rule_ = kerf::scene_piece_rule(scene_, 1);
  body_ = std::make_shared<const CutBody>(*organ_, scene_, rule_, std::vector<kerf::TriangleSurface>{}, nullptr, Eigen::AlignedBox3d{});
  kerf::QuasiNewtonNewmarkSettings settings;
  settings.newmark = {scene_.time.beta, scene_.time.gamma};
  settings.iterations = scene_.time.iterations.value_or(4);
  if (settings.iterations == 0) settings.tolerance = scene_.time.tolerance;
  newmark_ = std::make_unique<kerf::QuasiNewtonNewmark>(scene_.time.dt, scene_.material, settings);
  try {
    newmark_->set_body(body_->step_body(scene_));
  } catch (const std::invalid_argument& error) {
    throw kerf::InputError(scene_.source.string(), "dirichlet", error.what());
  }
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(body_->M.rows());
  state_ = newmark_->initial_state(zero, zero, 0.0);
  account_ = newmark_->start_account(state_);
  energy_scale_ = std::max(1e-12, account_.kinetic + account_.elastic);
  std::ostringstream line;
  line << "system: " << body_->dofs.num_free << " unknowns before the cut; " << settings.iterations << " iterations a step"
       << (settings.iterations == 0 ? " (to time.tolerance)" : "") << "; blade quad length " << 1e3 * blade_cut_->quad_length() << " mm";
  report(line.str());
}

// @sect4{RealTimeCut::setup_visual}
//
// As chapter 7's (app/organ.hpp): the liver's fine implicit surface, the scene's render.surface,
// or the mesh's boundary, embedded once in the reference tets.
void RealTimeCut::setup_visual(bool need_view, bool on_screen) {
  if (!need_view) return;
  const kerf::TriangleSurface surface = kerf::scene_visual_surface(scene_, organ_->mesh);
  visual_ = std::make_unique<kerf::VisualSurface>(organ_->mesh, surface);
  view_ = std::make_unique<kerf::OrganView>(surface, kerf::organ_view_settings(scene_.render, on_screen));
}

// @sect4{RealTimeCut::rebuild}
//
// The blade crossed a tet: the body of the longer cut, the state carried over with the field
// unchanged (chapter 7's transfer: the standard DOFs as they are, each enrichment from the old
// piece that holds its part), and the step's factor grown by the new enrichments' rows. In
// cuts.csv (the batch run's), the check that nothing was lost or put in: the pieces' volume and
// the body's mass against the uncut mesh's, and the energies of the state in the old body and in
// the new one.
void RealTimeCut::rebuild() {
  auto next = std::make_shared<const CutBody>(*organ_, scene_, rule_, blade_cut_->surfaces(), body_.get(), blade_cut_->take_grown_box());
  double kinetic_before = 0.0, elastic_before = 0.0;
  if (cuts_csv_.is_open()) {
    const auto start = clock::now();
    kinetic_before = 0.5 * state_.v.dot(body_->M * state_.v);
    elastic_before = newmark_->elastic_energy(state_.u);
    times_.output += seconds_since(start);
  }
  auto lap = clock::now();
  const kerf::CutStateTransfer transfer(*body_->model, *next->model, kerf::BranchStateRule::fit, &next->dofs);
  state_.u = transfer(state_.u);
  state_.v = transfer(state_.v);
  state_.a = transfer(state_.a);
  const double transfer_seconds = seconds_since(lap);
  if (log_) log_->model_changed();
  lap = clock::now();
  newmark_->set_body(next->step_body(scene_));
  const double set_body_seconds = seconds_since(lap);
  body_ = std::move(next);
  ++topology_changes_;
  if (rebuilds_csv_.is_open()) {
    const RebuildTimes& r = body_->times;
    char row[256];
    std::snprintf(row, sizeof row, "%d,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f\n", topology_changes_, 1e3 * r.pieces, 1e3 * r.enrichment,
                  1e3 * r.model, 1e3 * r.mass,
                  1e3 * r.corotated, 1e3 * transfer_seconds, 1e3 * set_body_seconds);
    rebuilds_csv_ << row;
  }
  if (cuts_csv_.is_open()) {
    const auto start = clock::now();
    const double volume = body_->model->integrated_volume();
    const double mass = kerf::translation_mass(body_->M, organ_->mesh.num_nodes());
    char row[512];
    std::snprintf(row, sizeof row, "%d,%.17g,%zu,%ld,%ld,%.6e,%.6e,%.17g,%.17g,%.17g,%.17g\n", topology_changes_, state_.t, crossed_tets(),
                  static_cast<long>(body_->enrichment->num_enrichments()), static_cast<long>(body_->dofs.num_free),
                  volume / organ_->volume - 1.0, mass / (scene_.material.density * organ_->volume) - 1.0, kinetic_before,
                  0.5 * state_.v.dot(body_->M * state_.v), elastic_before, newmark_->elastic_energy(state_.u));
    cuts_csv_ << row;
    times_.output += seconds_since(start);
  }
}

// @sect4{RealTimeCut::step}
//
// One step from t_{n-1} to t_n: the blade's edge at t_n cuts the body as the step before left it
// (as in chapter 7), then chapter 8's step. The energy account and the check that it stays
// bounded (no NaN, no energy from nowhere) close it.
void RealTimeCut::step(int n, const kerf::BladeEdge* blade, bool blade_last) {
  times_ = {};
  auto start = clock::now();
  const bool crossed = blade_cut_->advance(*body_->model, *organ_->locator, state_.u, blade, blade_last);
  times_.blade = seconds_since(start);
  if (crossed) {
    start = clock::now();
    rebuild();
    times_.topology = seconds_since(start) - times_.output;
  }
  const double t_before = state_.t;
  const double work_before = account_.external_work;
  start = clock::now();
  try {
    last_report_ = newmark_->step(state_);
  } catch (const std::exception& error) {
    std::ostringstream where;
    where << "step " << n << " (t = " << t_before << " s to " << t_before + scene_.time.dt << " s): " << error.what();
    throw std::runtime_error(where.str());
  }
  newmark_->add_step(account_, state_, last_report_);
  const double seconds = seconds_since(start);
  times_.local = last_report_.pieces_seconds;
  times_.global = last_report_.solve_seconds;
  times_.other = seconds - times_.local - times_.global;
  iterations_ += last_report_.iterations;
  energy_scale_ += std::abs(account_.external_work - work_before);
  kerf::check_bounded_state(state_, account_, energy_scale_, n);
  slowest_step_ = std::max(slowest_step_, times_.simulate());
  if (crossed) slowest_topology_step_ = std::max(slowest_topology_step_, times_.simulate());
}

// @sect4{RealTimeCut::draw}
//
// As chapter 7's, the visual surface moved by the field of the piece each vertex lies in, the
// walls of the cut and the blade where it is; but the triangles the cut tore are split along it
// (kerf::CutSkin), not dropped, so that the wound's rim follows the cut.
void RealTimeCut::draw(const std::shared_ptr<const CutBody>& body, const Eigen::VectorXd& u, const std::optional<kerf::BladeEdge>& blade) {
  if (skin_body_ != body) {
    skin_ = std::make_unique<kerf::CutSkin>(*visual_, *body->cuts, *organ_->locator);
    skin_body_ = body;
  }
  view_->show(skin_->deform(kerf::xfem_visual_displacement(*body->model, u)), kerf::cut_face_surface(*body->model, u), blade);
}

// @sect4{RealTimeCut::write_timings_row}
void RealTimeCut::write_timings_row(int n, double wall) {
  char row[512];
  std::snprintf(row, sizeof row, "%d,%.17g,%.6f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%d,%.3e,%ld,%zu,%d\n", n, state_.t, wall,
                1e3 * times_.simulate(), 1e3 * times_.blade, 1e3 * times_.topology, 1e3 * times_.local, 1e3 * times_.global,
                1e3 * times_.other, 1e3 * times_.output, 1e3 * times_.render, last_report_.iterations, last_report_.relative_gradient, static_cast<long>(body_->dofs.num_free),
                crossed_tets(), times_.topology > 0.0 ? 1 : 0);
  timings_csv_ << row;
}

constexpr const char* timings_header =
    "step,t,wall_s,simulate_ms,blade_ms,topology_ms,local_ms,global_ms,other_ms,output_ms,render_ms,iterations,relative_gradient,unknowns,crossed_tets,"
    "topology_changed\n";

// @sect4{RealTimeCut::run}
//
// The batch run: every step as fast as it goes, every file, a frame every render.every steps.
void RealTimeCut::run() {
  const auto setup_start = clock::now();
  setup(scene_.render.every > 0, false);
  // As in chapter 7: a blade that starts in the tissue would cut from nowhere.
  if (path_) kerf::require_blade_starts_outside(*body_->model, *organ_->locator, *path_, scene_.blade.samples, scene_.source.string());
  report("setup: " + std::to_string(seconds_since(setup_start)) + " s");
  const int steps = scene_.time.steps;
  log_ = std::make_unique<kerf::CutRunLog>(kerf::CutRunLogSettings{options_.out_dir, scene_.name, scene_.output_every, steps,
                                                                   organ_->mean_edge, options_.probes_in, options_.probes_history},
                                           *organ_->locator);
  timings_csv_ = kerf::open_csv(options_.out_dir / "timings.csv", timings_header);
  cuts_csv_ = kerf::open_csv(options_.out_dir / "cuts.csv",
                             "change,t,crossed_tets,enrichments,unknowns,volume_error,mass_error,kinetic_before,kinetic_after,"
                             "elastic_before,elastic_after\n");
  // What a change of topology spends its time on: the new body's pieces (recut), enrichment, model
  // (and DOF map), mass and corotated pieces; the state's transfer; the step's set_body.
  rebuilds_csv_ = kerf::open_csv(options_.out_dir / "rebuilds.csv", "change,pieces_ms,enrichment_ms,model_ms,mass_ms,corotated_ms,transfer_ms,set_body_ms\n");
  log_->write(0, 0.0, *body_->model, *body_->cuts, state_.u, account_);
  const auto start = clock::now();
  auto last_line = start;
  for (int n = 1; n <= steps; ++n) {
    const double t = n * scene_.time.dt;
    const std::optional<kerf::BladeEdge> blade = path_ ? std::optional(path_->edge_at(t)) : std::nullopt;
    step(n, blade ? &*blade : nullptr, path_ && t >= path_->end_time());
    const double wall = seconds_since(start);
    auto output_start = clock::now();
    log_->write(n, state_.t, *body_->model, *body_->cuts, state_.u, account_);
    times_.output += seconds_since(output_start);
    if (view_ && (n % scene_.render.every == 0 || n == steps)) {
      const auto render_start = clock::now();
      draw(body_, state_.u, blade);
      char name[64];
      std::snprintf(name, sizeof name, "_frame_%06d.png", n);
      png_frames_.push_back(options_.out_dir / "frames" / (scene_.name + name));
      view_->write_png(png_frames_.back());
      times_.render = seconds_since(render_start);
    }
    write_timings_row(n, wall);
    for (auto [sum, part] : {std::pair{&total_.blade, times_.blade}, {&total_.topology, times_.topology}, {&total_.local, times_.local},
                             {&total_.global, times_.global}, {&total_.other, times_.other}, {&total_.output, times_.output},
                             {&total_.render, times_.render}})
      *sum += part;
    if (!options_.quiet && (seconds_since(last_line) >= 1.0 || n == steps)) {
      std::ostringstream line;
      line.precision(3);
      line << "step " << n << "/" << steps << " (t = " << state_.t << " s): " << crossed_tets() << " tets cut, " << body_->dofs.num_free
           << " unknowns; " << 1e3 * total_.simulate() / n << " ms a step simulating";
      report(line.str());
      last_line = clock::now();
    }
  }
  const double wall = seconds_since(start);
  std::ostringstream line;
  line.precision(3);
  line << "stepped " << steps << " steps in " << wall << " s; per step: " << 1e3 * total_.simulate() / steps << " ms simulating (blade "
       << 1e3 * total_.blade / steps << ", topology " << 1e3 * total_.topology / steps << ", local " << 1e3 * total_.local / steps
       << ", global " << 1e3 * total_.global / steps << ", other " << 1e3 * total_.other / steps << "), output " << 1e3 * total_.output / steps
       << ", render " << 1e3 * total_.render / steps << "; " << static_cast<double>(iterations_) / steps << " iterations a step; slowest step "
       << 1e3 * slowest_step_ << " ms, slowest topology step " << 1e3 * slowest_topology_step_ << " ms";
  report(line.str());
  std::ostringstream cut;
  cut << "cut: " << crossed_tets() << " tets crossed, " << topology_changes_ << " topology changes, " << blade_cut_->sheets().size()
      << " sheets, " << body_->enrichment->num_enrichments() << " enrichments; " << kerf::energy_summary(account_);
  report(cut.str());
  if (options_.probes_out) {
    kerf::sample_cut_xfem_probes(*options_.probes_in, *options_.probes_out, *body_->model, state_.u, &std::cerr);
    report("wrote " + options_.probes_out->string());
  }
  report("wrote " + log_->pvd().string() + " (" + std::to_string(log_->num_frames()) +
         " frames), energy.csv, opening.csv, cuts.csv and timings.csv in " + options_.out_dir.string());
  for (const std::string& line : kerf::write_run_animation(png_frames_, scene_, options_.out_dir)) report(line);
}

// @sect4{RealTimeCut::simulate_in_real_time}
//
// The simulation's thread: step n is computed, then waits until n dt of wall-clock time has
// passed since the window opened, then is published. A step that ends late is published at once
// and the next one starts at once: the physics never skips a step and never changes dt; the
// window simply draws fewer of them. Once a second, if the last second's real-time factor fell
// below 0.95, it says so.
void RealTimeCut::simulate_in_real_time(Mailbox& mailbox, clock::time_point opened) {
  RealTimeMeter meter;
  double last_warning = -1e9;
  const double dt = scene_.time.dt;
  for (int n = 1; !mailbox.stop; ++n) {
    const std::optional<kerf::BladeEdge> blade = mailbox.blade();
    step(n, blade ? &*blade : nullptr, false);
    const auto output_start = clock::now();
    kerf::write_energy_row(energy_csv_, n, state_.t, account_);
    times_.output = seconds_since(output_start);
    const auto due = opened + std::chrono::duration_cast<clock::duration>(std::chrono::duration<double>(n * dt));
    if (clock::now() < due) std::this_thread::sleep_until(due);
    const double wall = seconds_since(opened);
    write_timings_row(n, wall);
    meter.add(wall, state_.t, 1e3 * times_.simulate());
    auto frame = std::make_shared<Frame>();
    frame->body = body_;
    frame->u = state_.u;
    frame->step = n;
    frame->t = state_.t;
    frame->step_ms = meter.mean_step_ms();
    frame->real_time_factor = meter.factor();
    frame->crossed_tets = crossed_tets();
    frame->blade = blade;
    mailbox.publish(std::move(frame));
    if (wall >= 1.0 && meter.factor() < 0.95 && wall - last_warning >= 2.0) {
      std::fprintf(stderr,
                   "warning: behind real time: %.2f simulated seconds a second (%.1f ms a step for a dt of %.1f ms); the physics keeps its "
                   "dt, the window skips frames\n",
                   meter.factor(), meter.mean_step_ms(), 1e3 * dt);
      last_warning = wall;
    }
  }
}

// @sect4{RealTimeCut::run_interactive}
//
// The window on this thread, the simulation on its own. Every tick of the window (15 ms, or
// between scripted events) hands the blade under the mouse to the simulation and draws the newest
// state it published, with a caption: how to cut, the step time and the real-time factor. A
// script (--events, keyed by seconds since the window opened) stands in for the hand in tests.
void RealTimeCut::run_interactive() {
  setup(true, true);
  std::filesystem::create_directories(options_.out_dir);
  timings_csv_ = kerf::open_csv(options_.out_dir / "timings.csv", timings_header);
  energy_csv_ = kerf::open_csv(options_.out_dir / "energy.csv", kerf::energy_csv_header);
  const std::vector<kerf::ScriptedEvent> script =
      options_.events ? kerf::read_events_csv(*options_.events, kerf::EventClock::time) : std::vector<kerf::ScriptedEvent>{};
  const double depth = path_ ? (path_->keyframes().front().edge.end - path_->keyframes().front().edge.start).norm() : 0.06;
  kerf::CuttingWindow window(*view_, depth);
  const std::string instructions = "Shift + drag: cut   drag: turn   q: quit";
  view_->caption(instructions);
  draw(body_, state_.u, std::nullopt);
  view_->window().Render();

  Mailbox mailbox;
  const auto opened = clock::now();
  std::thread simulation([&] {
    try {
      simulate_in_real_time(mailbox, opened);
    } catch (...) {
      mailbox.fail(std::current_exception());
    }
  });
  std::shared_ptr<const Frame> drawn;
  int frames_drawn = 0;
  const auto tick = [&] {
    mailbox.post_blade(window.blade());
    const std::shared_ptr<const Frame> frame = mailbox.newest();
    if (!frame || frame == drawn) return;
    draw(frame->body, frame->u, frame->blade);
    char caption[256];
    std::snprintf(caption, sizeof caption, "%s\nt = %.2f s, step %d: %.1f ms a step, real-time factor %.2f, %zu tets cut", instructions.c_str(),
                  frame->t, frame->step, frame->step_ms, frame->real_time_factor, frame->crossed_tets);
    view_->caption(caption);
    view_->window().Render();
    drawn = frame;
    ++frames_drawn;
  };
  if (script.empty()) {
    report("interactive: " + instructions);
    window.run(15, [&] {
      tick();
      if (mailbox.stop) window.close();
    });
  } else {
    // Each event is delivered once its time since the window opened has come, as the window
    // system would deliver it, between the window's ticks; the run ends with the script.
    std::size_t next = 0;
    while (!mailbox.stop && !window.closed() && next < script.size()) {
      for (; next < script.size() && script[next].at <= seconds_since(opened); ++next) window.deliver(script[next]);
      tick();
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
  }
  mailbox.stop = true;
  simulation.join();
  if (mailbox.error()) std::rethrow_exception(mailbox.error());
  const double wall = seconds_since(opened);
  std::ostringstream line;
  line.precision(4);
  line << "real time: " << state_.t << " s simulated in " << wall << " s of wall-clock time (factor " << state_.t / wall << "); "
       << frames_drawn << " frames drawn (" << frames_drawn / wall << " a second); " << crossed_tets() << " tets cut in " << topology_changes_
       << " topology changes";
  if (!script.empty()) line << "; played " << script.size() << " events";
  report(line.str());
}

} // namespace chapter08

// @sect3{The main function}
//
// As chapter 7's, with its refusals, and chapter 8's own: Tet4 only (the pieces are linear),
// no branch functions, the corotational model, nodes held still.
int main(int argc, char** argv) {
  const std::string usage =
      "usage: 08_real_time [--scene FILE.json] [--tets N] [--interactive [--events FILE.csv]] [--probes IN.csv [--probes-out OUT.csv] "
      "[--probes-history FILE.csv]]\n"
      "                    [--out DIR] [--quiet]\n"
      "Cuts a liver with a moving blade in real time: chapter 7's cut, stepped by a few quasi-Newton iterations on a factor made once and\n"
      "grown at each cut; in a window, on its own thread paced by the wall clock (Kerf, chapter 8).\n"
      "  --scene FILE.json         the scene (default: the demo; chapter 7's scene files run unchanged)\n"
      "  --tets N                  the liver's size in tets (default: the scene's, 10000 in the demo)\n"
      "  --interactive             a window in which Shift + left drag cuts, simulated in real time (needs a display)\n"
      "  --events FILE.csv         with --interactive: play these events (header time,event,x,y,shift; time in s since the window opened)\n"
      "  --probes IN.csv           points (header x,y,z) at which to write the displacement ...\n"
      "  --probes-out OUT.csv      ... at the last step (header x,y,z,ux,uy,uz)\n"
      "  --probes-history FILE.csv ... at every step from 0 (header step,t,probe,ux,uy,uz; probe 0-based)\n"
      "  --out DIR                 where timings.csv, energy.csv, opening.csv, cuts.csv, the .vtu frames and the PNG frames go "
      "(default: output)\n"
      "  --quiet                   no progress lines\n"
      "  --help                    this text\n"
      "PNG frames need an X display: run under xvfb-run -a without one, or set \"render\": {\"every\": 0}.\n";
  return kerf::run_guarded(
      argc, argv, "08_real_time", usage,
      [](const kerf::CommandLine& options) {
        kerf::Scene scene = options.scene ? kerf::read_scene_file(*options.scene) : kerf::parse_scene(chapter08::demo_scene, "demo scene", ".");
        kerf::require_features(scene, kerf::SceneFeatures{.corotational = true, .cuts = true, .dynamics = true, .cut_quadrature = true,
                                                          .crack_tip = true, .organ = true, .real_time = true});
        kerf::require_blade_scene(scene, "08_real_time", "chapter 8's quasi-Newton Newmark step", options.interactive);
        const std::string file = scene.source.string();
        if (scene.mesh.order != 1)
          throw kerf::InputError(file, "mesh.order", "08_real_time's pieces are linear: Tet4 only (chapter 7 cuts Tet10)");
        if (scene.crack_tip.given)
          throw kerf::InputError(file, "crack_tip", "08_real_time's pieces are linear: no branch functions (chapter 7 has them)");
        if (scene.model != "corotational")
          throw kerf::InputError(file, "model", "08_real_time's step is corotational (chapter 7 steps the linear model)");
        if (!scene.traction.empty()) throw kerf::InputError(file, "traction", "08_real_time's load is gravity alone");
        for (std::size_t i = 0; i < scene.dirichlet.size(); ++i)
          if (scene.dirichlet[i].displacement.norm() > 0.0 || scene.dirichlet[i].has_rotation || scene.dirichlet[i].from_file)
            throw kerf::InputError(file, "dirichlet[" + std::to_string(i) + "]",
                                   "08_real_time holds nodes still (chapter 7 moves them as prescribed)");
        if (!scene.time.corotation.empty() || scene.solver_given)
          std::cerr << "warning: " << file << ": " << (scene.solver_given ? "solver" : "time.corotation")
                    << ": chapter 7's step; 08_real_time steps with its own (time.iterations) and ignores it\n";
        chapter08::RealTimeCut problem(scene, options);
        if (options.interactive) problem.run_interactive();
        else problem.run();
      },
      kerf::CommandLineFeatures{.moments_out = false, .probes_history = true, .organ = true});
}
