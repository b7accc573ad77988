/// @file xfem_mass.hpp
/// @brief The XFEM mass: consistent (Schoch et al. eqs. 76-80), integrated piece by piece, and lumped (eqs. 81-82).
#pragma once

#include "kerf/xfem/xfem_model.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace kerf {

/// The consistent mass matrix on all 3 (N + N_enr) DOFs, no Dirichlet elimination.
///
/// Eqs. 77-80 are rho int Phi_i Phi_j times 1, Psi_j, Psi_i, Psi_i Psi_j. On each side Psi is
/// constant, so an element's mass is sum_side T_side^T (M_side kron I_3) T_side with
/// M_side = rho int_piece Phi_i Phi_j dV: unlike the stiffness, the integrand is not constant,
/// so a volume ratio is not enough; we integrate over the piece's sub-tets with the degree-2
/// rule, which is exact for the quadratic Phi_i Phi_j.
Eigen::SparseMatrix<double> assemble_xfem_mass(const XfemModel& model, double density);

/// The lumped mass (eqs. 81-82), a diagonal on all 3 (N + N_enr) DOFs: each corner of a tet of
/// mass m gets m / 4 on its u DOFs and (V_a / V Psi_a,i^2 + V_b / V Psi_b,i^2) m / 4 on its a
/// DOFs. The u part sums to rho V whatever the cut: cutting adds no mass.
Eigen::VectorXd xfem_lumped_mass(const XfemModel& model, double density);

} // namespace kerf
