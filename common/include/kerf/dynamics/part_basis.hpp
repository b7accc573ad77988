/// @file part_basis.hpp
/// @brief The change of basis from the shifted enrichment [u; a] to one value per part of each node's support (the phantom nodes' values), x = P w: the cure for what no diagonal preconditioner reaches.
#pragma once

#include "kerf/fem/dof_map.hpp"
#include "kerf/solve/linear_solver.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"
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

/// P on the free unknowns of `dofs` only, the basis in which chapters 6 and 7 precondition their
/// steps' conjugate gradients (LinearSolver::set_preconditioner_basis): rows and columns of the
/// free DOFs, identity on DOFs beyond the enrichments (crack-tip functions). A held enrichment
/// (a gripped node's, a sliver's) makes w_k = w_i and drops out; a free a_k of a held u_i is
/// w_k itself. Still invertible (unit triangular), so only the basis changes.
///
/// What it buys a step. Each w is the value of one part of one node's support, so a piece the
/// cuts freed from the body shares no w with it: S^T A S has no entry between the two, and
/// neither has S D^-1 S^T. Conjugate gradients then never move the piece while they correct the
/// body: a piece whose residual is zero when the solve starts (one in free fall, from the last
/// step's acceleration) stays exact to round-off, where in [u; a] the body's corrections move it
/// through the u_i the two share, by about the solver's tolerance. And the thin home part of a
/// node no longer shares its scale with the node's other parts (the conditioning above).
/// @param dofs the free and prescribed DOFs of all 3 num_dof_nodes unknowns (num_dof_nodes >=
///             num_nodes + the enrichments)
Eigen::SparseMatrix<double> free_part_basis(const SurfaceEnrichment& enrichment, Eigen::Index num_nodes, const DofMap& dofs);

/// free_part_basis of a cut body, with its components for "cg-jacobi" (PreconditionerBasis):
/// the w that phantom elements join, found by joining the DOF nodes of every piece's phantom
/// element (a held enrichment's phantom node is its node's, as in cut_xfem_unheld_pieces; a tet
/// with branch functions joins all its slots). A piece the cuts freed is then a component of its
/// own, which the body's iterations never move. Joining through prescribed DOF nodes too (a
/// clamp) merges more than the matrix couples, which is safe: fewer, larger systems.
PreconditionerBasis cut_body_preconditioner_basis(const CutXfemModel& model, const DofMap& dofs);

} // namespace kerf
