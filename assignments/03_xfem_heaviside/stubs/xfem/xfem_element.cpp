// Assignment 03: the side operator of a cut Tet4 and its enriched stiffness by volume ratios.
// This file stands in for common/src/xfem/xfem_element.cpp when assignment 03 is graded
// (./kerf.sh assignment 03); what to compute is in assignments/03_xfem_heaviside/README.md.
#include "kerf/xfem/xfem_element.hpp"

#include <stdexcept>

namespace kerf {

/// The side operator T (12 x 24) of one side of a cut Tet4: the displacements of the four
/// corners as that side sees them, from the element's [u_1..u_4, a_1..a_4] (eq. 45):
/// u_side,i = u_i + Psi_side,i a_i (eq. 66; eqs. 69-70 with the shifted values).
/// Rows 3i..3i+2 are corner i's three components; columns 0..11 are u (node-major), columns
/// 12..23 are a (node-major).
/// @param psi Psi_side,i of the four corners; 0 for a corner without enriched DOFs
Eigen::Matrix<double, 12, 24> side_operator([[maybe_unused]] const Eigen::Vector4d& psi) {
  throw std::logic_error("assignment 03: implement side_operator (assignments/03_xfem_heaviside/README.md)");
}

/// The enriched element stiffness K^X (24 x 24, eq. 53) of a Tet4 cut into V_a above and V_b
/// below, by volume ratios: each piece contributes (V_side / V) T_side^T K T_side (eq. 52 with
/// the constant B of a Tet4), so that
///
///   K^X = (V_a / V) T_a^T K T_a + (V_b / V) T_b^T K T_b,
///
/// which is eqs. 54-57 block by block and, with the shifted values of Psi, eqs. 60-63.
/// @param K              the uncut 12 x 12 element stiffness
/// @param fraction_above V_a / V; V_b / V = 1 - V_a / V
/// @param psi_above      Psi_a,i of the four corners (0 where a corner has no enriched DOFs)
/// @param psi_below      Psi_b,i
Eigen::Matrix<double, 24, 24> xfem_tet4_stiffness([[maybe_unused]] const Eigen::Matrix<double, 12, 12>& K,
                                                 [[maybe_unused]] double fraction_above,
                                                 [[maybe_unused]] const Eigen::Vector4d& psi_above,
                                                 [[maybe_unused]] const Eigen::Vector4d& psi_below) {
  throw std::logic_error("assignment 03: implement xfem_tet4_stiffness (assignments/03_xfem_heaviside/README.md)");
}

} // namespace kerf
