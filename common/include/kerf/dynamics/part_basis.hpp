/// @file part_basis.hpp
/// @brief The change of basis from the shifted enrichment [u; a] to one value per part of each node's support (the phantom nodes' values), x = P w: the cure for what no diagonal preconditioner reaches.
#pragma once

#include "kerf/xfem/surface_enrichment.hpp"

#include <Eigen/SparseCore>

namespace kerf {

/// P (3 (num_nodes + #enrichments) square, node-major) with x = P w, where w holds, for every
/// node i, its value w_i on its home part and, for every enrichment k of it, the value w_k on
/// part k (chapter 3's phantom node values):
///
///   u_i = w_i,   a_k = w_k - w_i   (k an enrichment of node i).
///
/// The field is the same, sum_i N_i (u_i + sum_k psi_i^k a_i^k) = sum over parts of N_i w, so P
/// is invertible and only the basis changes: from {N_i, N_i psi_i^k} to {N_i on the home part,
/// N_i on part k}, functions with disjoint supports. Why it matters for conditioning: when a
/// node's home part is a thin sliver, N_i and N_i psi_i^k are nearly the same function (they
/// differ on the sliver only), so A = M + dt^2 K has an eigenvalue ~ the sliver's relative
/// volume against O(1) diagonals, which no diagonal T can lift (Koschier's eqs. 26-27 cannot:
/// v_ik of such an enrichment is near 1, and eq. 22 never constrains it). In the part basis
/// those two functions are apart, and Jacobi scaling of P^T A P then keeps kappa at the uncut
/// mesh's value (chapter 6's conditioning study). Applied as S = P T, S^T A S y = S^T c,
/// x = S y: eqs. 24-25 with a non-diagonal, still symmetric, preconditioner.
/// @param enrichment the enrichments (which node each belongs to)
/// @param num_nodes  the mesh's nodes, numbered before the enrichments
Eigen::SparseMatrix<double> part_basis(const SurfaceEnrichment& enrichment, Eigen::Index num_nodes);

} // namespace kerf
