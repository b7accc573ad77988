/// @file lumped_mass.hpp
/// @brief Lumped masses of a cut body's [u; a] unknowns, and the body loads that go with them: row-sum, HRZ and
///        "virtual tet" lumping piece by piece, and Paper 000 eqs. 81-82 as printed.
#pragma once

#include "kerf/quadrature/piece_quadrature_rule.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"
#include "kerf/xfem/split_tet_masses.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace kerf {

/// How the mass of a cut body is lumped.
///
/// The first three lump each piece's phantom element on its own (cut_xfem_model.hpp: on piece
/// p the field is an ordinary element field u_p = T_p u_e), with a diagonal D_p, and scatter it
/// as the consistent mass is scattered:
///
///   M_lumped = sum_e sum_p T_p^T (D_p kron I_3) T_p.
///
/// The result is diagonal in the phantom unknowns u_p, not in [u; a]: a node with an enrichment
/// active on piece p couples its u and its a (a 2x2 block of 3x3 identities per enrichment,
/// e.g. (m_home + m_other, m_other; m_other, m_other) for one enrichment). Keeping that
/// coupling is what makes every piece's mass and free fall exact (notes 6.2): a rigid
/// translation t of piece p alone sets u_p = t at all n phantom nodes, and its kinetic energy
/// is (1/2) (sum_a D_p,aa) |t|^2 = (1/2) rho V_p |t|^2 for all three.
///
/// The fourth, eqs. 81-82 as printed, is diagonal in [u; a] and drops that coupling.
///
/// Crack-tip functions (chapter 5). A tet with branch functions is not lumped: it keeps its
/// consistent mass (cut_xfem_mass.hpp: rho sum_q w_q g_q g_q^T over its front or blending rule),
/// branch rows and columns and their coupling to the phantom unknowns included; every other tet
/// is lumped as above. Why:
/// - the branch functions are no partition of unity: no row sum or "total mass" of theirs means
///   anything to scale a diagonal by;
/// - the coupling rho int phi_j N_a is what keeps free fall exact with the branch rows of the
///   body force that statics uses (rho int phi_j g, notes 5.4): "every phantom node at g,
///   b'' = 0" then solves M_lumped a = f in the branch rows too (sum_a N_a = 1); a diagonal
///   branch block without it would accelerate a falling body's branch DOFs at
///   (rho int phi_j g) / (rho int phi_j^2);
/// - lumping only the phantom part beside a consistent branch block is not positive definite on
///   Tet10: the lumped phantom masses need not dominate the consistent ones, and the Schur
///   complement of the branch block goes negative (measured on the slab of
///   tests/dynamics/test_branch_mass.cpp: smallest eigenvalue -0.023 (hrz) and -0.033
///   (virtual_tet) of the largest; positive on Tet4). A sum of consistent element masses and
///   lumped ones is positive semi-definite whatever the order.
/// The body's mass, a rigid translation's kinetic energy (b = 0) and every piece's mass stay exact
/// (both parts are); the matrix is still the factorised one of chapter 6's integrators (it was
/// not diagonal in [u; a] before either). Eqs. 81-82 have no branch rows: they refuse a model
/// with crack-tip functions.
enum class LumpingScheme {
  /// D_p,aa = rho int_p N_a: the rows of the piece's consistent mass summed. The piece's mass
  /// and first moment are exact (sum_a N_a = 1, sum_a N_a x_a = x), so its centre of mass is
  /// too. Positive for Tet4; a Tet10's corner rows sum to a negative number (-rho V / 20 for a
  /// whole tet), so do not use it for Tet10.
  row_sum,
  /// Hinton, Rock and Zienkiewicz (1976): the diagonal of the piece's consistent mass, scaled to
  /// the piece's mass rho V_p. Always positive (Tet10 too); exact mass, not the centre of mass.
  hrz,
  /// The piece as its own "virtual tet": D_p,aa = rho V_p / n at every node (notes 6.2, the
  /// cure of eqs. 81-82, phantom-node lumping as in Song, Areias and Belytschko 2006). Exact mass;
  /// the piece's lumped centre of mass is the element's centroid. The one Kerf recommends (notes
  /// 6.7, item 4): it is positive for Tet4 and Tet10 alike.
  virtual_tet,
  /// Paper 000 eq. 81, M^uu_ii = m / n, and eq. 82, M^aa_kk = sum over the pieces p on which
  /// enrichment k is active of (V_p / V) (m / n), m the element mass; M^ua = 0. A piece
  /// separated from the rest moves with wrong inertia: with k of the n nodes on its side, its
  /// translation has kinetic energy (1/2) (m / n) (k + k V_other / V + (n - k) V_p / V) |t|^2
  /// (the whole element mass m for a Tet4 cut 2:2, whatever V_p) [derived, notes 6.2].
  schoch_eq_81_82,
};

/// The lumped mass on all 3 num_dof_nodes() DOFs (no Dirichlet elimination), symmetric.
/// @param rule the rule of each piece of a split tet; asked for degree 2 (Tet4) or 4 (Tet10), as
///             assemble_cut_xfem_mass does, and needed exact for it by row_sum and hrz (the
///             piece's volume only, degree 0, for virtual_tet and schoch_eq_81_82)
Eigen::SparseMatrix<double> lump_cut_xfem_mass(const CutXfemModel& model, double density, LumpingScheme scheme,
                                               const PieceRuleFunction& rule);
/// The same with the split tets' piece masses from `masses` (made for this model; chapter 7
/// keeps them from one model to the next of a growing cut).
Eigen::SparseMatrix<double> lump_cut_xfem_mass(const CutXfemModel& model, double density, LumpingScheme scheme,
                                               const SplitTetMasses& masses);

/// The body load rho g that goes with `scheme` (3 num_dof_nodes()).
///
/// For the three piece-wise schemes it is the lumped one, sum_p T_p^T (D_p 1 kron g): each
/// phantom node pulled by its own mass, so that M_lumped a = f has the solution "every phantom
/// node accelerates at g" (u'' = g, a'' = 0), exactly, however the body is cut.
/// In a tet with branch functions it is the consistent one, rho int g_s g on every slot
/// (CutXfemModel::gravity_load's share), which is the same rule: that tet's mass times "u'' = g".
/// For schoch_eq_81_82 it is Paper 000's consistent body load (eq. 19, sum_p T_p^T int_p N^T rho g,
/// CutXfemModel::gravity_load). With eqs. 81-82, on a single cut Tet4, it accelerates u at g but
/// an enrichment k at 4 g mean_p(N_a) (the mean of its node's shape function N_a over the piece p
/// where it is active), so a body in free fall opens at the cut (notes 6.2). Paulus's choice, no
/// load on a, keeps free fall right, but a piece hanging from the rest then falls with the wrong
/// acceleration (notes 6.2); Kerf does not offer it.
Eigen::VectorXd lumped_gravity_load(const CutXfemModel& model, double density, const Eigen::Vector3d& g,
                                    LumpingScheme scheme, const PieceRuleFunction& rule);

} // namespace kerf
