/* Kerf, chapter 5: crack-tip enrichment, a cut that ends where it ends.

   Build:   cmake --preset release && cmake --build --preset release --target 05_crack_tip

   Sample runs:
     05_crack_tip
     05_crack_tip --scene examples/05_beam_partial_cut_gravity_tet4.json --probes examples/05_partial_cut_probes.csv --probes-out output/partial_cut_probes.csv
     05_crack_tip --scene examples/05_beam_curved_front_tet4.json --moments-out output/curved_front_moments.csv --out output/curved_front
     05_crack_tip --scene examples/05_williams_slab_tet4.json --out output/williams_slab

   Description: the beam of chapters 1-4 (0.03 x 0.06 x 0.2 m, E = 300 kPa, nu = 0.35), Tet4
   elements, clamped at z = 0, is cut half-way through its depth by chapter 3's rectangle
   [0, 0.015] x [0, 0.06] x {0.1}. Its front, the line x = 0.015, z = 0.1 across the beam, runs
   through the middle of a layer of elements (the cells are 0.01 m wide in x; Paulus's test
   case). The top edge x = 0 is pulled up by 0.02 m, as in chapter 3, and the cut opens:

        z = 0.2 +-----+ <- edge pulled up      +-----+
                |     |                        |     |
        z = 0.1 |==*  |  cut, front * at       |=  \*|  the cut opens, and
                |     |  x = 0.015             |     |  closes at the front
        z = 0   +-----+                        +-----+
               //////// clamped               //////// clamped

   Chapters 3 and 4 end the simulated cut at the last row of enriched nodes: a node whose
   support the front crosses gets no enrichment, so the crack stops one element short of the
   front or reaches past it, and the answer jumps when the front moves inside an element. Here
   the nodes near the front get four more functions each, sqrt(r) times the angular shapes of
   the exact near-front field, and the crack ends where the rectangle ends. The program writes
   the front itself as a poly line (NAME_front.vtp) beside the pieces, so ParaView shows where
   the cut stops. Read chapters 3 and 4 first. */

// @sect3{Include files}
//
// New since chapter 4: the fronts of the cuts (cut area, crack_front.hpp), the node
// classification and the branch functions (xfem area), the scene's "crack_tip" field turned into
// both (scene_crack_tip.hpp), and the writer of the fronts (io area).
#include "kerf/app/command_line.hpp"
#include "kerf/app/input_error.hpp"
#include "kerf/corotation/quasi_static_solver.hpp"
#include "kerf/cut/crack_front.hpp"
#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/io/newton_history_csv.hpp"
#include "kerf/io/write_front_polyline.hpp"
#include "kerf/io/write_vtu.hpp"
#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/scene/cut_xfem_loads.hpp"
#include "kerf/scene/scene.hpp"
#include "kerf/scene/scene_crack_tip.hpp"
#include "kerf/scene/scene_cuts.hpp"
#include "kerf/scene/scene_mesh.hpp"
#include "kerf/scene/scene_quadrature.hpp"
#include "kerf/scene/scene_quasi_static.hpp"
#include "kerf/scene/scene_williams.hpp"
#include "kerf/scene/scene_xfem_dofs.hpp"
#include "kerf/xfem/branch_enrichment.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"
#include "kerf/xfem/cut_xfem_output.hpp"

#include <chrono>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace chapter05 {

// @sect3{The demo scene}
//
// Chapter 3's scene on Tet4 elements with the linear model. No "crack_tip" field: the default,
// branch functions on every node within the default radius of the front (geometric enrichment,
// scene_crack_tip.hpp). A scene of your own may write
// `"crack_tip": {"enrichment": "branch", "radius": 0.02}` for another radius, `"radius": 0` for
// the topological rule, or `"enrichment": "none"` for chapter 4's cut, which stops at the last
// row of enriched nodes.
constexpr const char* demo_scene = R"({
  "name": "beam_crack_tip",
  "mesh": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0.2], "cells": [3, 6, 19]}, "order": 1},
  "material": {"young": 300e3, "poisson": 0.35, "density": 1070},
  "model": "linear",
  "dirichlet": [
    {"region": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0]}}},
    {"region": {"box": {"min": [0, 0, 0.2], "max": [0, 0.06, 0.2]}}, "displacement": [0, 0, 0.02]}],
  "cuts": [{"rectangle": {"origin": [0, 0, 0.1], "edge1": [0.015, 0, 0], "edge2": [0, 0.06, 0]}}]
})";

// @sect3{The CrackTip class}
//
// Chapter 4's skeleton. apply_cut finds the fronts and classifies the nodes as well; everything
// after it is chapter 4's with twelve more unknowns per branch node.
class CrackTip {
public:
  CrackTip(kerf::Scene scene, kerf::CommandLine options) : scene_(std::move(scene)), options_(std::move(options)) {}
  void run();

private:
  void make_mesh();
  void apply_cut();
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
  std::unique_ptr<kerf::CutSurfaces> cuts_;
  kerf::MeshPieces pieces_;
  std::unique_ptr<kerf::SceneCrackTip> crack_tip_; // the fronts and the enrichment: the model refers to them
  kerf::PieceRuleFunction rule_;
  std::unique_ptr<kerf::CutXfemModel> model_;
  kerf::DofMap dofs_;
  Eigen::VectorXd f_ext_; // loads on all DOFs [u; a; b]
  Eigen::VectorXd u_;     // the solution [u; a; b]
  kerf::QuasiStaticResult result_;
};

// @sect4{CrackTip::make_mesh}
//
// As in chapter 4.
void CrackTip::make_mesh() {
  mesh_ = kerf::make_scene_mesh(scene_, &std::cerr);
  boundary_ = kerf::boundary_faces(mesh_);
  report("mesh: " + std::to_string(mesh_.num_nodes()) + " nodes, " + std::to_string(mesh_.num_tets()) +
         (mesh_.order() == 1 ? " Tet4" : " Tet10") + ", model " + scene_.model);
}

// @sect4{CrackTip::apply_cut}
//
// Chapter 4's surfaces and pieces, then two new steps.
//
// The fronts: every boundary edge of a cut surface (an edge of one triangle only) that lies
// inside the mesh, and not in its skin, where the cut is open rather than stopped. They are
// chained into polylines with a frame at every point: a ahead of the front, b the cut's normal,
// c along the front (Paulus section 3.4), from which every point gets its polar coordinates
// r and theta = atan2(x_b, x_a) (Paulus section 3.4).
//
// The classification (Paulus section 3.3). Chapter 3's rule enriched a node when the
// cut splits its support; the front's nodes, whose supports the front enters without splitting,
// got nothing. Now a node is a *branch* node if it lies within the radius r_e of a front, or is
// a corner of a tet the front passes through; it carries the four branch functions and no sign
// enrichment. The other nodes chapter 4 enriched are *sign* nodes, as before. With r_e = 0 the
// rule is Paulus's topological one; the default r_e (geometric enrichment) keeps a fixed region
// around the front enriched as the mesh is refined, which Laborde et al. 2005 show restores the
// optimal rate in 2D; here it raises the rate but does not quite reach it (1.66 and 1.71 in L2
// on the last steps of figures/05_crack_tip/convergence.md, against 2: the results' known defects).
//
// Blending tets, those with some corners branch enriched and some not, spoil the rate: there
// the branch nodes' hats do not sum to one, so the enrichment is a fraction of F that the
// standard functions cannot make up. With `"blending": "corrected"` the functions are
// multiplied by Fries's ramp R, the sum of the branch nodes' hats, and every corner of a
// blending tet gets them: the *ramp* nodes, which keep their sign enrichments (Fries 2008;
// branch_enrichment.hpp). It lowers the error on the convergence ladder, but the ramp nodes'
// functions are nearly dependent far from the front and, on a straight front, exactly so in six
// directions (branch_null_space.hpp holds one DOF per direction), so the default stays Paulus's
// plain blending and the corotated model refuses the correction.
void CrackTip::apply_cut() {
  cuts_ = std::make_unique<kerf::CutSurfaces>(kerf::scene_cut_surfaces(scene_, &std::cerr));
  pieces_ = kerf::scene_mesh_pieces(scene_, mesh_, *cuts_, &std::cerr);
  report("cut: " + std::to_string(cuts_->num_triangles()) + " triangles in " + std::to_string(cuts_->num_surfaces()) + " surfaces; " +
         std::to_string(pieces_.count(kerf::SurfaceCutState::completely_cut)) + " tets completely cut, " +
         std::to_string(pieces_.count(kerf::SurfaceCutState::partially_cut)) + " partially cut");
  crack_tip_ = std::make_unique<kerf::SceneCrackTip>(scene_, mesh_, pieces_, *cuts_, &std::cerr);
  const kerf::CrackFronts& fronts = crack_tip_->fronts();
  std::ostringstream line;
  line << "front: " << fronts.polylines.size() << " polylines, " << fronts.num_segments() << " segments, length " << fronts.length()
       << " m";
  report(line.str());
  line.str("");
  if (const kerf::BranchEnrichment* branch = crack_tip_->branch_enrichment()) {
    int front_tets = 0, branch_tets = 0;
    for (std::size_t t = 0; t < branch->front_tet.size(); ++t) {
      front_tets += branch->front_tet[t];
      branch_tets += branch->has_branch_nodes[t];
    }
    line << "enrichment: branch, "
         << (crack_tip_->rule() == kerf::TipEnrichmentRule::topological ? std::string("topological")
                                                                         : "geometric, radius " + std::to_string(crack_tip_->radius()) + " m")
         << (crack_tip_->default_radius() ? " (default)" : "") << "; " << branch->count(kerf::NodeEnrichmentKind::branch)
         << " branch nodes, " << branch->count(kerf::NodeEnrichmentKind::sign) << " sign nodes, " << branch->num_ramp_nodes()
         << " ramp nodes (blending "
         << (branch->blending_correction == kerf::BlendingCorrection::corrected ? "corrected" : "not corrected") << "); "
         << front_tets << " tets hold the front, " << branch_tets << " have branch functions";
  } else {
    line << "enrichment: none (chapter 4's); " << crack_tip_->sign_enrichment().enriched_nodes << " enriched nodes, 0 branch nodes";
  }
  report(line.str());
}

// @sect4{CrackTip::setup_system}
//
// The model of chapter 4 with the branch functions. On a tet with branch nodes the field is the
// phantom element's plus sum_v sum_l N_v (F_l - F_l(x_v)) b_{v,l} (Paulus eq. 3 in the shifted
// form, which vanishes at every node, so that the standard DOFs stay the field at the nodes).
// Those functions are no polynomials and their gradients grow like 1 / sqrt(r) at the front, so
// the tets the front crosses are integrated by sub-tets collapsed onto the front, exact in r
// (front_quadrature.hpp), and the other tets with branch nodes by graded Gauss rules; the
// scene's "quadrature" rule still integrates every other split tet, and goes to --moments-out.
//
// The Dirichlet conditions are chapter 4's, and one more kind: a `"williams"` entry prescribes
// Williams's near-front field of the cut's front, the benchmark of this chapter's convergence
// study. A node where the crack reaches the boundary lies beside two faces of the crack, on which
// the field has two values, and one value per node (a clamp, a displacement file) would hold
// its enrichments at 0 and shut the crack's mouth. So every DOF of the entry's nodes takes the
// field's XFEM interpolant: u_v the field on the node's own side, a_v^k the field on the far
// part minus that, b_{v,l} the field's coefficients in the branch functions
// (scene_williams.hpp). That is why the DOF map is given the fronts.
void CrackTip::setup_system() {
  rule_ = kerf::scene_piece_rule(scene_, mesh_.order());
  if (options_.moments_out) {
    kerf::write_piece_moments_csv(*options_.moments_out, mesh_, pieces_, rule_);
    report("wrote " + options_.moments_out->string());
  }
  model_ = std::make_unique<kerf::CutXfemModel>(mesh_, scene_.material, pieces_, crack_tip_->sign_enrichment(), rule_,
                                                crack_tip_->tip_functions());
  dofs_ = kerf::scene_cut_xfem_dof_map(scene_, *model_, crack_tip_->fronts(), &std::cerr);
  report("system: " + std::to_string(dofs_.num_free) + " unknowns (" + std::to_string(3 * crack_tip_->sign_enrichment().num_enrichments()) +
         " of them sign-enriched, " + std::to_string(12 * crack_tip_->num_branch_nodes()) + " branch)");
}

// @sect4{CrackTip::assemble_system}
//
// As in chapter 4, and the branch rows too: Paulus drops the body force on them (section 4.2),
// which is wrong for gravity; the model integrates N_v (F_l - F_l(x_v)) rho g with
// the same rules as the stiffness.
void CrackTip::assemble_system() {
  f_ext_ = kerf::cut_xfem_scene_loads(scene_, *model_, boundary_);
}

// @sect4{CrackTip::solve}
//
// As in chapter 4: one solve for the linear model, chapter 2's Newton iteration for the
// corotated one. A tet with branch functions turns with one rotation per piece, that of the
// piece's mean deformation gradient (corotation/corotated_piece.hpp, and the intro says why not
// one per point): the branch gradients are singular at the front.
void CrackTip::solve() {
  if (scene_.model == "linear") {
    u_ = kerf::solve_linear_cut_xfem(*model_, dofs_, f_ext_, scene_.solver);
    return;
  }
  const kerf::QuasiStaticSettings settings = kerf::scene_quasi_static_settings(scene_);
  const auto path = [this](double lambda) {
    return kerf::scene_cut_prescribed_displacements(scene_, *model_, crack_tip_->fronts(), lambda);
  };
  result_ = kerf::solve_quasi_static(*model_, dofs_, f_ext_, settings, path);
  u_ = result_.u;
  report("newton: " + std::to_string(result_.total_iterations) + " iterations over " + std::to_string(settings.load_steps) +
         " load steps, final relative residual " + std::to_string(result_.history.back().relative_residual));
  if (!result_.converged)
    std::cerr << "warning: " << scene_.source.string() << ": the Newton iteration did not reach the tolerance "
              << settings.tolerance << " in every load step (see the _newton.csv file)\n";
}

// @sect4{CrackTip::output_results}
//
// Chapter 4's two files, NAME.vtu (nodal u, and per node what it carries: 0 nothing, 1 sign,
// 2 branch) and NAME_pieces.vtu, in which every split tet is drawn as its pieces and every tet
// with branch functions cell by cell with the branch field added, so that the cut opens and
// closes at the front. New: NAME_front.vtp, the fronts as poly lines with the frame's c and b
// at every point. Load it beside the pieces in ParaView to see where the cut stops.
void CrackTip::output_results() const {
  Eigen::MatrixXd displacement(mesh_.num_nodes(), 3), node_kind = Eigen::MatrixXd::Zero(mesh_.num_nodes(), 1);
  for (Eigen::Index v = 0; v < mesh_.num_nodes(); ++v) {
    displacement.row(v) = u_.segment<3>(3 * v).transpose();
    if (const kerf::BranchEnrichment* branch = crack_tip_->branch_enrichment())
      node_kind(v, 0) = static_cast<double>(branch->kind[static_cast<std::size_t>(v)]);
    else
      node_kind(v, 0) = crack_tip_->sign_enrichment().enrichments_of(v) > 0 ? 1.0 : 0.0;
  }
  Eigen::MatrixXd state(mesh_.num_tets(), 1), branch_functions(mesh_.num_tets(), 1);
  for (Eigen::Index t = 0; t < mesh_.num_tets(); ++t) {
    state(t, 0) = static_cast<double>(pieces_.state(t));
    branch_functions(t, 0) = model_->has_branch_functions(t) ? 1.0 : 0.0;
  }
  const std::filesystem::path vtu = options_.out_dir / (scene_.name + ".vtu");
  kerf::write_vtu(vtu, mesh_, {{"displacement", displacement}, {"node_kind", node_kind}},
                  {{"cut_state", state}, {"branch_functions", branch_functions}});
  const std::filesystem::path drawn = options_.out_dir / (scene_.name + "_pieces.vtu");
  kerf::write_cut_xfem_vtu(drawn, *model_, u_);
  const std::filesystem::path front = options_.out_dir / (scene_.name + "_front.vtp");
  kerf::write_front_polyline(front, crack_tip_->fronts());
  report("wrote " + vtu.string() + ", " + drawn.string() + " and " + front.string() + "; max |u| = " +
         std::to_string(displacement.rowwise().norm().maxCoeff()) + " m");
  if (!result_.history.empty()) kerf::write_newton_history_csv(options_.out_dir / (scene_.name + "_newton.csv"), result_.history);
  if (options_.probes_in) {
    kerf::sample_cut_xfem_probes(*options_.probes_in, *options_.probes_out, *model_, u_, &std::cerr);
    report("wrote " + options_.probes_out->string());
  }
  // A scene that prescribes Williams's field (a "williams" Dirichlet entry, scene_williams.hpp)
  // is the convergence study's benchmark when the field is given on the whole boundary: the
  // field is then the exact solution, and we print how far the solution is from it, relative to
  // the field's own norms (cut_xfem_field_error.hpp).
  if (const std::optional<kerf::SceneWilliamsError> williams = kerf::scene_williams_error(scene_, *model_, crack_tip_->fronts(), u_)) {
    std::ostringstream line;
    line << "williams: error against dirichlet[" << williams->entry << "]'s field: relative L2 " << williams->error.relative_L2()
         << ", relative energy " << williams->error.relative_energy();
    report(line.str());
  }
}

// @sect4{CrackTip::run}
//
// As in chapter 4.
void CrackTip::run() {
  using clock = std::chrono::steady_clock;
  const auto seconds_since = [](clock::time_point start) { return std::chrono::duration<double>(clock::now() - start).count(); };
  auto start = clock::now();
  make_mesh();
  apply_cut();
  report("cut processing: " + std::to_string(seconds_since(start)) + " s");
  setup_system();
  assemble_system();
  report("setup: " + std::to_string(seconds_since(start)) + " s");
  start = clock::now();
  solve();
  report("solve: " + std::to_string(seconds_since(start)) + " s");
  std::filesystem::create_directories(options_.out_dir);
  output_results();
}

} // namespace chapter05

// @sect3{The main function}
//
// As in chapter 4, with the "crack_tip" field allowed.
int main(int argc, char** argv) {
  const std::string usage =
      "usage: 05_crack_tip [--scene FILE.json] [--probes IN.csv --probes-out OUT.csv] [--moments-out FILE.csv]\n"
      "                    [--out DIR] [--quiet]\n"
      "Solves a static elasticity problem whose cuts may end inside the body: XFEM with the four crack-tip (branch)\n"
      "functions on the nodes near each front, sign enrichment elsewhere, Tet4 or Tet10 (Kerf, chapter 5).\n"
      "  --scene FILE.json      the scene (default: the demo, a beam cut half-way, its front inside elements)\n"
      "  --probes IN.csv        points (header x,y,z) at which to write the displacement ...\n"
      "  --probes-out OUT.csv   ... to this file (header x,y,z,ux,uy,uz), each on its own side of the cut\n"
      "  --moments-out FILE.csv the integrals of 1, x, y, z, x^2, y^2, z^2, xy, yz, xz over every piece of every\n"
      "                         cut tet by the scene's quadrature rule\n"
      "                         (header element,piece,volume,mx,my,mz,mxx,myy,mzz,mxy,myz,mxz)\n"
      "  --out DIR              where the .vtu, .vtp and CSV files go (default: output)\n"
      "  --quiet                no progress lines\n"
      "  --help                 this text\n";
  return kerf::run_guarded(
      argc, argv, "05_crack_tip", usage,
      [](const kerf::CommandLine& options) {
        const kerf::Scene scene = options.scene ? kerf::read_scene_file(*options.scene)
                                                : kerf::parse_scene(chapter05::demo_scene, "demo scene", ".");
        kerf::require_features(scene, kerf::SceneFeatures{.corotational = true, .cuts = true, .cut_quadrature = true, .crack_tip = true,
                                                        .williams = true});
        chapter05::CrackTip problem(scene, options);
        problem.run();
      },
      kerf::CommandLineFeatures{.moments_out = true});
}
