/* Kerf, chapter 7: a liver cut by a moving blade while it moves (not yet in real time: see the results).

   Build:   cmake --preset release && cmake --build --preset release --target 07_liver

   Sample runs:
     xvfb-run -a 07_liver                        (the demo: frames need a display, xvfb-run gives one)
     07_liver --scene examples/07_liver_cut.json --out output/liver
     07_liver --tets 3000 --out output/liver_3k
     xvfb-run -a 07_liver --interactive          (drag with the left mouse button to cut)

   Description: a liver of our own (mesh/liver_shape.hpp: two lobes, 0.20 x 0.15 x 0.10 m),
   meshed by CGAL Mesh_3 into about 10 000 Tet4, liver tissue (E = 4 kPa, nu = 0.45,
   rho = 1060 kg/m^3), held at the back where the ligaments and the vena cava tie it to the
   diaphragm and resting on the organs beneath its back half. Gravity pulls it down from rest;
   a scalpel, its edge upright, enters the right lobe from the side at 0.5 s, cuts across it
   6 cm deep, and stops inside the organ at 1.7 s; the front half sags and the wound gapes.
   2.5 s of corotational Newmark at 10 ms a step.

          blade edge (world)                    the cut in the reference configuration
              |  ---> moves along -x              +--------------------------+
              |                                    | sheet of swept quads      |  front: the blade's
       ~~~~~~~|~~~~~~~~  liver top                 |  (pulled back)            |  last edge and the
              |                                    +--------------------------+  path of its tip
              +  tip 6 cm deep

   What is new:
   - the cut is not given: it grows while the body moves. Each step the blade's edge is pulled
     back into the reference configuration (xfem/blade_pull_back.hpp) and extends a sheet of
     quads (cut/cut_sheet.hpp), Gutierrez and Ramos's semi-progressive cut decides which tets the
     sheet has crossed (cut/semi_progressive_cut.hpp), and only when a tet becomes crossed is the
     model rebuilt on the longer cut, the state carried over with the field unchanged (with a
     "crack_tip" field: fitted near the front, xfem/cut_state_transfer.hpp);
   - pictures: a fine visual surface (xfem/visual_surface.hpp) and the walls of the cut
     (xfem/cut_faces.hpp), drawn from a fixed camera (render/organ_view.hpp), a PNG per frame
     and an animated PNG of them all (io/animated_png.hpp);
   - a window in which the mouse is the blade (--interactive);
   - chapter 6's step, checked: solved again with the rotations of its end where they lagged
     (nonlinear_newmark.hpp, RotationUpdate::checked), for the pieces the blade sets turning.
   Read chapters 1-6 first. */

// @sect3{Include files}
//
// New since chapter 6: the liver, the blade and its cut, the transfer of the state, and the
// render area (which needs a display, so chapters 1-6 do not link it).
#include "kerf/app/command_line.hpp"
#include "kerf/app/cut_run_log.hpp"
#include "kerf/app/input_error.hpp"
#include "kerf/app/organ.hpp"
#include "kerf/cut/blade_path.hpp"
#include "kerf/cut/cut_sheet.hpp"
#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/cut/semi_progressive_cut.hpp"
#include "kerf/dynamics/energy_account.hpp"
#include "kerf/dynamics/nonlinear_newmark.hpp"
#include "kerf/dynamics/part_basis.hpp"
#include "kerf/io/animated_png.hpp"
#include "kerf/io/probes_csv.hpp"
#include "kerf/io/write_vtu.hpp"
#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/mesh/implicit_surface_mesh.hpp"
#include "kerf/mesh/liver_mesh.hpp"
#include "kerf/mesh/liver_shape.hpp"
#include "kerf/mesh/point_locator.hpp"
#include "kerf/mesh/read_surface.hpp"
#include "kerf/mesh/tet_neighbours.hpp"
#include "kerf/mesh/tet_quality.hpp"
#include "kerf/io/events_csv.hpp"
#include "kerf/render/cutting_window.hpp"
#include "kerf/render/organ_view.hpp"
#include "kerf/scene/scene.hpp"
#include "kerf/scene/scene_crack_tip.hpp"
#include "kerf/scene/scene_dynamic_mass.hpp"
#include "kerf/scene/scene_mesh.hpp"
#include "kerf/scene/scene_quadrature.hpp"
#include "kerf/scene/scene_quasi_static.hpp"
#include "kerf/xfem/blade_cut.hpp"
#include "kerf/xfem/blade_pull_back.hpp"
#include "kerf/xfem/cut_faces.hpp"
#include "kerf/xfem/cut_opening.hpp"
#include "kerf/xfem/cut_state_transfer.hpp"
#include "kerf/xfem/cut_xfem_mass.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"
#include "kerf/xfem/cut_xfem_output.hpp"
#include "kerf/xfem/hinged_fragments.hpp"
#include "kerf/xfem/split_tet_masses.hpp"
#include "kerf/xfem/surface_enrichment.hpp"
#include "kerf/xfem/visual_surface.hpp"

#include <vtkRenderWindow.h>

#include <Eigen/Geometry>
#include <algorithm>
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

namespace chapter07 {

// @sect3{The demo scene}
//
// Every number of the scene, and where it comes from:
// - the liver: mesh/liver_shape.hpp's, 10 000 Tet4 (--tets changes it);
// - the tissue: E = 4 kPa, nu = 0.45, rho = 1060 kg/m^3. Human liver measured in vivo by
//   elastography is 2-6 kPa when healthy (transient elastography's normal range; our E is in
//   it), nearly incompressible (nu = 0.45-0.49 in the simulation literature; Tet4 locks above
//   0.45, chapter 1) and a little denser than water (1050-1070 kg/m^3);
// - the support: the liver hangs from the diaphragm by its bare area and the coronary and
//   falciform ligaments, the vena cava runs up its back, and it rests on the organs beneath.
//   We hold every node of the upper back (y >= 0.045, z >= -0.01) and of the underside's back
//   half (y >= -0.01, z <= -0.03); the front half overhangs. Held only at the back, it would
//   droop 6 cm under its weight at this E, and the blade would pass above it;
// - gravity -z; Rayleigh damping C = 2 M + 0.01 K_R: the sag rings down within half a second;
// - the blade: an upright edge 9 cm long, from 3 cm above the lobe's top down to z = 0, in the
//   plane y = -0.005, just in front of the held back; waiting beside the organ until 0.5 s, then
//   moving 15 cm along -x in 1.2 s (12.5 cm/s) and stopping inside the organ at x = -0.03. The
//   cut is partial in depth and in length, so its front (the blade's last edge and the path of
//   its tip) stays inside, and the overhanging front half, whose top is stretched by its weight,
//   pulls the wound open;
// - 2.5 s at 10 ms a step; the frames: every 5 steps (20 per simulated second), 960 x 720.
constexpr const char* demo_scene = R"({
  "name": "liver_cut",
  "mesh": {"liver": {"tets": 10000}, "order": 1},
  "material": {"young": 4000, "poisson": 0.45, "density": 1060},
  "model": "corotational",
  "gravity": [0, 0, -9.81],
  "dirichlet": [{"region": {"box": {"min": [-1, 0.045, -0.01], "max": [1, 1, 1]}}},
                {"region": {"box": {"min": [-1, -0.01, -1], "max": [1, 1, -0.03]}}}],
  "blade": {"path": [{"time": 0.5, "edge": [[0.12, -0.005, 0.09], [0.12, -0.005, 0.0]]},
                     {"time": 1.7, "edge": [[-0.03, -0.005, 0.09], [-0.03, -0.005, 0.0]]}]},
  "time": {"integrator": "newmark", "dt": 0.01, "steps": 250, "mass": "lumped", "rayleigh": [2, 0.01]},
  "output": {"every": 10},
  "render": {"every": 5, "width": 960, "height": 720, "camera": {"azimuth": -100, "elevation": 40, "zoom": 1.3}}
})";

// @sect3{Where the time of a step goes}
//
// The stacked chart of the results page: each step's wall-clock seconds, by what they were spent on.
struct StepTimes {
  double blade = 0.0;    // pulling the edge back, growing the sheet, the crossing test
  double topology = 0.0; // rebuilding pieces, enrichment, model, mass and integrator, and the state transfer
  double assemble = 0.0; // the corotated forces and tangent (inside the Newmark step)
  double solve = 0.0;    // the rest of the Newmark step: its linear solve and vector work
  double render = 0.0;   // moving the visual surface and drawing a frame
  double output = 0.0;   // writing files
};

// What a change of topology spends its time on (rebuilds.csv), stage by stage.
struct RebuildTimes {
  double pieces = 0.0, enrichment = 0.0, model = 0.0, transfer = 0.0, mass = 0.0, loads = 0.0, pattern = 0.0, integrator = 0.0;
};

// Seconds since the last call (or since it was made).
class Lap {
public:
  double operator()() {
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return seconds;
  }

private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

// @sect3{The LiverCut class}
//
// Chapter 6's skeleton with apply_cut called again whenever the blade has crossed a tet.
class LiverCut {
public:
  LiverCut(kerf::Scene scene, kerf::CommandLine options) : scene_(std::move(scene)), options_(std::move(options)) {}
  void run();
  void run_interactive();

private:
  void make_mesh();
  void setup_blade();
  void setup_visual(bool need_view, bool on_screen);
  void apply_cut();
  void setup_system();
  void assemble_at(const Eigen::VectorXd& u, kerf::RotationMethod rotation);
  void cut(const kerf::BladeEdge* blade, bool blade_done);
  void do_timestep(int step, bool cut_next, const kerf::BladeEdge* next, bool next_done);
  void check_state(int step) const;
  void output_step(int step);
  void draw(int step);
  void output_results();
  void report(const std::string& line) const {
    if (!options_.quiet) std::cout << line << '\n';
  }
  const kerf::SurfaceEnrichment& enrichment() const { return crack_tip_ ? crack_tip_->sign_enrichment() : *enrichment_; }

  kerf::Scene scene_;
  kerf::CommandLine options_;
  std::unique_ptr<kerf::Organ> organ_; // the mesh and what every model of its cut shares

  // The cut as it grows (xfem/blade_cut.hpp): the blade's path, the sheets it has left and the
  // tets they have crossed.
  std::unique_ptr<kerf::BladePath> path_;
  std::unique_ptr<kerf::BladeCut> blade_cut_;
  int topology_changes_ = 0;

  // The model of the current cut (rebuilt by apply_cut), and what it refers to.
  std::unique_ptr<kerf::CutSurfaces> cuts_;
  std::unique_ptr<kerf::MeshPieces> pieces_;
  std::unique_ptr<kerf::SurfaceEnrichment> enrichment_; // chapter 4's, without a "crack_tip" field
  std::unique_ptr<kerf::SceneCrackTip> crack_tip_;
  kerf::PieceRuleFunction rule_;
  std::unique_ptr<kerf::CutXfemModel> model_;
  kerf::DofMap dofs_;
  std::unique_ptr<kerf::SparseAssembler> tangent_assembler_;
  std::unique_ptr<kerf::SplitTetMasses> piece_masses_; // of model_, kept across rebuilds like its points
  // The corotated forces, the warped tangent (in tangent_assembler_) and the strain energy at the
  // last u assembled (assemble_at): a step ends by asking for W at the state the next step starts
  // from, so one pass serves both.
  struct Assembled {
    Eigen::VectorXd u, f_int;
    double energy = 0.0;
    bool valid = false; // false after the model or the assembler's matrix changed
  } assembled_;
  kerf::NonlinearDynamicSystem system_;
  std::unique_ptr<kerf::NonlinearNewmarkIntegrator> newmark_;
  kerf::DynamicState state_;
  kerf::EnergyAccount account_;
  double energy_scale_ = 0.0;
  double body_mass_ = 0.0;
  int unconverged_steps_ = 0;

  // Pictures.
  std::unique_ptr<kerf::VisualSurface> visual_;
  std::unique_ptr<kerf::OrganView> view_;
  std::vector<int> untorn_; // the visual triangles no cut crosses (the cut's, recomputed by apply_cut)
  std::vector<std::filesystem::path> png_frames_;

  // Output along the run.
  StepTimes step_times_, total_times_;
  double max_step_seconds_ = 0.0, max_topology_step_seconds_ = 0.0;
  std::unique_ptr<kerf::CutRunLog> log_; // energy.csv, opening.csv, the probes' history, the .pvd series (the batch run's)
  std::ofstream timings_csv_, cuts_csv_, rebuilds_csv_;
  RebuildTimes rebuild_times_;
};

// @sect4{LiverCut::make_mesh}
//
// The scene's mesh (the liver by default, made by Mesh_3 with the size --tets asks for), its
// quality, and the structures every rebuild of the cut shares (app/organ.hpp): the face and
// node adjacency and a point locator of the reference mesh.
void LiverCut::make_mesh() {
  organ_ = std::make_unique<kerf::Organ>(scene_, options_.tets, &std::cerr);
  report(organ_->summary);
}

// @sect4{LiverCut::setup_blade}
//
// The path and the cut it grows, whose sheet keeps the blade's edge every quad length: the
// scene's, or a quarter of the mesh's mean edge (blade_cut.hpp); 2 mm for the mouse of a scene
// without a blade.
void LiverCut::setup_blade() {
  blade_cut_ = std::make_unique<kerf::BladeCut>(organ_->mesh, scene_.blade.given ? scene_.blade.quad_length : 0.002, scene_.blade.samples);
  if (!scene_.blade.given) return;
  path_ = std::make_unique<kerf::BladePath>(scene_.blade.path);
  std::ostringstream line;
  line.precision(3);
  line << "blade: " << path_->keyframes().size() << " keyframes, " << path_->start_time() << " s to " << path_->end_time()
       << " s, quad length " << 1e3 * blade_cut_->quad_length() << " mm";
  report(line.str());
}

// @sect4{LiverCut::setup_visual}
//
// The picture's surface: for the built-in liver a fine mesh of its implicit surface (Mesh_3's
// surface mesher, triangles of render.visual_size), several times finer than the tets' boundary;
// for a mesh read from a file, the scene's render.surface (SOFA's liver comes with a smooth one),
// or else the mesh's own boundary. Embedded once in the reference tets.
void LiverCut::setup_visual(bool need_view, bool on_screen) {
  const kerf::TriangleSurface surface = kerf::scene_visual_surface(scene_, organ_->mesh);
  visual_ = std::make_unique<kerf::VisualSurface>(organ_->mesh, surface);
  report("visual surface: " + std::to_string(surface.num_triangles()) + " triangles (" +
         std::to_string(static_cast<double>(surface.num_triangles()) / organ_->boundary.faces.rows()).substr(0, 4) +
         " times the tet mesh's boundary)");
  if (!need_view) return;
  view_ = std::make_unique<kerf::OrganView>(surface, kerf::organ_view_settings(scene_.render, on_screen));
}

// @sect4{LiverCut::apply_cut}
//
// Chapter 4's (or with a "crack_tip" field chapter 5's) model of the cut as the sheets stand,
// then the system on it; the state of the model before, if there was one, carried over
// (cut_state_transfer.hpp): the standard DOFs as they are, each enrichment from the field of the
// old piece that holds its part, so the field, and with it every energy, is the same before and
// after. With branch functions the DOFs near the front are fitted to the old field in H1 instead
// (the same file), which changes the energies by under 1 % (chapter 7's results); the held DOFs
// (the new model's DofMap, made here for that) keep their values. One map, built once, carries
// u, v and a.
void LiverCut::apply_cut() {
  // cuts.csv's check that no energy goes in: the old model's energies of the state, before the
  // transfer. Diagnostics, booked as output: the simulation itself never needs the old model's W
  // here (do_timestep closes the step with the new model's).
  double kinetic_before = 0.0, elastic_before = 0.0;
  if (model_ && cuts_csv_.is_open()) {
    const auto start = std::chrono::steady_clock::now();
    kinetic_before = 0.5 * state_.v.dot(system_.M * state_.v);
    elastic_before = scene_.model == "corotational" ? model_->energy(state_.u, true, kerf::scene_quasi_static_settings(scene_).rotation)
                                                    : model_->energy(state_.u, false);
    step_times_.output += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  Lap lap;
  auto cuts = std::make_unique<kerf::CutSurfaces>(blade_cut_->surfaces());
  // Only the tets near the quads added since the last rebuild can have new pieces: the others
  // keep theirs (recut_mesh_into_pieces).
  auto pieces = std::make_unique<kerf::MeshPieces>(pieces_ ? kerf::recut_mesh_into_pieces(organ_->mesh, *cuts, *pieces_, blade_cut_->take_grown_box())
                                                           : kerf::cut_mesh_into_pieces(organ_->mesh, *cuts, organ_->neighbours));
  rebuild_times_.pieces = lap();
  std::unique_ptr<kerf::SceneCrackTip> crack_tip;
  std::unique_ptr<kerf::SurfaceEnrichment> enrichment;
  if (scene_.crack_tip.given) crack_tip = std::make_unique<kerf::SceneCrackTip>(scene_, organ_->mesh, *pieces, *cuts, nullptr);
  else enrichment = std::make_unique<kerf::SurfaceEnrichment>(kerf::make_surface_enrichment(organ_->mesh, *pieces));
  rebuild_times_.enrichment = lap();
  // The model integrates anew only the tets recut_mesh_into_pieces cut again (and those with
  // branch functions); every other tet keeps the old model's points.
  const kerf::SurfaceEnrichment& sign = crack_tip ? crack_tip->sign_enrichment() : *enrichment;
  const kerf::CrackTipFunctions* tip = crack_tip ? crack_tip->tip_functions() : nullptr;
  auto model = model_ ? std::make_unique<kerf::CutXfemModel>(*model_, *pieces, sign, tip)
                      : std::make_unique<kerf::CutXfemModel>(organ_->mesh, scene_.material, *pieces, sign, rule_, tip);
  // Several passes of the blade beside the held back carve out fragments that the clamp's hold
  // of an enrichment (or Koschier et al.'s eq. 22) pins at one node or along one line: a pendulum
  // that swings faster than a frozen step can follow, whose energy then grows by 1 + theta^2 a
  // step, and that no tissue holds. Such a fragment is let go, free as any piece the cut frees
  // (xfem/hinged_fragments.hpp).
  kerf::DofMap dofs = kerf::release_hinged_fragments(*model, kerf::make_cut_xfem_dof_map(*model, organ_->held));
  rebuild_times_.model = lap();
  const bool rebuild = model_ != nullptr;
  if (model_) {
    const kerf::CutStateTransfer transfer(*model_, *model, kerf::BranchStateRule::fit, &dofs);
    state_.u = transfer(state_.u);
    state_.v = transfer(state_.v);
    state_.a = transfer(state_.a);
  }
  // The old model is gone only now: the transfer read it. Then what it referred to, and the
  // opening's sample points, which were found in the old pieces.
  if (log_) log_->model_changed();
  assembled_.valid = false; // of the old model
  model_ = std::move(model);
  dofs_ = std::move(dofs);
  crack_tip_ = std::move(crack_tip);
  enrichment_ = std::move(enrichment);
  pieces_ = std::move(pieces);
  cuts_ = std::move(cuts);
  rebuild_times_.transfer = lap();
  // The visual triangles the cut tears change only with the cut: found here, once per change,
  // not at every frame.
  if (view_ && cuts_->num_surfaces() > 0) untorn_ = kerf::untorn_triangles(visual_->reference(), *cuts_);
  setup_system();
  if (rebuild && rebuilds_csv_.is_open()) {
    const RebuildTimes& r = rebuild_times_;
    char row[512];
    std::snprintf(row, sizeof row, "%d,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e\n", topology_changes_ + 1, r.pieces, r.enrichment, r.model,
                  r.transfer, r.mass, r.loads, r.pattern, r.integrator);
    rebuilds_csv_ << row;
  }
  if (rebuild && cuts_csv_.is_open()) {
    // Nothing lost: the pieces' volumes (the weights of their rules) and the mass e^T M e of a
    // unit translation against the uncut mesh's, and the energies of the same field in the old
    // and the new DOFs (tests/chapter_07 asserts they are equal). The new model's W is its
    // assembly at the state, which the step's energy and the next step's start take from it.
    const kerf::EnergyAccount after = newmark_->start_account(state_);
    const auto start = std::chrono::steady_clock::now();
    const double volume = model_->integrated_volume();
    char row[512];
    std::snprintf(row, sizeof row, "%d,%.17g,%d,%ld,%ld,%.6e,%.6e,%.17g,%.17g,%.17g,%.17g\n", topology_changes_ + 1, state_.t,
                  static_cast<int>(blade_cut_->crossing().crossed_tets().size()), static_cast<long>(this->enrichment().num_enrichments()),
                  static_cast<long>(dofs_.num_free), volume / organ_->volume - 1.0, body_mass_ / (scene_.material.density * organ_->volume) - 1.0,
                  kinetic_before, after.kinetic, elastic_before, after.elastic);
    cuts_csv_ << row;
    step_times_.output += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
}

// @sect4{LiverCut::setup_system}
//
// Chapter 6's corotated Newmark step on the current model and apply_cut's unknowns (a piece the
// cut frees simply falls, as in chapter 6): the mass and the gravity load of the scene's lumping, the
// tangent's assembler on the model's pattern, and the checked step (by default) with
// Jacobi-preconditioned CG started from the last acceleration. The pattern, the mass and the
// preconditioner change only here, when the topology changes; a step of a run whose cut does not
// grow reuses them.
void LiverCut::setup_system() {
  Lap lap;
  // The split tets' piece masses: those whose pieces the cut kept are copied from the last
  // model's, the others integrated by the scene's rule (cut_xfem_mass.hpp).
  piece_masses_ = std::make_unique<kerf::SplitTetMasses>(*model_, rule_, piece_masses_.get());
  const Eigen::SparseMatrix<double> M = kerf::scene_cut_xfem_mass(scene_, *model_, *piece_masses_);
  rebuild_times_.mass = lap();
  // The loads that go with the mass. Gravity is the mass times a unit translation along g, M e_g
  // (u = g at the nodes, a = 0): for the consistent mass that is rho int N^T g, for the per-piece
  // lumpings each phantom node pulled by its own mass, exactly lumped_gravity_load's definition
  // (lumped_mass.hpp; tests/chapter_07 checks the two agree), at the cost of one product instead of
  // a second pass over every piece's rule. Eqs. 81-82 and tractions take the library's path.
  Eigen::VectorXd f;
  if (scene_.time.mass == "schoch_eq_81_82" || !scene_.traction.empty()) {
    f = kerf::scene_cut_xfem_dynamic_loads(scene_, *model_, organ_->boundary, rule_);
  } else {
    Eigen::VectorXd e_g = Eigen::VectorXd::Zero(M.rows());
    for (Eigen::Index v = 0; v < organ_->mesh.num_nodes(); ++v) e_g.segment<3>(3 * v) = scene_.gravity;
    f = M * e_g;
  }
  rebuild_times_.loads = lap();
  // The tangent's pattern: the mesh's part copied from the last one, only the enriched tets' rows
  // walked (sparse_assembler.hpp).
  const kerf::DofMap all_free = kerf::make_dof_map(model_->num_dof_nodes(), {});
  tangent_assembler_ = tangent_assembler_ ? std::make_unique<kerf::SparseAssembler>(*tangent_assembler_, model_->assembly_slots(), all_free,
                                                                                    organ_->mesh.nodes_per_tet())
                                          : std::make_unique<kerf::SparseAssembler>(model_->assembly_slots(), all_free);
  rebuild_times_.pattern = lap();
  const bool corotated = scene_.model == "corotational";
  const kerf::RotationMethod rotation = kerf::scene_quasi_static_settings(scene_).rotation;
  system_ = {};
  system_.M = M;
  system_.rayleigh_alpha = scene_.time.rayleigh[0];
  system_.rayleigh_beta = scene_.time.rayleigh[1];
  system_.dofs = dofs_;
  // CG's Jacobi scaling in the part basis, as chapter 6's: a freed piece is never moved by the
  // corrections of the body (part_basis.hpp).
  if (scene_.solver.basis == "parts") system_.solver_basis = kerf::cut_body_preconditioner_basis(*model_, dofs_);
  system_.load = [f](double) { return f; };
  const Eigen::Index n = 3 * model_->num_dof_nodes();
  system_.motion = [n](double) {
    kerf::PrescribedMotion still;
    still.u = still.v = still.a = Eigen::VectorXd::Zero(n);
    return still;
  };
  system_.internal_force = [this, rotation, corotated](const Eigen::VectorXd& u, kerf::CorotationalTangent tangent, Eigen::VectorXd& f_int,
                                                      const Eigen::SparseMatrix<double>** K) {
    if (corotated && tangent == kerf::CorotationalTangent::warped) {
      assemble_at(u, rotation);
      f_int = assembled_.f_int;
      if (K) *K = &tangent_assembler_->matrix();
      return;
    }
    // Newton's consistent tangent, or the linear body: assembled each time asked.
    const auto start = std::chrono::steady_clock::now();
    assembled_.valid = false;
    Eigen::VectorXd unused = Eigen::VectorXd::Zero(u.size());
    if (K) tangent_assembler_->set_zero();
    if (corotated) {
      model_->assemble(u, rotation, tangent, f_int, K ? tangent_assembler_.get() : nullptr, K ? &unused : nullptr);
    } else {
      model_->assemble_linear_stiffness(*tangent_assembler_, unused);
      f_int = tangent_assembler_->matrix() * u;
    }
    if (K) *K = &tangent_assembler_->matrix();
    step_times_.assemble += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  system_.elastic_energy = [this, rotation, corotated](const Eigen::VectorXd& u) {
    if (!corotated) return model_->energy(u, false, rotation);
    assemble_at(u, rotation);
    return assembled_.energy;
  };
  kerf::NonlinearNewmarkSettings settings;
  settings.newmark = {scene_.time.beta, scene_.time.gamma};
  // Chapter 7's default is the checked step: the blade carves slabs and chips that turn a good
  // part of a radian in a step, where the frozen step's lagged rotations feed their energy.
  settings.update = kerf::rotation_update_named(scene_.time.corotation, kerf::RotationUpdate::checked);
  settings.tolerance = scene_.time.tolerance;
  settings.solver = scene_.solver;
  if (!scene_.solver_given) {
    settings.solver.type = "cg-jacobi";
    settings.solver.tolerance = scene_.time.tolerance;
  }
  // The first model's initial state assembles it (booked as assembly in timings.csv, so not as
  // the integrator's time here); a rebuilt model is assembled at the carried-over state by
  // apply_cut's energy check or by the step's close (do_timestep).
  const double assembled_before = step_times_.assemble;
  newmark_ = std::make_unique<kerf::NonlinearNewmarkIntegrator>(system_, scene_.time.dt, settings);
  if (state_.u.size() == 0) {
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
    state_ = newmark_->initial_state(zero, zero, 0.0);
    account_ = newmark_->start_account(state_);
  }
  body_mass_ = kerf::translation_mass(system_.M, organ_->mesh.num_nodes());
  rebuild_times_.integrator = lap() - (step_times_.assemble - assembled_before);
}

// @sect4{LiverCut::assemble_at}
//
// The corotated f_int, warped tangent and W at u, unless they are those of the last u asked
// about. A checked step asks for f_int(u_{n+1}) and K_R(u_{n+1}) for its check, for W(u_{n+1})
// at its end, and the next step for the same f_int and K_R at its start: one rotation per point
// serves them all (CutXfemModel::assemble_with_energy), where energy() and assemble() would find
// it twice.
void LiverCut::assemble_at(const Eigen::VectorXd& u, kerf::RotationMethod rotation) {
  if (assembled_.valid && assembled_.u.size() == u.size() && assembled_.u == u) return;
  const auto start = std::chrono::steady_clock::now();
  Eigen::VectorXd unused = Eigen::VectorXd::Zero(u.size());
  tangent_assembler_->set_zero();
  assembled_.energy = model_->assemble_with_energy(u, rotation, kerf::CorotationalTangent::warped, assembled_.f_int,
                                                   tangent_assembler_.get(), &unused);
  assembled_.u = u;
  assembled_.valid = true;
  step_times_.assemble += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// @sect4{LiverCut::check_state}
//
// As in chapter 6: no NaN, and an energy bounded by what was put in.
void LiverCut::check_state(int step) const { kerf::check_bounded_state(state_, account_, energy_scale_, step); }

// @sect4{LiverCut::cut}
//
// The blade's next edge cuts the body as it stands, and if it crossed a tet the model is rebuilt
// (apply_cut). The time goes to the step being timed; an assembly made inside (the new model's,
// at the current state) is booked as assembly, and cuts.csv's energy check as output.
void LiverCut::cut(const kerf::BladeEdge* blade, bool blade_done) {
  using clock = std::chrono::steady_clock;
  auto start = clock::now();
  const bool crossed = path_ && blade_cut_->advance(*model_, *organ_->locator, state_.u, blade, blade_done);
  step_times_.blade += std::chrono::duration<double>(clock::now() - start).count();
  if (!crossed) return;
  start = clock::now();
  const double assembled_before = step_times_.assemble, output_before = step_times_.output;
  apply_cut();
  ++topology_changes_;
  step_times_.topology += std::chrono::duration<double>(clock::now() - start).count() - (step_times_.assemble - assembled_before) -
                          (step_times_.output - output_before);
}

// @sect4{LiverCut::do_timestep}
//
// Chapter 6's step on the model as the blade has cut it, then the blade's edge for the next step
// (`next`, if `cut_next`; nullptr: away from the tissue) cuts the body this step has moved. The
// step's energy account closes last: its W(u_{n+1}) comes from the model the next step starts on,
// whose assembly at u_{n+1} is the next step's f_int and K_R as well. Were the blade to cut at the
// start of the next step instead (the same cut: the same edge on the same state), a step that
// changes the topology would assemble twice, the old model at u_{n+1} for W and the new one for
// the next step; the field, and so W, is the same in both (cut_state_transfer.hpp).
void LiverCut::do_timestep(int step, bool cut_next, const kerf::BladeEdge* next, bool next_done) {
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  const double assembled_before_step = step_times_.assemble;
  const double work_before = account_.external_work;
  const double t_before = state_.t;
  try {
    kerf::NonlinearStepReport report = newmark_->open_step(state_);
    if (!report.converged) ++unconverged_steps_;
    step_times_.solve += std::chrono::duration<double>(clock::now() - start).count() - (step_times_.assemble - assembled_before_step);
    state_.t = step * scene_.time.dt;
    if (cut_next) cut(next, next_done);
    // The end's energies by the current model: the new one's if the blade crossed a tet
    // (apply_cut assembled it there), else one assembly that the next step's start reuses
    // (assemble_at).
    newmark_->close_step(report, state_);
    newmark_->add_step(account_, state_, report);
  } catch (const kerf::InputError&) {
    throw; // names its file and field already
  } catch (const std::exception& error) {
    // One line: the step and the time it spans, then what failed (a failed solve names its
    // matrix, its solver and what can make the matrix so).
    std::ostringstream where;
    where << "step " << step << " (t = " << t_before << " s to " << step * scene_.time.dt << " s): " << error.what();
    throw std::runtime_error(where.str());
  }
  energy_scale_ += std::abs(account_.external_work - work_before);
  check_state(step);
}

// @sect4{LiverCut::draw}
//
// The visual surface moved by the field of the piece each vertex lies in, without its triangles
// that the cut tore (their corners are on both sides), and the walls of the cut.
void LiverCut::draw(int step) {
  if (!view_) return;
  const auto start = std::chrono::steady_clock::now();
  kerf::TriangleSurface skin = visual_->deform(kerf::xfem_visual_displacement(*model_, state_.u));
  if (cuts_->num_surfaces() > 0) skin = kerf::keep_triangles(skin, untorn_);
  view_->show(skin, kerf::cut_face_surface(*model_, state_.u));
  if (!options_.interactive) {
    char name[64];
    std::snprintf(name, sizeof name, "_frame_%06d.png", step);
    const std::filesystem::path file = options_.out_dir / "frames" / (scene_.name + name);
    view_->write_png(file);
    png_frames_.push_back(file);
  }
  step_times_.render += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// @sect4{LiverCut::output_step}
//
// energy.csv, opening.csv (how far the wound has opened), timings.csv and the probes' history
// every step; the pieces into the .pvd series every output.every steps (app/cut_run_log.hpp); a
// frame every render.every steps.
void LiverCut::output_step(int step) {
  const auto start = std::chrono::steady_clock::now();
  char row[512];
  if (log_) log_->write(step, state_.t, *model_, *cuts_, state_.u, account_);
  step_times_.output += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (view_ && scene_.render.every > 0 && (step % scene_.render.every == 0 || step == scene_.time.steps)) draw(step);
  std::snprintf(row, sizeof row, "%d,%.17g,%ld,%d,%d,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e\n", step, state_.t, static_cast<long>(dofs_.num_free),
                static_cast<int>(blade_cut_->crossing().crossed_tets().size()), step_times_.topology > 0.0 ? 1 : 0, step_times_.blade,
                step_times_.topology, step_times_.assemble, step_times_.solve, step_times_.render, step_times_.output);
  timings_csv_ << row;
}

// @sect4{LiverCut::output_results}
//
// The probes where the run ended, the animation, and the run's account.
void LiverCut::output_results() {
  if (options_.moments_out) {
    kerf::write_piece_moments_csv(*options_.moments_out, organ_->mesh, *pieces_, rule_);
    report("wrote " + options_.moments_out->string());
  }
  if (options_.probes_out) {
    kerf::sample_cut_xfem_probes(*options_.probes_in, *options_.probes_out, *model_, state_.u, &std::cerr);
    report("wrote " + options_.probes_out->string());
  }
  report("wrote " + log_->pvd().string() + " (" + std::to_string(log_->num_frames()) +
         " frames), energy.csv, opening.csv and timings.csv in " + options_.out_dir.string());
  for (const std::string& line : kerf::write_run_animation(png_frames_, scene_, options_.out_dir)) report(line);
}

// @sect4{LiverCut::run}
//
// Mesh, blade, pictures, the uncut model, then the steps, each with its blade frame; a progress
// line about once a second, and at the end where the time went.
void LiverCut::run() {
  using clock = std::chrono::steady_clock;
  const auto seconds_since = [](clock::time_point start) { return std::chrono::duration<double>(clock::now() - start).count(); };
  auto start = clock::now();
  make_mesh();
  setup_blade();
  setup_visual(scene_.render.every > 0, false);
  rule_ = kerf::scene_piece_rule(scene_, organ_->mesh.order());
  apply_cut();
  report("system: " + std::to_string(dofs_.num_free) + " unknowns before the cut; mass " + std::to_string(body_mass_) + " kg (" +
         scene_.time.mass + ")");
  // A blade that starts in the tissue would cut from nowhere: its path must begin outside.
  if (path_) kerf::require_blade_starts_outside(*model_, *organ_->locator, *path_, scene_.blade.samples, scene_.source.string());
  report("setup: " + std::to_string(seconds_since(start)) + " s");

  log_ = std::make_unique<kerf::CutRunLog>(kerf::CutRunLogSettings{options_.out_dir, scene_.name, scene_.output_every, scene_.time.steps,
                                                                   organ_->mean_edge, options_.probes_in, options_.probes_history},
                                           *organ_->locator);
  cuts_csv_ = kerf::open_csv(options_.out_dir / "cuts.csv", "change,t,crossed_tets,enrichments,unknowns,volume_error,mass_error,"
                                                             "kinetic_before,kinetic_after,elastic_before,elastic_after\n");
  rebuilds_csv_ = kerf::open_csv(options_.out_dir / "rebuilds.csv",
                                 "change,pieces_s,enrichment_s,model_s,transfer_s,mass_s,loads_s,pattern_s,integrator_s\n");
  timings_csv_ = kerf::open_csv(options_.out_dir / "timings.csv",
                                "step,t,unknowns,crossed_tets,topology_changed,blade_s,topology_s,assemble_s,solve_s,render_s,output_s\n");
  energy_scale_ = account_.kinetic + account_.elastic;
  // The blade cuts the body as the step before left it: the first step's edge here, on the body at
  // rest, each later one at the end of the step before (do_timestep). timings.csv books a cut in
  // the row of the step that left the body as it was cut (row 0 for this one).
  const int steps = scene_.time.steps;
  const auto blade_at = [this](int step) {
    const double t = step * scene_.time.dt;
    return std::pair{path_ ? path_->edge_at(t) : kerf::BladeEdge{}, path_ && t >= path_->end_time()};
  };
  step_times_ = {};
  if (path_) {
    const auto [blade, done] = blade_at(1);
    cut(&blade, done);
  }
  output_step(0);
  const auto add_to_totals = [this] {
    const double simulated = step_times_.blade + step_times_.topology + step_times_.assemble + step_times_.solve;
    max_step_seconds_ = std::max(max_step_seconds_, simulated);
    if (step_times_.topology > 0.0) max_topology_step_seconds_ = std::max(max_topology_step_seconds_, simulated);
    for (auto [total, part] : {std::pair{&total_times_.blade, step_times_.blade}, {&total_times_.topology, step_times_.topology},
                               {&total_times_.assemble, step_times_.assemble}, {&total_times_.solve, step_times_.solve},
                               {&total_times_.render, step_times_.render}, {&total_times_.output, step_times_.output}})
      *total += part;
  };
  if (step_times_.topology > 0.0) add_to_totals(); // the first blade crossed a tet already

  start = clock::now();
  auto last_line = start;
  for (int step = 1; step <= steps; ++step) {
    step_times_ = {};
    const auto [next, next_done] = blade_at(step + 1);
    do_timestep(step, path_ && step < steps, &next, next_done);
    output_step(step);
    add_to_totals();
    if (!options_.quiet && (seconds_since(last_line) >= 1.0 || step == steps)) {
      const double rate = step / seconds_since(start);
      std::ostringstream line;
      line.precision(3);
      line << "step " << step << "/" << steps << " (t = " << state_.t << " s): " << blade_cut_->crossing().crossed_tets().size() << " tets cut, "
           << dofs_.num_free << " unknowns; " << rate << " steps/s, about " << (steps - step) / rate << " s left";
      report(line.str());
      last_line = clock::now();
    }
  }
  const double wall = seconds_since(start);
  std::ostringstream line;
  line.precision(3);
  const double simulated = total_times_.blade + total_times_.topology + total_times_.assemble + total_times_.solve;
  line << "stepped " << steps << " steps in " << wall << " s; per step: " << 1e3 * simulated / steps << " ms simulating (blade "
       << 1e3 * total_times_.blade / steps << ", topology " << 1e3 * total_times_.topology / steps << ", assemble "
       << 1e3 * total_times_.assemble / steps << ", solve " << 1e3 * total_times_.solve / steps << "), render "
       << 1e3 * total_times_.render / steps << ", output " << 1e3 * total_times_.output / steps << "; slowest step "
       << 1e3 * max_step_seconds_ << " ms, slowest topology step " << 1e3 * max_topology_step_seconds_ << " ms";
  report(line.str());
  std::ostringstream cut;
  cut.precision(4);
  cut << "cut: " << blade_cut_->crossing().crossed_tets().size() << " tets crossed, " << topology_changes_ << " topology changes, "
      << blade_cut_->sheets().size() << " sheets of " << (blade_cut_->sheets().empty() ? 0 : blade_cut_->sheets().back().num_triangles())
      << " triangles, " << enrichment().num_enrichments() << " enrichments; " << kerf::energy_summary(account_);
  report(cut.str());
  if (unconverged_steps_ > 0)
    std::cerr << "warning: " << scene_.source.string() << ": time.tolerance: the step's iteration missed " << scene_.time.tolerance << " in "
              << unconverged_steps_ << " steps\n";
  output_results();
}

// @sect4{LiverCut::run_interactive}
//
// The same steps in a window: a VTK timer fires every dt, and the blade is the mouse
// (render/cutting_window.hpp): its edge reaches the scene's blade depth (the first keyframe's edge
// length) behind the point under the cursor. Each step prints its time.
void LiverCut::run_interactive() {
  make_mesh();
  setup_blade();
  setup_visual(true, true);
  rule_ = kerf::scene_piece_rule(scene_, organ_->mesh.order());
  apply_cut();
  const double depth = path_ ? (path_->keyframes().front().edge.end - path_->keyframes().front().edge.start).norm() : 0.06;
  std::filesystem::create_directories(options_.out_dir);
  timings_csv_.open(options_.out_dir / "timings.csv");
  timings_csv_ << "step,t,unknowns,crossed_tets,topology_changed,blade_s,topology_s,assemble_s,solve_s,render_s,output_s\n";
  energy_scale_ = 1e-12;

  // The window (render/cutting_window.hpp): Shift + left drag is the blade, a drag alone turns
  // the camera, q closes.
  kerf::CuttingWindow window(*view_, depth);
  int step = 0;
  const auto on_timer = [&] {
    ++step;
    // The blade: along the view direction through the point under the cursor while Shift and
    // the button are held over the organ; away otherwise.
    const std::optional<kerf::BladeEdge> edge = window.blade();
    if (edge && !path_) path_ = std::make_unique<kerf::BladePath>(std::vector<kerf::BladeKeyframe>{{0.0, *edge}, {1.0, *edge}});
    const auto start = std::chrono::steady_clock::now();
    // The edge under the cursor now is the blade of the next step: it cuts the body as this step
    // leaves it (do_timestep), as a scripted path's edge at t_{n+1} does.
    step_times_ = {};
    do_timestep(step, true, edge ? &*edge : nullptr, false);
    draw(step);
    view_->window().Render();
    const double ms = 1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("step %d (t = %.2f s): %.1f ms (blade %.2f, topology %.1f, assemble %.1f, solve %.1f, render %.1f), %zu tets cut\n", step,
                state_.t, ms, 1e3 * step_times_.blade, 1e3 * step_times_.topology, 1e3 * step_times_.assemble, 1e3 * step_times_.solve,
                1e3 * step_times_.render, blade_cut_->crossing().crossed_tets().size());
    std::fflush(stdout);
    output_step(step);
  };
  view_->window().Render();
  if (!options_.events) {
    report("interactive: hold Shift and drag with the left button to cut; drag without Shift to turn; q closes the window");
    window.run(static_cast<int>(std::max(1.0, 1e3 * scene_.time.dt)), on_timer);
  } else {
    // A script instead of a hand (the test of this mode): each row is an event that the window
    // receives before the timer of its step fires, as the window system would deliver it; the
    // run ends after the script's last step.
    const std::vector<kerf::ScriptedEvent> script = kerf::read_events_csv(*options_.events, kerf::EventClock::step);
    std::size_t next = 0;
    const int last = script.empty() ? 0 : static_cast<int>(script.back().at);
    for (int tick = 1; tick <= last; ++tick) {
      for (; next < script.size() && script[next].at == tick; ++next) window.deliver(script[next]);
      on_timer();
    }
    report("played " + std::to_string(script.size()) + " events over " + std::to_string(last) + " steps; " +
           std::to_string(blade_cut_->crossing().crossed_tets().size()) + " tets cut");
  }
}

} // namespace chapter07

// @sect3{The main function}
//
// As in chapter 6, with --tets and --interactive, and the demo scene when no --scene is given.
int main(int argc, char** argv) {
  const std::string usage =
      "usage: 07_liver [--scene FILE.json] [--tets N] [--interactive [--events FILE.csv]] [--probes IN.csv [--probes-out OUT.csv] [--probes-history FILE.csv]]\n"
      "                [--moments-out FILE.csv] [--out DIR] [--quiet]\n"
      "Cuts a liver with a moving blade while it moves under gravity: semi-progressive XFEM cuts stored in the\n"
      "reference configuration, corotational Newmark dynamics, PNG frames and an animated PNG (Kerf, chapter 7).\n"
      "  --scene FILE.json         the scene, with a \"blade\" field (default: the demo, examples/07_liver_cut.json)\n"
      "  --tets N                  the liver's size in tets (default: the scene's, 10000 in the demo)\n"
      "  --interactive             a window in which Shift + left drag cuts (needs a display)\n"
      "  --events FILE.csv         with --interactive: play these mouse events (header step,event,x,y,shift), then stop\n"
      "  --probes IN.csv           points (header x,y,z) at which to write the displacement ...\n"
      "  --probes-out OUT.csv      ... at the last step (header x,y,z,ux,uy,uz)\n"
      "  --probes-history FILE.csv ... at every step from 0 (header step,t,probe,ux,uy,uz; probe 0-based)\n"
      "  --moments-out FILE.csv    the moments of every piece of every cut tet at the last step, as in chapter 4\n"
      "  --out DIR                 where energy.csv, timings.csv, the .vtu frames, their .pvd and the PNG frames go (default: output)\n"
      "  --quiet                   no progress lines\n"
      "  --help                    this text\n"
      "PNG frames need an X display: run under xvfb-run -a without one, or set \"render\": {\"every\": 0}.\n";
  return kerf::run_guarded(
      argc, argv, "07_liver", usage,
      [](const kerf::CommandLine& options) {
        const kerf::Scene scene = options.scene ? kerf::read_scene_file(*options.scene)
                                                : kerf::parse_scene(chapter07::demo_scene, "demo scene", ".");
        kerf::require_features(scene, kerf::SceneFeatures{.corotational = true, .cuts = true, .dynamics = true, .cut_quadrature = true,
                                                          .crack_tip = true, .organ = true});
        kerf::require_blade_scene(scene, "07_liver", "chapter 6's corotated step", options.interactive);
        chapter07::LiverCut problem(scene, options);
        if (options.interactive) problem.run_interactive();
        else problem.run();
      },
      kerf::CommandLineFeatures{.moments_out = true, .probes_history = true, .organ = true});
}
