/// @file tet_mass.hpp
/// @brief Consistent element mass matrices of Tet4 and Tet10, eq. (26).
#pragma once

#include <Eigen/Core>

namespace kerf {

/// Scalar consistent mass m_ab = rho int N_a N_b dV (eq. 26), 4x4. The full 12x12 element mass
/// is m kron I_3: each displacement component sees the same scalar matrix. Closed form
/// rho V (1 + delta_ab) / 20.
Eigen::Matrix4d tet4_mass(const Eigen::Matrix<double, 4, 3>& X, double density);

/// Scalar consistent mass of a Tet10, 10x10, integrated with the degree-4 rule (exact for
/// straight edges: N_a N_b has degree 4).
Eigen::Matrix<double, 10, 10> tet10_mass(const Eigen::Matrix<double, 10, 3>& X, double density);

} // namespace kerf
