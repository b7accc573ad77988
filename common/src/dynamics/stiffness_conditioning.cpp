#include "kerf/dynamics/stiffness_conditioning.hpp"

#include "kerf/dynamics/bilateral_preconditioner.hpp"
#include "kerf/dynamics/newton_matrix_conditioning.hpp"
#include "kerf/dynamics/part_basis.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/xfem/node_block_preconditioner.hpp"

#include <algorithm>
#include <limits>

namespace kerf {

namespace {

double condition(const Eigen::SparseMatrix<double>& A) { return spectral_condition_number(Eigen::MatrixXd(A)); }

// A full-size DOF-node transform (3 num_dof_nodes square) restricted to the free DOFs.
Eigen::SparseMatrix<double> restrict_square(const Eigen::SparseMatrix<double>& P, const DofMap& dofs) {
  std::vector<Eigen::Triplet<double>> entries;
  for (Eigen::Index c = 0; c < P.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(P, c); it; ++it) {
      const int i = dofs.free_index[static_cast<std::size_t>(it.row())], j = dofs.free_index[static_cast<std::size_t>(it.col())];
      if (i >= 0 && j >= 0) entries.emplace_back(i, j, it.value());
    }
  Eigen::SparseMatrix<double> P_ff(dofs.num_free, dofs.num_free);
  P_ff.setFromTriplets(entries.begin(), entries.end());
  return P_ff;
}

} // namespace

std::vector<int> dof_node_owners(const CutXfemModel& model) {
  const Eigen::Index N = model.mesh().num_nodes();
  std::vector<int> owner(static_cast<std::size_t>(model.num_dof_nodes()));
  for (Eigen::Index v = 0; v < N; ++v) owner[static_cast<std::size_t>(v)] = static_cast<int>(v);
  const SurfaceEnrichment& sign = model.enrichment();
  for (int k = 0; k < sign.num_enrichments(); ++k) owner[static_cast<std::size_t>(N + k)] = sign.enrichment_node[static_cast<std::size_t>(k)];
  for (int k = 0; k < static_cast<int>(model.num_branch_nodes()); ++k)
    for (int l = 0; l < 4; ++l)
      owner[static_cast<std::size_t>(model.branch_dof_node(k) + l)] = model.crack_tip()->enrichment.branch_node[static_cast<std::size_t>(k)];
  return owner;
}

Eigen::SparseMatrix<double> free_stiffness(const CutXfemModel& model, const DofMap& dofs) {
  SparseAssembler assembler(model.assembly_slots(), dofs);
  Eigen::VectorXd unused_rhs = Eigen::VectorXd::Zero(dofs.num_free);
  model.assemble_linear_stiffness(assembler, unused_rhs);
  return assembler.matrix();
}

StiffnessConditioning stiffness_conditioning(const CutXfemModel& model, const DofMap& dofs) {
  const Eigen::SparseMatrix<double> K = free_stiffness(model, dofs);
  const Eigen::Index N = model.mesh().num_nodes(), dof_nodes = model.num_dof_nodes();
  StiffnessConditioning result;
  result.free_dofs = dofs.num_free;
  result.branch_nodes = static_cast<int>(model.num_branch_nodes());
  const EnrichmentVolumes volumes = model.enrichment_volumes();
  result.sign_enrichments = static_cast<int>(volumes.enriched.size());
  for (Eigen::Index k = 0; k < result.sign_enrichments; ++k) result.smallest_fraction = std::min(result.smallest_fraction, volumes.fraction(k));

  result.plain = condition(K);
  result.jacobi = condition(scale_bilaterally(K, jacobi_preconditioner(K)));

  // Koschier's T on [u; a], padded with ones for the branch DOFs [b]. An enrichment without
  // volume must be constrained (the caller's DofMap); its entry is never used.
  EnrichmentVolumes with_volume = volumes;
  for (double& v : with_volume.enriched) v = std::max(v, std::numeric_limits<double>::min());
  Eigen::VectorXd t = Eigen::VectorXd::Ones(3 * dof_nodes);
  t.head(3 * (N + result.sign_enrichments)) = koschier_preconditioner(with_volume, N);
  result.koschier = condition(scale_bilaterally(K, dofs.restrict_to_free(t)));

  // The part basis on [u; a], the identity on [b].
  const Eigen::SparseMatrix<double> P_sign = part_basis(model.enrichment(), N);
  std::vector<Eigen::Triplet<double>> entries;
  for (Eigen::Index c = 0; c < P_sign.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(P_sign, c); it; ++it) entries.emplace_back(it.row(), it.col(), it.value());
  for (Eigen::Index i = P_sign.rows(); i < 3 * dof_nodes; ++i) entries.emplace_back(i, i, 1.0);
  Eigen::SparseMatrix<double> P(3 * dof_nodes, 3 * dof_nodes);
  P.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SparseMatrix<double> P_ff = restrict_square(P, dofs);
  const Eigen::SparseMatrix<double> B = P_ff.transpose() * K * P_ff;
  result.part_jacobi = B.diagonal().minCoeff() > 0.0 ? condition(scale_bilaterally(B, jacobi_preconditioner(B)))
                                                     : std::numeric_limits<double>::infinity();

  // Bechet's node blocks: each free DOF with the mesh node it belongs to.
  const std::vector<int> owner = dof_node_owners(model);
  std::vector<int> group(static_cast<std::size_t>(dofs.num_free));
  for (Eigen::Index d = 0; d < 3 * dof_nodes; ++d)
    if (const int f = dofs.free_index[static_cast<std::size_t>(d)]; f >= 0)
      group[static_cast<std::size_t>(f)] = owner[static_cast<std::size_t>(d / 3)];
  const Eigen::SparseMatrix<double> S = node_block_preconditioner(K, group);
  result.node_block = condition(Eigen::SparseMatrix<double>(S.transpose() * K * S));
  return result;
}

} // namespace kerf
