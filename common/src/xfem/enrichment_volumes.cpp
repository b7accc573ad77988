#include "kerf/xfem/enrichment_volumes.hpp"

#include <cmath>

namespace kerf {

EnrichmentVolumes enrichment_volumes(const TetMesh& mesh, const MeshPieces& pieces, const SurfaceEnrichment& enrichment,
                                     const PieceVolumeFunction& piece_volume) {
  const auto M = static_cast<std::size_t>(enrichment.num_enrichments());
  EnrichmentVolumes volumes{std::vector<double>(M, 0.0), std::vector<double>(M, 0.0)};
  const int n = mesh.nodes_per_tet();
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    if (enrichment.active[static_cast<std::size_t>(t)].empty()) continue; // no enriched node: no support counted here
    const int np = pieces.num_pieces(t);
    double tet_volume = 0.0;
    for (int p = 0; p < np; ++p) tet_volume += piece_volume(t, p);
    for (int a = 0; a < n; ++a) {
      const int i = mesh.tets(t, a);
      // Every enrichment of node i has this tet in its support, whichever part it is active on.
      for (int k = enrichment.first_enrichment[static_cast<std::size_t>(i)]; k < enrichment.first_enrichment[static_cast<std::size_t>(i) + 1]; ++k)
        volumes.support[static_cast<std::size_t>(k)] += tet_volume;
      for (int p = 0; p < np; ++p) {
        const int k = enrichment.active_enrichment(pieces, t, a, p);
        if (k >= 0) volumes.enriched[static_cast<std::size_t>(k)] += piece_volume(t, p);
      }
    }
  }
  return volumes;
}

std::vector<int> sliver_enrichments(const EnrichmentVolumes& volumes, double epsilon) {
  std::vector<int> constrained;
  for (std::size_t k = 0; k < volumes.enriched.size(); ++k) {
    const double fraction = volumes.fraction(static_cast<Eigen::Index>(k));
    // Not "fraction < epsilon" alone: a fraction that is NaN (an empty support cannot happen,
    // but a rule's NaN weights could) must be constrained too.
    if (!(fraction >= epsilon) || volumes.enriched[k] <= 0.0) constrained.push_back(static_cast<int>(k));
  }
  return constrained;
}

} // namespace kerf
