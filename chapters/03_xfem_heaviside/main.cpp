/* Kerf, chapter 3: shifted-Heaviside XFEM, a cut without remeshing.

   Build:   cmake --preset release && cmake --build --preset release --target 03_xfem_heaviside

   Sample runs:
     03_xfem_heaviside
     03_xfem_heaviside --scene examples/03_beam_cut_gravity_linear.json --probes examples/03_cut_probes.csv --probes-out output/cut_probes.csv
     03_xfem_heaviside --scene examples/03_beam_cut_edge_pulled_corotational.json --out output/cut_pulled

   Description: the beam of chapters 1 and 2 (0.03 x 0.06 x 0.2 m, E = 300 kPa, nu = 0.35),
   clamped at z = 0, is cut half-way through its depth by the rectangle
   [0, 0.015] x [0, 0.06] x {0.1} of Schoch et al.'s test cases, on a mesh that does NOT conform
   to the cut: the plane z = 0.1 and the cut's front x = 0.015 run through the middle of
   elements. Its top edge x = 0 is pulled up by 0.02 m (the paper's test case 2), which opens
   the cut:

        z = 0.2 +-----+ <- edge pulled up       +-----+
                |     |                         |     |
        z = 0.1 |===  |  cut, x in [0, 0.015]   |=  \ |  the cut opens
                |     |                         |     |
        z = 0   +-----+                         +-----+
               //////// clamped                //////// clamped

   Nothing is remeshed. The nodes around the cut get three more unknowns each, and the
   elements the cut crosses get stiffness blocks scaled by the volumes of their two pieces.
   Read chapters 1 and 2 first. */

// @sect3{Include files}
//
// New since chapter 2: the cut area (the rectangle, its level set, how it meets each tet,
// clipping a tet) and the xfem area (which nodes to enrich, the enriched model, its loads,
// mass and output).
#include "kerf/app/command_line.hpp"
#include "kerf/app/input_error.hpp"
#include "kerf/corotation/quasi_static_solver.hpp"
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/io/newton_history_csv.hpp"
#include "kerf/io/write_vtu.hpp"
#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/scene/scene.hpp"
#include "kerf/scene/scene_mesh.hpp"
#include "kerf/scene/scene_quasi_static.hpp"
#include "kerf/scene/scene_xfem_dofs.hpp"
#include "kerf/scene/xfem_loads.hpp"
#include "kerf/xfem/enrichment.hpp"
#include "kerf/xfem/xfem_field.hpp"
#include "kerf/xfem/xfem_model.hpp"

#include <chrono>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

namespace chapter03 {

// @sect3{The demo scene}
//
// New field since chapter 2: "cuts", here one rectangle (a corner and two edges). Its normal
// is edge1 x edge2 = +z, so "above" the cut means z > 0.1. The mesh has 19 cells along the
// beam, so z = 0.1 lies half-way through a layer of elements, and 3 across its depth, so the
// front x = 0.015 does too.
constexpr const char* demo_scene = R"({
  "name": "beam_cut_pulled",
  "mesh": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0.2], "cells": [3, 6, 19]}, "order": 1},
  "material": {"young": 300e3, "poisson": 0.35, "density": 1070},
  "model": "corotational",
  "dirichlet": [
    {"region": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0]}}},
    {"region": {"box": {"min": [0, 0, 0.2], "max": [0, 0.06, 0.2]}}, "displacement": [0, 0, 0.02]}],
  "cuts": [{"rectangle": {"origin": [0, 0, 0.1], "edge1": [0.015, 0, 0], "edge2": [0, 0.06, 0]}}],
  "quasi_static": {"load_steps": 5}
})";

// @sect3{The CutElasticity class}
//
// The skeleton of chapters 1 and 2. New in setup_system: the cut, the enrichment it asks for,
// and the enriched model; everything after that is chapter 2's with more unknowns.
class CutElasticity {
public:
  CutElasticity(kerf::Scene scene, kerf::CommandLine options) : scene_(std::move(scene)), options_(std::move(options)) {}
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
  std::optional<kerf::RectangleCut> cut_;
  kerf::Enrichment enrichment_;
  std::unique_ptr<kerf::XfemModel> model_;
  kerf::DofMap dofs_;
  Eigen::VectorXd f_ext_;  // loads on all 3 (N + N_enr) DOFs [u; a]
  Eigen::VectorXd u_;      // the solution [u; a]
  kerf::QuasiStaticResult result_;
};

// @sect4{CutElasticity::make_mesh}
//
// As in chapter 1, with two checks that this chapter needs: Tet4 elements (a cut Tet10 needs
// the sub-element quadrature of chapter 4, since its stiffness integrand is not constant) and
// exactly one rectangle cut (a node that two cuts reach needs two enrichments; chapter 4 on).
void CutElasticity::make_mesh() {
  mesh_ = kerf::make_scene_mesh(scene_, &std::cerr);
  boundary_ = kerf::boundary_faces(mesh_);
  if (mesh_.order() != 1)
    throw kerf::InputError(scene_.source.string(), "mesh.order",
                           "chapter 3 cuts Tet4 meshes (order 1); a cut Tet10 needs chapter 4's quadrature");
  if (scene_.cuts.size() != 1 || !scene_.cuts[0].is_rectangle)
    throw kerf::InputError(scene_.source.string(), "cuts", "chapter 3 takes exactly one cut, given as a rectangle");
  const kerf::CutSpec& spec = scene_.cuts[0];
  try {
    cut_.emplace(spec.origin, spec.edge1, spec.edge2);
  } catch (const std::invalid_argument& error) {
    throw kerf::InputError(scene_.source.string(), "cuts[0].rectangle", error.what());
  }
  report("mesh: " + std::to_string(mesh_.num_nodes()) + " nodes, " + std::to_string(mesh_.num_tets()) + " Tet4, model " +
         scene_.model);
}

// @sect4{CutElasticity::setup_system}
//
// Three steps turn the cut into unknowns.
//
// First the level set: the signed distance of every node to the cut's plane (eq. 72),
// snapped to exactly 0 within round-off of the plane. Its signs classify every tet
// (eq. 73, and Paulus et al.'s uncut / touched / partially / completely cut), and a tet the plane
// splits is clipped into the sub-tets of its two pieces, whose volumes \f$V_a\f$ and
// \f$V_b\f$ are all the stiffness needs.
//
// Then the enrichment: a node is enriched when the cut splits the tets around it into two
// parts, with shifted functions \f$\Phi_i \Psi_i\f$, \f$\Psi_i = (H(x) - H_i)/2\f$ (eq. 44).
// A piece smaller than the minimum volume fraction is not kept: its corners are moved onto the
// cut instead, so that no enriched function lives on a sliver (the results chart why).
//
// Last the unknowns \f$[u; a]\f$ (eq. 74) and the Dirichlet conditions on them. With the shifted
// enrichment \f$u_i\f$ is the node's displacement, but fixing \f$u_i\f$ alone holds only the
// node: on a clamped face inside a cut tet, the far side's field
// \f$\sum_j \Phi_j (u_j + \Psi_j a_j)\f$ would still slide. So a gripped enriched node gets
// \f$a_i = 0\f$ too, and the clamp holds both flaps of the cut. Then the check of chapter 1, on
// the cut body: every piece the cut leaves must be held by some condition, or there is no static
// answer, and we say which piece before any solver can return garbage.
void CutElasticity::setup_system() {
  enrichment_ = kerf::make_enrichment(mesh_, *cut_);
  const kerf::MeshCutClassification& classes = enrichment_.classification;
  report("cut: " + std::to_string(classes.count(kerf::ElementCutState::completely_cut)) + " tets completely cut, " +
         std::to_string(classes.count(kerf::ElementCutState::partially_cut)) + " partially cut (extended through), " +
         std::to_string(classes.count(kerf::ElementCutState::touched)) + " touched, " +
         std::to_string(classes.count(kerf::ElementCutState::uncut)) + " uncut");
  report("enrichment: " + std::to_string(enrichment_.num_enriched()) + " enriched nodes, " +
         std::to_string(enrichment_.front_nodes) + " front nodes left unenriched, " + std::to_string(enrichment_.snapped_nodes) +
         " nodes moved onto the cut (minimum volume fraction " + std::to_string(enrichment_.minimum_volume_fraction) + ")");
  model_ = std::make_unique<kerf::XfemModel>(mesh_, scene_.material, enrichment_);
  dofs_ = kerf::scene_xfem_dof_map(scene_, *model_, &std::cerr);
  report("system: " + std::to_string(dofs_.num_free) + " unknowns (" + std::to_string(3 * enrichment_.num_enriched()) +
         " of them enriched)");
}

// @sect4{CutElasticity::assemble_system}
//
// The loads on \f$[u; a]\f$: chapter 1's on the \f$u\f$ rows, and on the \f$a\f$ rows the
// enriched loads \f$\int \Phi_i \Psi_i \rho g \, dV\f$ (and the same over cut boundary faces for
// a traction), integrated piece by piece since \f$\Psi_i\f$ is constant on each piece.
void CutElasticity::assemble_system() {
  f_ext_ = kerf::xfem_scene_loads(scene_, *model_, boundary_);
}

// @sect4{CutElasticity::solve}
//
// Linear XFEM is one solve with the stiffness of eqs. (60)-(63), assembled once: every cut
// element's blocks are its uncut blocks times a volume ratio. Corotational XFEM is chapter
// 2's quasi-static Newton iteration on the enriched model, in which each piece of a cut
// element turns with its own rotation, \f$R_a\f$ and \f$R_b\f$ (eqs. 64-71): the solver is the
// same function, since it only asks the model for forces and tangents. The report counts the
// inverted pieces and their volume: a piece's deformation gradient is that of its whole phantom
// tet (the side's field is linear over it), so an inverted phantom is an inverted piece, but a
// sliver's inversion weighs next to nothing.
//
// Reading Schoch et al. alongside: eq. 61's second case should read \f$H_i = -1\f$; eq. 71 has its
// two case labels swapped relative to eqs. 58-59 and ends in \f$x_{a_j}\f$ where the reference
// position \f$x_{0_j}\f$ is meant; and the remark after eq. 63 that these results "hold for
// quadratical elements, too" is false for the stiffness of a Tet10, whose strain is not constant
// (chapter 4). The code never types these equations in: it builds every block from the side
// operator \f$T\f$ of `xfem_element.hpp`, which lists the three slips where it departs from
// the printed text.
void CutElasticity::solve() {
  if (scene_.model == "linear") {
    u_ = kerf::solve_linear_xfem(*model_, dofs_, f_ext_, scene_.solver);
    return;
  }
  const kerf::QuasiStaticSettings settings = kerf::scene_quasi_static_settings(scene_);
  // The scene's prescribed path is on the nodes; the enriched DOFs are never prescribed.
  const auto path = [this](double lambda) {
    Eigen::VectorXd prescribed = Eigen::VectorXd::Zero(3 * model_->num_dof_nodes());
    prescribed.head(3 * mesh_.num_nodes()) = kerf::scene_prescribed_displacements(scene_, mesh_, lambda);
    return prescribed;
  };
  result_ = kerf::solve_quasi_static(*model_, dofs_, f_ext_, settings, path);
  u_ = result_.u;
  report("newton: " + std::to_string(result_.total_iterations) + " iterations over " + std::to_string(settings.load_steps) +
         " load steps, final relative residual " + std::to_string(result_.history.back().relative_residual) + ", " +
         std::to_string(result_.last_statistics.inverted_points) + " inverted pieces (" +
         std::to_string(result_.last_statistics.inverted_volume) + " m^3)");
  if (!result_.converged)
    std::cerr << "warning: " << scene_.source.string() << ": the Newton iteration did not reach the tolerance "
              << settings.tolerance << " in every load step (see the _newton.csv file)\n";
}

// @sect4{CutElasticity::output_results}
//
// Two views of the same solution. `NAME.vtu` is the mesh with its nodal displacements
// \f$u_i\f$, as chapters 1 and 2 write it: with the shifted enrichment these are the nodes'
// true displacements, but the mesh shows no cut. `NAME_pieces.vtu` is the XFEM view of
// Schoch et al.'s Figs. 7-8: every element with an enriched corner is written as its pieces, each
// displaced by the field of its own side, so the cut opens in ParaView. Probes are evaluated on
// the side of the cut where each point lies.
void CutElasticity::output_results() const {
  Eigen::MatrixXd displacement(mesh_.num_nodes(), 3);
  for (Eigen::Index v = 0; v < mesh_.num_nodes(); ++v) displacement.row(v) = u_.segment<3>(3 * v).transpose();
  Eigen::MatrixXd enriched(mesh_.num_nodes(), 1);
  for (Eigen::Index v = 0; v < mesh_.num_nodes(); ++v) enriched(v, 0) = enrichment_.enriched_index[static_cast<std::size_t>(v)] >= 0;
  Eigen::MatrixXd side(mesh_.num_tets(), 1);
  for (Eigen::Index t = 0; t < mesh_.num_tets(); ++t) side(t, 0) = static_cast<double>(enrichment_.tet_side[static_cast<std::size_t>(t)]);
  const std::filesystem::path vtu = options_.out_dir / (scene_.name + ".vtu");
  kerf::write_vtu(vtu, mesh_, {{"displacement", displacement}, {"enriched", enriched}}, {{"tet_side", side}});
  const std::filesystem::path pieces = options_.out_dir / (scene_.name + "_pieces.vtu");
  kerf::write_xfem_vtu(pieces, *model_, u_);
  report("wrote " + vtu.string() + " and " + pieces.string() + "; max |u| = " +
         std::to_string(displacement.rowwise().norm().maxCoeff()) + " m");

  if (!result_.history.empty()) {
    const std::filesystem::path csv = options_.out_dir / (scene_.name + "_newton.csv");
    kerf::write_newton_history_csv(csv, result_.history);
  }

  if (options_.probes_in) {
    kerf::sample_xfem_probes(*options_.probes_in, *options_.probes_out, *model_, u_, &std::cerr);
    report("wrote " + options_.probes_out->string());
  }
}

// @sect4{CutElasticity::run}
//
// As in chapters 1 and 2.
void CutElasticity::run() {
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

} // namespace chapter03

// @sect3{The main function}
//
// As in chapter 2; the chapter now teaches cuts too.
int main(int argc, char** argv) {
  const std::string usage =
      "usage: 03_xfem_heaviside [--scene FILE.json] [--probes IN.csv --probes-out OUT.csv] [--out DIR] [--quiet]\n"
      "Solves a static elasticity problem with one planar cut, linear or corotational XFEM on Tet4 elements (Kerf, chapter 3).\n";
  return kerf::run_guarded(argc, argv, "03_xfem_heaviside", usage, [](const kerf::CommandLine& options) {
    const kerf::Scene scene = options.scene ? kerf::read_scene_file(*options.scene)
                                            : kerf::parse_scene(chapter03::demo_scene, "demo scene", ".");
    kerf::require_features(scene, kerf::SceneFeatures{.corotational = true, .cuts = true});
    chapter03::CutElasticity problem(scene, options);
    problem.run();
  });
}
