/// @file xfem_element.hpp
/// @brief One enriched Tet4: the shifted enrichment values Psi (eqs. 44, 58, 59), the side operators, and the
///        element stiffness by volume ratios (eqs. 54-57, which the shifted enrichment turns into eqs. 60-63).
#pragma once

#include <Eigen/Core>

namespace kerf {

/// Psi_i on one side of the cut, (H_side - H_i) / 2 (eq. 44): 0 on the node's own side, and
/// +1 above (eq. 58) or -1 below (eq. 59) for a node on the other side.
/// @param side_sign +1 above the cut, -1 below
/// @param node_sign H_i, +1 or -1
inline double shifted_enrichment(int side_sign, int node_sign) { return 0.5 * (side_sign - node_sign); }

/// The side operator T (12 x 24) of one side of a cut Tet4: the displacements of the four
/// corners as that side sees them, from the element's [u_1..u_4, a_1..a_4] (eq. 45):
/// u_side,i = u_i + Psi_side,i a_i (eq. 66; eqs. 69-70 with the shifted values).
///
/// This is the whole trick of the shifted Heaviside enrichment for a Tet4: inside the piece on
/// one side Psi is constant, so the enriched field there is an ordinary linear field with
/// corner values u_side (a "phantom" element that the side alone would deform). Everything on
/// that side, strain, stress, rotation, is the ordinary Tet4's of u_side.
/// @param psi Psi_side,i of the four corners; 0 for a corner without enriched DOFs
Eigen::Matrix<double, 12, 24> side_operator(const Eigen::Vector4d& psi);

/// The enriched element stiffness K^X (24 x 24, eq. 53) of a Tet4 cut into V_a above and V_b
/// below, by volume ratios.
///
/// Eq. 52 splits the integral of B^X^T C B^X (eq. 51) over the two pieces. On a piece B^X is
/// the constant B of the Tet4 times [I, Psi_side] (eq. 50), so each piece contributes
/// (V_side / V) T_side^T K T_side, with K the uncut element stiffness (eq. 47):
///
///   K^X = (V_a / V) T_a^T K T_a + (V_b / V) T_b^T K T_b.
///
/// Written out block by block this is eqs. 54-57; with the shifted values of Psi it is eqs.
/// 60-63. No new quadrature point is needed, only the two volumes: Schoch et al.'s "very special
/// feature".
///
/// Where the code departs from Schoch et al.'s printed text (a student reading along should know):
/// - eq. 61: its second case reads "if H_j = -1" where H_i = -1 is meant;
/// - eq. 71 (the corotated a-rows): its case labels are swapped relative to eqs. 58-59. It reads
///   "if H_i = -1, i.e. if Psi_ai = 0 and Psi_bi = -1", but Psi_ai = 0, Psi_bi = -1 belong to
///   H_i = +1; and its second line ends in x_{a_j} where x_{0_j}, the reference position, is
///   meant. We never type eq. 71 in: the a-rows are T^T times the side's corotated force,
///   which is eq. 71 with both corrections (XfemModel::assemble);
/// - after eq. 63 the paper says these results "hold for quadratical elements, too". They do not
///   for the stiffness: B is constant on a Tet4, so a piece's integral is a volume ratio, but it
///   is linear on a Tet10, and the pieces need a real quadrature. Chapter 3 refuses Tet10
///   meshes for that reason; chapter 4 integrates over the pieces.
/// The test suite checks this form against eqs. 60-63 typed in entry by entry.
/// @param K              the uncut 12 x 12 element stiffness
/// @param fraction_above V_a / V; V_b / V = 1 - V_a / V
/// @param psi_above      Psi_a,i of the four corners (0 where a corner has no enriched DOFs)
/// @param psi_below      Psi_b,i
Eigen::Matrix<double, 24, 24> xfem_tet4_stiffness(const Eigen::Matrix<double, 12, 12>& K, double fraction_above,
                                                 const Eigen::Vector4d& psi_above, const Eigen::Vector4d& psi_below);

} // namespace kerf
