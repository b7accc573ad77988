/// @file scene_crack_tip.hpp
/// @brief The scene's "crack_tip" field as what a CutXfemModel takes: the fronts of the cuts, the nodes that carry the branch functions, and the rule and radius that chose them.
///
/// Chapter 5's program, and every later one that ends a cut inside the tissue, turns the scene
/// into a model in the same three steps: find the fronts of the cuts (crack_front.hpp), classify
/// the nodes (branch_enrichment.hpp, Paulus section 3.3), and hand the model the sign
/// enrichment and the branch functions. The scene decides the rule:
/// - no "crack_tip", or `"enrichment": "branch"` without "radius": geometric enrichment with
///   default_tip_enrichment_radius (tip_enrichment_radius.hpp), the rule that restores the
///   optimal rate of convergence (Laborde et al. 2005, Bechet et al. 2005);
/// - `"radius": r > 0`: geometric enrichment with r_e = r (m);
/// - `"radius": 0`: the topological rule, the nodes of the tets the front passes through
///   (geometric enrichment with radius 0 would enrich the same nodes: branch_enrichment.hpp makes
///   the geometric set contain the topological one, so radius 0 IS the topological rule);
/// - `"enrichment": "none"`: chapter 4's enrichment alone, the cut ends at the last row of
///   enriched nodes (surface_enrichment.hpp); the fronts are still found, to be reported and drawn.
///
/// The rules of the tets with branch functions are the model's (CrackTipFunctions), except that
/// the blending rules are graded towards the front once, not three times, and held to 1e-5 of
/// V / h, not the strict default: ten times cheaper, for a quadrature error (2e-5 on the Williams
/// slab) far below a program's discretisation error (scene_crack_tip.cpp gives the numbers).
#pragma once

#include "kerf/cut/crack_front.hpp"
#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/mesh/tet_mesh.hpp"
#include "kerf/scene/scene.hpp"
#include "kerf/xfem/branch_enrichment.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"
#include "kerf/xfem/surface_enrichment.hpp"

#include <optional>
#include <ostream>

namespace kerf {

/// The crack-tip enrichment a scene asks for, built for one mesh and its cuts. The model keeps
/// references into it (the enrichment, the fronts, the functions), so it is neither copied nor
/// moved: hold it where the model can see it for its whole life (e.g. in a std::unique_ptr).
class SceneCrackTip {
public:
  /// @param scene    the scene (its crack_tip field; its source names the file in warnings)
  /// @param mesh     Tet4 or Tet10 mesh
  /// @param pieces   the pieces of its tets (scene_mesh_pieces)
  /// @param cuts     the cut surfaces those pieces come from
  /// @param warnings where to say that a "crack_tip" field has no front to act on (nullptr: nowhere)
  SceneCrackTip(const Scene& scene, const TetMesh& mesh, const MeshPieces& pieces, const CutSurfaces& cuts, std::ostream* warnings);
  SceneCrackTip(const SceneCrackTip&) = delete;
  SceneCrackTip& operator=(const SceneCrackTip&) = delete;

  /// The fronts of the cuts inside the mesh (found for "none" too).
  const CrackFronts& fronts() const { return fronts_; }
  /// Whether the scene asks for branch functions ("enrichment": "branch").
  bool branch() const { return branch_enrichment_.has_value(); }
  /// The rule that chose the branch nodes (meaningful when branch()).
  TipEnrichmentRule rule() const { return rule_; }
  /// r_e of the geometric rule (m); 0 for the topological rule and for "none".
  double radius() const { return radius_; }
  /// Whether the radius is the default (the scene gave none).
  bool default_radius() const { return default_radius_; }
  /// The enrichment the model takes: BranchEnrichment::sign with branch functions, chapter 4's
  /// make_surface_enrichment without.
  const SurfaceEnrichment& sign_enrichment() const { return branch() ? branch_enrichment_->sign : surface_enrichment_; }
  /// The node classification (nullptr for "none").
  const BranchEnrichment* branch_enrichment() const { return branch() ? &*branch_enrichment_ : nullptr; }
  /// What the model's last argument is: the branch functions, or nullptr for "none" and for a
  /// mesh in which no node is branch enriched (no front inside it).
  const CrackTipFunctions* tip_functions() const { return functions_ ? &*functions_ : nullptr; }
  /// The number of branch-enriched nodes (0 for "none").
  int num_branch_nodes() const { return branch() ? branch_enrichment_->num_branch_nodes() : 0; }

private:
  CrackFronts fronts_;
  TipEnrichmentRule rule_ = TipEnrichmentRule::geometric;
  double radius_ = 0.0;
  bool default_radius_ = false;
  std::optional<BranchEnrichment> branch_enrichment_;
  SurfaceEnrichment surface_enrichment_;
  std::optional<CrackTipFunctions> functions_;
};

} // namespace kerf
