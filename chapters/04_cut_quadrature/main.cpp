/* Kerf, chapter 4: cuts as triangle meshes, and quadrature on the pieces of cut elements.

   Build:   cmake --preset release && cmake --build --preset release --target 04_cut_quadrature

   Sample runs:
     04_cut_quadrature
     04_cut_quadrature --scene examples/04_beam_blade_linear_tet10.json --probes examples/04_blade_probes.csv --probes-out output/blade_probes.csv
     04_cut_quadrature --scene examples/04_beam_two_cuts_tet4.json --moments-out output/two_cuts_moments.csv --out output/two_cuts

   Description: the beam of chapters 1-3 (0.03 x 0.06 x 0.2 m, E = 300 kPa, nu = 0.35), Tet10
   elements, clamped at z = 0, is cut half-way through its depth by a CURVED blade, the sheet
   z = 0.1 + 0.01 sin(pi y / 0.06) for x <= 0.015, which the program writes itself as a
   triangle mesh (output/blade.obj). Its top edge x = 0 is pulled up by 0.02 m, as in chapter
   3, and the cut opens:

        z = 0.2 +-----+ <- edge pulled up      +-----+
                |     |                        |     |
        z = 0.1 |~~~  |  curved cut            |~  \ |  the cut opens
                |     |                        |     |
        z = 0   +-----+                        +-----+
               //////// clamped               //////// clamped

   The mesh ignores the cut. Every tet the blade's triangles cross is split exactly into its
   pieces (convex cells glued into polyhedra), the nodes whose supports the cut separates get
   one enrichment per extra part, and every piece is integrated by its own quadrature rule,
   which a Tet10 needs: its stiffness is quadratic on a piece, so chapter 3's volume ratios
   are wrong for it. Read chapters 1-3 first. */

// @sect3{Include files}
//
// New since chapter 3: triangle-mesh cut surfaces and their AABB tree, the pieces of every cut
// tet (cut area), the rules that integrate over them (quadrature area), and the enrichment on
// the one-ring with the phantom-element model that uses them (xfem area).
#include "kerf/app/command_line.hpp"
#include "kerf/app/input_error.hpp"
#include "kerf/corotation/quasi_static_solver.hpp"
#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/height_field_surface.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/io/newton_history_csv.hpp"
#include "kerf/io/write_surface_obj.hpp"
#include "kerf/io/write_vtu.hpp"
#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/scene/cut_xfem_loads.hpp"
#include "kerf/scene/scene.hpp"
#include "kerf/scene/scene_cuts.hpp"
#include "kerf/scene/scene_mesh.hpp"
#include "kerf/scene/scene_quadrature.hpp"
#include "kerf/scene/scene_quasi_static.hpp"
#include "kerf/scene/scene_xfem_dofs.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"
#include "kerf/xfem/cut_xfem_output.hpp"
#include "kerf/xfem/surface_enrichment.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

namespace chapter04 {

// @sect3{The demo scene}
//
// Chapter 3's scene with Tet10 elements and no "cuts" entry: the demo's blade is not a file but
// a surface the program makes (make_blade below) and adds to the scene's cuts. A scene of your
// own gives its cuts as `{"surface": "blade.obj"}` (paths relative to the scene file), as
// rectangles, or both; `"quadrature": {"rule": ...}` chooses how the pieces are integrated.
constexpr const char* demo_scene = R"({
  "name": "beam_curved_cut",
  "mesh": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0.2], "cells": [3, 6, 19]}, "order": 2},
  "material": {"young": 300e3, "poisson": 0.35, "density": 1070},
  "model": "corotational",
  "dirichlet": [
    {"region": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0]}}},
    {"region": {"box": {"min": [0, 0, 0.2], "max": [0, 0.06, 0.2]}}, "displacement": [0, 0, 0.02]}],
  "quasi_static": {"load_steps": 5}
})";

// The blade: the sheet z = 0.1 + 0.01 sin(pi y / 0.06) over x in [-0.005, 0.015] and
// y in [-0.005, 0.065], 8 by 28 cells of two triangles. It reaches out of the beam at x = 0 and
// at both sides y = 0 and y = 0.06, and its front x = 0.015 runs through the middle of a layer
// of elements (the mesh's cells are 0.01 m wide in x), as chapter 3's rectangle's does.
kerf::TriangleSurface make_blade() {
  const kerf::HeightField h = [](double, double y) { return 0.01 * std::sin(M_PI * y / 0.06); };
  return kerf::height_field_surface(h, 0.1, {-0.005, -0.005}, {0.015, 0.065}, {8, 28});
}

// @sect3{The CutQuadrature class}
//
// The skeleton of chapters 1-3, with the step DESIGN.md names apply_cut: the cut's geometry and
// the enrichment it asks for, before the unknowns are set up.
class CutQuadrature {
public:
  CutQuadrature(kerf::Scene scene, kerf::CommandLine options, std::optional<kerf::TriangleSurface> blade)
      : scene_(std::move(scene)), options_(std::move(options)), blade_(std::move(blade)) {}
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
  std::optional<kerf::TriangleSurface> blade_; // the demo's blade, added to the scene's cuts
  kerf::TetMesh mesh_;
  kerf::BoundaryFaces boundary_;
  std::unique_ptr<kerf::CutSurfaces> cuts_;
  kerf::MeshPieces pieces_;
  kerf::SurfaceEnrichment enrichment_;
  kerf::PieceRuleFunction rule_;
  std::unique_ptr<kerf::CutXfemModel> model_;
  kerf::DofMap dofs_;
  Eigen::VectorXd f_ext_; // loads on all 3 (N + M) DOFs [u; a]
  Eigen::VectorXd u_;     // the solution [u; a]
  kerf::QuasiStaticResult result_;
};

// @sect4{CutQuadrature::make_mesh}
//
// As in chapter 1. Tet10 meshes are welcome now, and so is any number of cuts.
void CutQuadrature::make_mesh() {
  mesh_ = kerf::make_scene_mesh(scene_, &std::cerr);
  boundary_ = kerf::boundary_faces(mesh_);
  report("mesh: " + std::to_string(mesh_.num_nodes()) + " nodes, " + std::to_string(mesh_.num_tets()) +
         (mesh_.order() == 1 ? " Tet4" : " Tet10") + ", model " + scene_.model);
}

// @sect4{CutQuadrature::apply_cut}
//
// Three steps turn the cut surfaces into pieces and enrichments.
//
// First the surfaces, all behind one AABB tree: a rectangle is two triangles now, a surface
// file is read and checked (cut_surfaces.hpp, check_triangle_surface.hpp).
//
// Then the pieces: every tet the tree says a triangle meets is split into convex cells, plane
// by plane inside each triangle's prism, and the cells are glued into pieces through the faces
// the cut does not cover (tet_pieces.hpp). Which side of a triangle a corner of a tet lies on
// is decided by an exact predicate, so a cut through a node, along an edge or in a face is
// that case, not a coin toss. A tet is completely cut when it falls into two or more pieces,
// partially cut when the cut's front ends inside it (Koschier section 4.3).
//
// Last the enrichment: a node whose support the cut divides into r parts gets r - 1 sets of
// enriched unknowns, one per part other than its own (surface_enrichment.hpp). A node between
// two cuts gets two; a node whose support a front crosses gets none, so the simulated cut ends
// at the last element it fully crosses (chapter 5 lets it end where it ends).
void CutQuadrature::apply_cut() {
  std::vector<kerf::TriangleSurface> surfaces = kerf::scene_cut_surfaces(scene_, &std::cerr);
  if (blade_) surfaces.push_back(*blade_);
  cuts_ = std::make_unique<kerf::CutSurfaces>(std::move(surfaces));
  pieces_ = kerf::scene_mesh_pieces(scene_, mesh_, *cuts_, &std::cerr);
  report("cut: " + std::to_string(cuts_->num_triangles()) + " triangles in " + std::to_string(cuts_->num_surfaces()) + " surfaces; " +
         std::to_string(pieces_.count(kerf::SurfaceCutState::completely_cut)) + " tets completely cut, " +
         std::to_string(pieces_.count(kerf::SurfaceCutState::partially_cut)) + " partially cut, " +
         std::to_string(pieces_.count(kerf::SurfaceCutState::touched)) + " touched, " +
         std::to_string(pieces_.count(kerf::SurfaceCutState::uncut)) + " uncut");
  enrichment_ = kerf::make_surface_enrichment(mesh_, pieces_);
  report("enrichment: " + std::to_string(enrichment_.enriched_nodes) + " enriched nodes, " +
         std::to_string(enrichment_.num_enrichments()) + " enrichments (at most " + std::to_string(enrichment_.most_enrichments) +
         " on one node)");
}

// @sect4{CutQuadrature::setup_system}
//
// The rule for the pieces, the model, and the unknowns. The model integrates every piece of a
// split tet as its own "phantom" element: on a piece every enrichment is 0 or 1, so the field
// there is an ordinary Tet4 or Tet10 field whose nodal values are u_i, or u_i + a_i^k where
// enrichment k is 1, and everything (stiffness, corotation, loads) is the ordinary element's,
// integrated over the piece alone. The rule is the scene's choice. The default, "subtets", puts a
// Gauss rule of the needed degree on every sub-tetrahedron of the piece's convex cells: exact
// for the stiffness and loads of both element types, with positive weights inside the piece.
// "exact" is exact too, with fewer points (weights fitted at fixed points to the piece's exact
// polyhedral moments), but some of its weights are negative and its points lie outside the
// piece. That is harmless for the linear model; for the corotated one the tangent at each point,
// R K_q R^T, is no polynomial, and summed with negative weights it need not stay positive
// definite: the demo's Newton iteration fails with it (results.md says where).
//
// The moments of every piece go to --moments-out as soon as the rule is known: a run that
// fails later still says what its quadrature did.
void CutQuadrature::setup_system() {
  rule_ = kerf::scene_piece_rule(scene_, mesh_.order());
  model_ = std::make_unique<kerf::CutXfemModel>(mesh_, scene_.material, pieces_, enrichment_, rule_);
  report("quadrature: rule \"" + scene_.quadrature.rule + "\", " + std::to_string(model_->num_piece_points()) +
         " points on the pieces of the split tets, " + std::to_string(model_->num_negative_weights()) + " of them with negative weights");
  if (scene_.model == "corotational" && model_->num_negative_weights() > 0)
    std::cerr << "warning: " << scene_.source.string() << ": quadrature.rule: \"" << scene_.quadrature.rule << "\" has "
              << model_->num_negative_weights() << " negative weights; the corotated tangent summed with them may not be "
              << "positive definite (\"subtets\" has none)\n";
  if (options_.moments_out) {
    kerf::write_piece_moments_csv(*options_.moments_out, mesh_, pieces_, rule_);
    report("wrote " + options_.moments_out->string());
  }
  dofs_ = kerf::scene_cut_xfem_dof_map(scene_, *model_, &std::cerr);
  report("system: " + std::to_string(dofs_.num_free) + " unknowns (" + std::to_string(3 * enrichment_.num_enrichments()) +
         " of them enriched)");
}

// @sect4{CutQuadrature::assemble_system}
//
// Chapter 1's loads on the u rows; on the a rows the same integrals over the pieces where each
// enrichment is 1 (gravity with the pieces' rule, a traction over each piece's part of a face).
void CutQuadrature::assemble_system() {
  f_ext_ = kerf::cut_xfem_scene_loads(scene_, *model_, boundary_);
}

// @sect4{CutQuadrature::solve}
//
// As in chapter 3: one solve for linear XFEM, chapter 2's Newton iteration for the corotated
// model, which now takes a rotation at every quadrature point of every piece of a Tet10 (the
// phantom element's deformation gradient varies over the piece; Schoch et al. eqs. 31-40 applied
// piece by piece).
void CutQuadrature::solve() {
  if (scene_.model == "linear") {
    u_ = kerf::solve_linear_cut_xfem(*model_, dofs_, f_ext_, scene_.solver);
    return;
  }
  const kerf::QuasiStaticSettings settings = kerf::scene_quasi_static_settings(scene_);
  // The scene's prescribed path is on the nodes; the enriched unknowns of gripped nodes stay 0.
  const auto path = [this](double lambda) {
    Eigen::VectorXd prescribed = Eigen::VectorXd::Zero(3 * model_->num_dof_nodes());
    prescribed.head(3 * mesh_.num_nodes()) = kerf::scene_prescribed_displacements(scene_, mesh_, lambda);
    return prescribed;
  };
  result_ = kerf::solve_quasi_static(*model_, dofs_, f_ext_, settings, path);
  u_ = result_.u;
  report("newton: " + std::to_string(result_.total_iterations) + " iterations over " + std::to_string(settings.load_steps) +
         " load steps, final relative residual " + std::to_string(result_.history.back().relative_residual) + ", " +
         std::to_string(result_.last_statistics.inverted_points) + " inverted points");
  if (!result_.converged)
    std::cerr << "warning: " << scene_.source.string() << ": the Newton iteration did not reach the tolerance "
              << settings.tolerance << " in every load step (see the _newton.csv file)\n";
}

// @sect4{CutQuadrature::output_results}
//
// As in chapter 3: `NAME.vtu` with the nodal u_i, and `NAME_pieces.vtu`, the XFEM view in which
// every split tet is drawn as its pieces, each displaced by its own phantom element's field, so
// that the cut opens in ParaView. The demo also writes its blade, `blade.obj`, to use in a scene.
void CutQuadrature::output_results() const {
  Eigen::MatrixXd displacement(mesh_.num_nodes(), 3);
  for (Eigen::Index v = 0; v < mesh_.num_nodes(); ++v) displacement.row(v) = u_.segment<3>(3 * v).transpose();
  Eigen::MatrixXd enrichments(mesh_.num_nodes(), 1);
  for (Eigen::Index v = 0; v < mesh_.num_nodes(); ++v) enrichments(v, 0) = enrichment_.enrichments_of(v);
  Eigen::MatrixXd state(mesh_.num_tets(), 1), pieces(mesh_.num_tets(), 1);
  for (Eigen::Index t = 0; t < mesh_.num_tets(); ++t) {
    state(t, 0) = static_cast<double>(pieces_.state(t));
    pieces(t, 0) = pieces_.num_pieces(t);
  }
  const std::filesystem::path vtu = options_.out_dir / (scene_.name + ".vtu");
  kerf::write_vtu(vtu, mesh_, {{"displacement", displacement}, {"enrichments", enrichments}},
                  {{"cut_state", state}, {"pieces", pieces}});
  const std::filesystem::path drawn = options_.out_dir / (scene_.name + "_pieces.vtu");
  kerf::write_cut_xfem_vtu(drawn, *model_, u_);
  report("wrote " + vtu.string() + " and " + drawn.string() + "; max |u| = " +
         std::to_string(displacement.rowwise().norm().maxCoeff()) + " m");
  if (blade_) {
    const std::filesystem::path obj = options_.out_dir / "blade.obj";
    kerf::write_surface_obj(obj, *blade_);
    report("wrote " + obj.string());
  }
  if (!result_.history.empty()) kerf::write_newton_history_csv(options_.out_dir / (scene_.name + "_newton.csv"), result_.history);
  if (options_.probes_in) {
    kerf::sample_cut_xfem_probes(*options_.probes_in, *options_.probes_out, *model_, u_, &std::cerr);
    report("wrote " + options_.probes_out->string());
  }
}

// @sect4{CutQuadrature::run}
//
// As in chapters 1-3, with apply_cut before setup_system.
void CutQuadrature::run() {
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

} // namespace chapter04

// @sect3{The main function}
//
// As in chapter 3, with --moments-out, which this chapter teaches.
int main(int argc, char** argv) {
  const std::string usage =
      "usage: 04_cut_quadrature [--scene FILE.json] [--probes IN.csv --probes-out OUT.csv] [--moments-out FILE.csv]\n"
      "                         [--out DIR] [--quiet]\n"
      "Solves a static elasticity problem cut by triangle-mesh surfaces and rectangles, linear or corotational XFEM\n"
      "on Tet4 or Tet10 elements, every cut element integrated piece by piece (Kerf, chapter 4).\n"
      "  --scene FILE.json      the scene (default: the demo, a beam cut by a curved blade the program makes)\n"
      "  --probes IN.csv        points (header x,y,z) at which to write the displacement ...\n"
      "  --probes-out OUT.csv   ... to this file (header x,y,z,ux,uy,uz), each on its own side of the cut\n"
      "  --moments-out FILE.csv the integrals of 1, x, y, z, x^2, y^2, z^2, xy, yz, xz over every piece of every\n"
      "                         cut tet (completely or partially) by the scene's quadrature rule\n"
      "                         (header element,piece,volume,mx,my,mz,mxx,myy,mzz,mxy,myz,mxz)\n"
      "  --out DIR              where the .vtu files and CSV files go (default: output)\n"
      "  --quiet                no progress lines\n"
      "  --help                 this text\n";
  return kerf::run_guarded(
      argc, argv, "04_cut_quadrature", usage,
      [](const kerf::CommandLine& options) {
        const bool demo = !options.scene;
        const kerf::Scene scene = demo ? kerf::parse_scene(chapter04::demo_scene, "demo scene", ".")
                                       : kerf::read_scene_file(*options.scene);
        kerf::require_features(scene, kerf::SceneFeatures{.corotational = true, .cuts = true, .cut_quadrature = true});
        std::optional<kerf::TriangleSurface> blade;
        if (demo) blade = chapter04::make_blade();
        chapter04::CutQuadrature problem(scene, options, std::move(blade));
        problem.run();
      },
      kerf::CommandLineFeatures{.moments_out = true});
}
