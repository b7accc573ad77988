#include "kerf/dynamics/part_basis.hpp"

#include <numeric>
#include <stdexcept>
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

Eigen::SparseMatrix<double> free_part_basis(const SurfaceEnrichment& enrichment, Eigen::Index num_nodes, const DofMap& dofs) {
  const auto n = static_cast<Eigen::Index>(dofs.free_index.size());
  const Eigen::Index sign_dofs = 3 * (num_nodes + enrichment.num_enrichments());
  if (n < sign_dofs) throw std::invalid_argument("free_part_basis: the DOF map has fewer DOFs than the nodes and their enrichments");
  const Eigen::SparseMatrix<double> P = part_basis(enrichment, num_nodes);
  std::vector<Eigen::Triplet<double>> entries;
  const auto add = [&](Eigen::Index row, Eigen::Index column, double value) {
    const int i = dofs.free_index[static_cast<std::size_t>(row)], j = dofs.free_index[static_cast<std::size_t>(column)];
    if (i >= 0 && j >= 0) entries.emplace_back(i, j, value);
  };
  for (Eigen::Index c = 0; c < P.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(P, c); it; ++it) add(it.row(), it.col(), it.value());
  for (Eigen::Index d = sign_dofs; d < n; ++d) add(d, d, 1.0);
  Eigen::SparseMatrix<double> P_ff(dofs.num_free, dofs.num_free);
  P_ff.setFromTriplets(entries.begin(), entries.end());
  return P_ff;
}

PreconditionerBasis cut_body_preconditioner_basis(const CutXfemModel& model, const DofMap& dofs) {
  const TetMesh& mesh = model.mesh();
  const Eigen::Index N = mesh.num_nodes();
  const SurfaceEnrichment& enrichment = model.enrichment();
  PreconditionerBasis basis{free_part_basis(enrichment, N, dofs), {}};
  // Union-find over the DOF nodes, which number the basis's w as they number the unknowns.
  std::vector<int> parent(static_cast<std::size_t>(model.num_dof_nodes()));
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int v) {
    while (parent[static_cast<std::size_t>(v)] != v) v = parent[static_cast<std::size_t>(v)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(v)])];
    return v;
  };
  const auto join = [&](int a, int b) { parent[static_cast<std::size_t>(root(a))] = root(b); };
  const auto prescribed = [&](int v) {
    for (int c = 0; c < 3; ++c)
      if (dofs.free_index[static_cast<std::size_t>(3 * v + c)] >= 0) return false;
    return true;
  };
  // The DOF node that carries a phantom node's value: a held enrichment's value is its node's.
  const auto carrier = [&](int v) { return v >= N && prescribed(v) ? enrichment.enrichment_node[static_cast<std::size_t>(v - N)] : v; };
  const int n = mesh.nodes_per_tet();
  const TetMatrix& slots = model.assembly_slots();
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    if (model.has_branch_functions(t)) {
      for (Eigen::Index s = 1; s < slots.cols() && slots(t, s) >= 0; ++s) join(carrier(slots(t, 0)), carrier(slots(t, s)));
      continue;
    }
    for (int p = 0; p < model.num_integrated_pieces(t); ++p) {
      const int first = carrier(model.phantom_node(t, p, 0));
      for (int a = 1; a < n; ++a) join(first, carrier(model.phantom_node(t, p, a)));
    }
  }
  // Labels 0 .. C - 1 on the free unknowns, in order of first appearance.
  std::vector<int> label(parent.size(), -1);
  basis.component.assign(static_cast<std::size_t>(dofs.num_free), 0);
  int count = 0;
  for (std::size_t d = 0; d < dofs.free_index.size(); ++d) {
    const int f = dofs.free_index[d];
    if (f < 0) continue;
    int& l = label[static_cast<std::size_t>(root(static_cast<int>(d / 3)))];
    if (l < 0) l = count++;
    basis.component[static_cast<std::size_t>(f)] = l;
  }
  return basis;
}

} // namespace kerf
