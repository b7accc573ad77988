/// @file node_block_preconditioner.hpp
/// @brief The node-block preconditioner of Bechet et al. (2005): each node's DOFs (standard, sign and branch) orthonormalised together by the Cholesky factor of their diagonal block, x = S y with S^T A S having identity diagonal blocks.
///
/// Why a block and not a diagonal. Away from the front the four branch functions of a node are
/// nearly dependent on each other and on the node's standard hat: across a support of size h at
/// a distance R from the front, F_l(x) - F_l(x_i) is nearly grad F_l . (x - x_i), and the four
/// gradients span only the two directions a and b, so two combinations of the four functions are
/// of second order in h / R only, and what is left is nearly the linear field that the standard
/// hats already hold. A diagonal T (Jacobi, or Koschier's eq. 26 from the volumes) rescales each
/// DOF alone and cannot undo a near-dependence inside one node's DOFs. The Cholesky factor of the
/// node's block A_ii = L_i L_i^T does: with S_ii = L_i^-T the block becomes the identity, which
/// is Bechet, Minnebo, Moes and Burgardt's "preconditioner" for geometric enrichment (Int. J.
/// Numer. Meth. Engng 64, 2005, section 4). Dependence between DIFFERENT nodes' functions is
/// left, which is why it does not bring kappa back to the uncut mesh's value.
///
/// S is block diagonal and invertible, so S^T A S y = S^T c, x = S y is the same system
/// (Koschier's eqs. 24-25 with a block T), still symmetric.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace kerf {

/// S = blockdiag(L_g^-T) over the groups of `group` (one entry per row of A: the mesh node a
/// free DOF belongs to; DOFs of one group need not be contiguous), A_gg = L_g L_g^T.
/// @param A     symmetric positive definite (only its diagonal blocks are read)
/// @param group per row of A, the group (node) it belongs to, >= 0
/// @throws std::invalid_argument if the sizes differ, a group is negative, or a diagonal block
///         is not positive definite (the message names the group)
Eigen::SparseMatrix<double> node_block_preconditioner(const Eigen::SparseMatrix<double>& A, const std::vector<int>& group);

} // namespace kerf
