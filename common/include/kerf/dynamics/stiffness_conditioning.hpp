/// @file stiffness_conditioning.hpp
/// @brief The 2-norm condition number of the static XFEM stiffness K_ff with crack-tip (branch) DOFs, bare and with the cures: Jacobi scaling, Koschier's bilateral diagonal (Koschier et al. eqs. 23-27), the part basis and Bechet's node blocks.
///
/// Chapter 6 measures the Newton matrix M + dt^2 K of a free body (newton_matrix_conditioning.hpp);
/// chapter 5's question is the static stiffness of a held body once the branch DOFs are in: how
/// kappa grows with the geometric enrichment radius, and as the front nears a node or a face.
/// The variants, each the condition number of S^T K_ff S for a different S:
/// - plain:      S = I;
/// - jacobi:     S = diag(K_ff)^-1/2;
/// - koschier:   S = Koschier's T of eqs. 26-27 on the sign DOFs (v = V_enr / V_supp from the
///               rules' weights), 1 on the standard and on the branch DOFs: Koschier's paper has
///               no branch functions, so it gives them nothing;
/// - part_jacobi: the part basis (part_basis.hpp) on the sign DOFs, the identity on the branch
///               DOFs, then Jacobi;
/// - node_block: Bechet et al.'s node blocks (node_block_preconditioner.hpp), every free DOF
///               grouped with its mesh node (a sign or branch DOF with the node it enriches).
/// Dense eigenvalues (spectral_condition_number): for small bodies only.
#pragma once

#include "kerf/fem/dof_map.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"

#include <Eigen/SparseCore>
#include <vector>

namespace kerf {

/// The condition numbers of one held cut body's K_ff.
struct StiffnessConditioning {
  double plain = 0.0;      ///< kappa(K_ff)
  double jacobi = 0.0;     ///< kappa(T K_ff T), T = diag(K_ff)^-1/2
  double koschier = 0.0;   ///< kappa(T K_ff T), T of eqs. 26-27 on the sign DOFs, 1 elsewhere
  double part_jacobi = 0.0; ///< kappa of the part basis, Jacobi-scaled
  double node_block = 0.0; ///< kappa(S^T K_ff S), S of Bechet's node blocks
  double smallest_fraction = 1.0; ///< the smallest V_enr / V_supp of a sign enrichment (1 if none)
  int free_dofs = 0;       ///< rows of K_ff
  int branch_nodes = 0;    ///< branch-enriched nodes
  int sign_enrichments = 0; ///< sign enrichments
};

/// The mesh node each DOF node of `model` belongs to (num_dof_nodes() entries): a node itself,
/// an enrichment's node, a branch function's node.
std::vector<int> dof_node_owners(const CutXfemModel& model);

/// K_ff of the linear XFEM stiffness on the free DOFs of `dofs`.
Eigen::SparseMatrix<double> free_stiffness(const CutXfemModel& model, const DofMap& dofs);

/// Assembles K_ff and measures the five condition numbers.
/// @param dofs a DofMap that holds every piece (cut_xfem_unheld_pieces empty), so K_ff is
///             positive definite; every sign enrichment it leaves free must have V_enr > 0
StiffnessConditioning stiffness_conditioning(const CutXfemModel& model, const DofMap& dofs);

} // namespace kerf
