#include "kerf/dynamics/part_basis.hpp"

#include <vector>

namespace kerf {

Eigen::SparseMatrix<double> part_basis(const SurfaceEnrichment& enrichment, Eigen::Index num_nodes) {
  const Eigen::Index n = 3 * (num_nodes + enrichment.num_enrichments());
  std::vector<Eigen::Triplet<double>> entries;
  for (Eigen::Index d = 0; d < n; ++d) entries.emplace_back(d, d, 1.0);
  for (Eigen::Index k = 0; k < enrichment.num_enrichments(); ++k) {
    const Eigen::Index i = enrichment.enrichment_node[static_cast<std::size_t>(k)];
    for (int p = 0; p < 3; ++p) entries.emplace_back(3 * (num_nodes + k) + p, 3 * i + p, -1.0); // a_k = w_k - w_i
  }
  Eigen::SparseMatrix<double> P(n, n);
  P.setFromTriplets(entries.begin(), entries.end());
  return P;
}

} // namespace kerf
