/// @file tet_mass.hpp
/// @brief Consistent element mass matrices of Tet4 and Tet10, eq. (26).
#pragma once

#include <Eigen/Core>

namespace kerf {

/// Scalar consistent mass m_ab = rho int N_a N_b dV (eq. 26), 4x4. The full 12x12 element mass
/// is m kron I_3: each displacement component sees the same scalar matrix. Closed form
/// rho V (1 + delta_ab) / 20. The corners must be positively oriented, det J = 6 V > 0, or
/// std::invalid_argument (see positive_jacobian.hpp).
Eigen::Matrix4d tet4_mass(const Eigen::Matrix<double, 4, 3>& X, double density);

/// Scalar consistent mass of a Tet10, 10x10, integrated with the degree-4 rule (exact for
/// straight edges: N_a N_b has degree 4). det J must be positive at every point of the rule,
/// or std::invalid_argument (see positive_jacobian.hpp).
Eigen::Matrix<double, 10, 10> tet10_mass(const Eigen::Matrix<double, 10, 3>& X, double density);

} // namespace kerf
