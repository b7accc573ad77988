/// @file lumped_mass.hpp
/// @brief Lumped masses of a cut body's [u; a] unknowns, and the body loads that go with them: Bernstein, row-sum,
///        HRZ and "virtual tet" lumping piece by piece, and Schoch et al.'s eqs. 81-82 as printed.
#pragma once

#include "kerf/quadrature/piece_quadrature_rule.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"
#include "kerf/xfem/split_tet_masses.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace kerf {

/// How the mass of a cut body is lumped.
///
/// The first four lump each piece's phantom element on its own (cut_xfem_model.hpp: on piece
/// p the field is an ordinary element field u_p = T_p u_e), with a diagonal D_p, and scatter it
/// as the consistent mass is scattered:
///
///   M_lumped = sum_e sum_p T_p^T (D_p kron I_3) T_p.
///
/// The result is diagonal in the phantom unknowns u_p, not in [u; a]: a node with an enrichment
/// active on piece p couples its u and its a (a 2x2 block of 3x3 identities per enrichment,
/// e.g. (m_home + m_other, m_other; m_other, m_other) for one enrichment). Keeping that
/// coupling is what makes every piece's mass and free fall exact: a rigid translation t of
/// piece p alone sets u_p = t at all n phantom nodes, and its kinetic energy is
/// (1/2) (sum_a D_p,aa) |t|^2 = (1/2) rho V_p |t|^2 for all four.
///
/// What a diagonal can get right on a piece p: its mass, sum_a D_a = rho V_p, and its first
/// moment, sum_a D_a X_a = rho int_p x (X_a the phantom nodes' rest positions, the element's
/// nodes), which puts the piece's weight at its own centre of mass. The first moment is what
/// a hanging piece's rest depends on: a piece turned rigidly by R about a point h moves its
/// phantom nodes to h + R (X_a - h), so the lumped weights' moment about h is
/// (R (sum_a D_a X_a - rho V_p h)) x g, the true one exactly when the first moment is. No
/// diagonal keeps the second moments (a piece's rotational inertia).
///
/// Crack-tip functions (chapter 5). A tet with branch functions is not lumped: it keeps its
/// consistent mass (cut_xfem_mass.hpp: rho sum_q w_q g_q g_q^T over its front or blending rule),
/// branch rows and columns and their coupling to the phantom unknowns included; every other tet
/// is lumped as above. Why:
/// - the branch functions are no partition of unity: no row sum or "total mass" of theirs means
///   anything to scale a diagonal by;
/// - the coupling rho int phi_j N_a is what keeps free fall exact with the branch rows of the
///   body force that statics uses (rho int phi_j g): "every phantom node at g, b'' = 0" then
///   solves M_lumped a = f in the branch rows too (sum_a N_a = 1); a diagonal branch block
///   without it would accelerate a falling body's branch DOFs at
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
  /// D_p,i = rho int_p B_i: the row sums of the piece's mass in the Bernstein basis B_i of the
  /// element's degree, one polynomial per node. In barycentric coordinates L: on a Tet4
  /// B_a = L_a = N_a (this is row_sum); on a Tet10 B_a = L_a^2 at corner a and B_ab = 2 L_a L_b
  /// at the node of edge ab. What a scene's "lumped" means.
  ///
  /// Exact: the piece's mass and first moment. The B_i sum to 1, and sum_i B_i X_i = x because
  /// the nodes of a straight-edged tet (Kerf's tets all are: check_tet_mesh.hpp) are the
  /// Bernstein basis's domain points (corners, and edge midpoints for degree 2). Positive: each
  /// B_i is positive inside the tet, and a piece has volume. So a piece hangs with its own
  /// centre of mass under its support, and with the load below it falls at g.
  ///
  /// Computed from the Lagrange row sums r_i = rho int_p N_i, which the Tet10 basis turns into
  /// Bernstein's by B_a = N_a + (N_ab + N_ac + N_ad) / 4 and B_ab = N_ab / 2: every edge node
  /// keeps half its row sum and gives a quarter to each end (mass and first moment unchanged,
  /// the node being the ends' midpoint). A whole Tet4 gets rho V / 4 at every node, a whole
  /// Tet10 rho V / 10, as virtual_tet gives them.
  ///
  /// What it costs: a phantom node far from its piece gets little mass (int_p L_a is small when
  /// the piece lies near the face opposite corner a), so the piece's highest frequency grows as
  /// the cut nears a node and the central difference's critical step shrinks; virtual_tet keeps
  /// each piece's stiffness-to-mass ratio that of its whole element. On a Tet4 no diagonal has
  /// both: four positive weights with the piece's mass and first moment are unique, the row sums.
  bernstein,
  /// D_p,aa = rho int_p N_a: the rows of the piece's consistent mass summed. The piece's mass
  /// and first moment are exact (sum_a N_a = 1, sum_a N_a x_a = x), so its centre of mass is
  /// too. Positive for Tet4, where it is bernstein; a Tet10's corner rows sum to a negative
  /// number (-rho V / 20 for a whole tet), so do not use it for Tet10.
  row_sum,
  /// Hinton, Rock and Zienkiewicz (1976): the diagonal of the piece's consistent mass, scaled to
  /// the piece's mass rho V_p. Always positive (Tet10 too); exact mass, not the centre of mass.
  hrz,
  /// The piece as its own "virtual tet": D_p,aa = rho V_p / n at every node (phantom-node
  /// lumping as in Song, Areias and Belytschko 2006), what a scene's "lumped" meant before
  /// bernstein. Exact mass; the piece's weight acts at its element's centroid, not at its own
  /// centre of mass, so a hanging piece rests turned too far (Koschier et al.'s hinged cube
  /// with the slice [0, 0.2]: 30.96 degrees instead of atan 0.2 = 11.31, chapter 6's results).
  /// Each piece keeps its whole element's stiffness-to-mass ratio, so a cut does not lower the
  /// central difference's critical step.
  virtual_tet,
  /// Schoch et al. 2013, eq. 81, M^uu_ii = m / n, and eq. 82, M^aa_kk = sum over the pieces p on
  /// which enrichment k is active of (V_p / V) (m / n), m the element mass; M^ua = 0. A piece
  /// separated from the rest moves with wrong inertia: with k of the n nodes on its side, its
  /// translation has kinetic energy (1/2) (m / n) (k + k V_other / V + (n - k) V_p / V) |t|^2
  /// (the whole element mass m for a Tet4 cut 2:2, whatever V_p) [derived].
  schoch_eq_81_82,
};

/// The lumped mass on all 3 num_dof_nodes() DOFs (no Dirichlet elimination), symmetric.
/// @param rule the rule of each piece of a split tet; asked for degree 2 (Tet4) or 4 (Tet10), as
///             assemble_cut_xfem_mass does, and needed exact for it by bernstein, row_sum and hrz
///             (the piece's volume only, degree 0, for virtual_tet and schoch_eq_81_82)
Eigen::SparseMatrix<double> lump_cut_xfem_mass(const CutXfemModel& model, double density, LumpingScheme scheme,
                                               const PieceRuleFunction& rule);
/// The same with the split tets' piece masses from `masses` (made for this model; chapter 7
/// keeps them from one model to the next of a growing cut).
Eigen::SparseMatrix<double> lump_cut_xfem_mass(const CutXfemModel& model, double density, LumpingScheme scheme,
                                               const SplitTetMasses& masses);

/// The body load rho g that goes with `scheme` (3 num_dof_nodes()).
///
/// For the four piece-wise schemes it is the lumped one, sum_p T_p^T (D_p 1 kron g): each
/// phantom node pulled by its own mass, so that M_lumped a = f has the solution "every phantom
/// node accelerates at g" (u'' = g, a'' = 0), exactly, however the body is cut. Its resultant
/// on a piece is rho V_p g, and with bernstein or row_sum its moment is the true one
/// (rho int_p x) x g; on a Tet4 bernstein's is the consistent load rho int_p N_a g itself.
/// In a tet with branch functions it is the consistent one, rho int g_s g on every slot
/// (CutXfemModel::gravity_load's share), which is the same rule: that tet's mass times "u'' = g".
/// For schoch_eq_81_82 it is Schoch et al.'s consistent body load (eq. 19,
/// sum_p T_p^T int_p N^T rho g, CutXfemModel::gravity_load). With eqs. 81-82, on a single cut
/// Tet4, it accelerates u at g but an enrichment k at 4 g mean_p(N_a) (the mean of its node's
/// shape function N_a over the piece p where it is active), so a body in free fall opens at the
/// cut. Paulus's choice, no load on a, keeps free fall right, but a piece hanging from the rest
/// then falls with the wrong acceleration; Kerf does not offer it.
Eigen::VectorXd lumped_gravity_load(const CutXfemModel& model, double density, const Eigen::Vector3d& g,
                                    LumpingScheme scheme, const PieceRuleFunction& rule);

} // namespace kerf
