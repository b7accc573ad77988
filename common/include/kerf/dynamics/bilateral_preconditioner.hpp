/// @file bilateral_preconditioner.hpp
/// @brief Diagonal preconditioners applied on both sides, T^T A T y = T^T c, x = T y (Koschier et al. eqs. 23-27): Koschier's from the enrichment volumes, and plain Jacobi scaling beside it.
#pragma once

#include "kerf/solve/linear_solver.hpp"
#include "kerf/xfem/enrichment_volumes.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace kerf {

/// Koschier's diagonal T for the DOFs [u; a] of a cut body (3 (num_nodes + #enrichments)
/// entries, node-major as everywhere in Kerf):
///
///   T_{d_ik, d_ik} = 1 / sqrt(v_ik),   v_ik = V_{i,k,enr} / V_{i,supp},          (eqs. 26, 27)
///
/// the same value on the three components of enrichment k's DOF, and 1 on the standard DOFs
/// (the paper does not say; 1 is implied). Eq. 26 prints V_{i,j}: it means the ratio
/// v of eq. 27, which makes T independent of the body's size. The volumes
/// are those the rules' weights give (CutXfemModel::enrichment_volumes), as Koschier sums them.
///
/// Why it helps: the rows of an enrichment whose function acts on a small part v of its
/// node's support are small, of the order of v; scaling them by 1 / v brings them to the order
/// of the standard rows. It cannot cure an enrichment on a sliver far from its node, whose rows
/// fall faster than v (N_i is small there too), nor the near-dependence of u_i and a_ik when
/// the node's own part is the small one: eq. 22 constrains the former, nothing in
/// the paper the latter.
///
/// @param volumes   V_enr and V_supp of every enrichment
/// @param num_nodes the mesh's nodes (the standard DOF nodes, numbered before the enrichments)
/// @throws std::invalid_argument if an enrichment has v <= 0 (constrain it by eq. 22 first:
///         sliver_enrichments with epsilon 0 lists them)
Eigen::VectorXd koschier_preconditioner(const EnrichmentVolumes& volumes, Eigen::Index num_nodes);

/// Plain Jacobi scaling T_kk = 1 / sqrt(A_kk), which makes the diagonal of T^T A T all ones.
/// @param A symmetric with a positive diagonal
/// @throws std::invalid_argument if a diagonal entry is not positive
Eigen::VectorXd jacobi_preconditioner(const Eigen::SparseMatrix<double>& A);

/// T^T A T for the diagonal T = diag(t) (eq. 24's matrix): entry (i, j) is t_i A_ij t_j, so a
/// symmetric A stays symmetric (the reason for applying T on both sides).
Eigen::SparseMatrix<double> scale_bilaterally(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& t);

/// Solves A x = c (eq. 23) through the preconditioned system T^T A T y = T^T c (eq. 24) and
/// x = T y (eq. 25), A symmetric positive definite, with the solver `settings` choose.
Eigen::VectorXd solve_bilaterally_preconditioned(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& c,
                                                 const Eigen::VectorXd& t, const SolverSettings& settings);

} // namespace kerf
