#include "kerf/scene/scene_crack_tip.hpp"

#include "kerf/xfem/tip_enrichment_radius.hpp"

namespace kerf {

SceneCrackTip::SceneCrackTip(const Scene& scene, const TetMesh& mesh, const MeshPieces& pieces, const CutSurfaces& cuts,
                             std::ostream* warnings)
    : fronts_(find_crack_fronts(mesh, cuts)) {
  if (scene.crack_tip.given && fronts_.empty() && warnings)
    *warnings << "warning: " << scene.source.string() << ": crack_tip: no cut ends inside the mesh, so there is no front to enrich\n";
  if (scene.crack_tip.enrichment == "none") {
    surface_enrichment_ = make_surface_enrichment(mesh, pieces);
    return;
  }
  default_radius_ = !scene.crack_tip.radius.has_value();
  radius_ = default_radius_ ? default_tip_enrichment_radius(mesh, fronts_) : *scene.crack_tip.radius;
  rule_ = radius_ > 0.0 ? TipEnrichmentRule::geometric : TipEnrichmentRule::topological;
  branch_enrichment_ = make_branch_enrichment(mesh, pieces, fronts_, rule_, radius_);
  // The model's defaults for the front and blending rules: the collapsed rule, exact in r, in the
  // tets the front crosses (front_quadrature.hpp), graded Gauss rules in the others.
  if (branch_enrichment_->num_branch_nodes() > 0) functions_.emplace(CrackTipFunctions{.enrichment = *branch_enrichment_, .fronts = fronts_});
}

} // namespace kerf
