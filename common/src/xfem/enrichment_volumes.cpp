#include "kerf/xfem/enrichment_volumes.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace kerf {

double EnrichmentVolumes::home_fraction(Eigen::Index k) const {
  const int i = node[static_cast<std::size_t>(k)];
  // The node's enrichments are numbered consecutively (SurfaceEnrichment): walk to both ends.
  double far = 0.0;
  for (Eigen::Index l = k; l >= 0 && node[static_cast<std::size_t>(l)] == i; --l) far += enriched[static_cast<std::size_t>(l)];
  for (auto l = static_cast<std::size_t>(k) + 1; l < node.size() && node[l] == i; ++l) far += enriched[l];
  const double V_supp = support[static_cast<std::size_t>(k)];
  return (V_supp - far) / V_supp;
}

EnrichmentVolumes enrichment_volumes(const TetMesh& mesh, const MeshPieces& pieces, const SurfaceEnrichment& enrichment,
                                     const IntegratedPieceVolumes& piece_volumes) {
  const auto M = static_cast<std::size_t>(enrichment.num_enrichments());
  EnrichmentVolumes volumes{std::vector<double>(M, 0.0), std::vector<double>(M, 0.0), enrichment.enrichment_node};
  const int n = mesh.nodes_per_tet();
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    if (enrichment.active[static_cast<std::size_t>(t)].empty()) continue; // no enriched node: no support counted here
    const int np = pieces.num_pieces(t);
    const std::vector<double> integrated = piece_volumes(t);
    const bool by_pieces = static_cast<int>(integrated.size()) == np;
    if (!by_pieces && integrated.size() != 1)
      throw std::invalid_argument("enrichment_volumes: tet " + std::to_string(t) + " reports " + std::to_string(integrated.size()) +
                                  " integrated volumes for " + std::to_string(np) + " pieces");
    double tet_volume = 0.0;
    for (const double v : integrated) tet_volume += v;
    for (int a = 0; a < n; ++a) {
      const int i = mesh.tets(t, a);
      // Every enrichment of node i has this tet in its support, whichever part it is active on.
      for (int k = enrichment.first_enrichment[static_cast<std::size_t>(i)]; k < enrichment.first_enrichment[static_cast<std::size_t>(i) + 1]; ++k)
        volumes.support[static_cast<std::size_t>(k)] += tet_volume;
      for (int p = 0; p < np; ++p) {
        const int k = enrichment.active_enrichment(pieces, t, a, p);
        if (k < 0) continue;
        // An enrichment acting on a piece of a tet integrated whole would be integrated nowhere.
        if (!by_pieces)
          throw std::invalid_argument("enrichment_volumes: an enrichment acts on piece " + std::to_string(p) + " of tet " + std::to_string(t) +
                                      ", which is integrated whole");
        volumes.enriched[static_cast<std::size_t>(k)] += integrated[static_cast<std::size_t>(p)];
      }
    }
  }
  return volumes;
}

std::vector<int> sliver_enrichments(const EnrichmentVolumes& volumes, double epsilon) {
  std::vector<int> constrained;
  const std::size_t M = volumes.enriched.size();
  for (std::size_t first = 0; first < M;) {
    // The enrichments of one node: [first, last).
    std::size_t last = first + 1;
    while (last < M && volumes.node[last] == volumes.node[first]) ++last;
    // The home part a sliver: hold the enrichment of the largest part (the first of equals).
    std::size_t largest = first;
    for (std::size_t k = first + 1; k < last; ++k)
      if (volumes.enriched[k] > volumes.enriched[largest]) largest = k;
    const double home = volumes.home_fraction(static_cast<Eigen::Index>(first));
    for (std::size_t k = first; k < last; ++k) {
      const double fraction = volumes.fraction(static_cast<Eigen::Index>(k));
      // Not "fraction < epsilon" alone: a fraction that is NaN (an empty support cannot happen,
      // but a rule's NaN weights could) must be constrained too.
      const bool far_sliver = !(fraction >= epsilon) || volumes.enriched[k] <= 0.0;
      // (epsilon = 0 holds no home part: it always holds its node, so some volume, which a
      // fraction at round-off, V_supp minus the parts' sum, could hide.)
      const bool home_sliver = k == largest && epsilon > 0.0 && !(home >= epsilon);
      if (far_sliver || home_sliver) constrained.push_back(static_cast<int>(k));
    }
    first = last;
  }
  return constrained;
}

} // namespace kerf
