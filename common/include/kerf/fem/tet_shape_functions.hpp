/// @file tet_shape_functions.hpp
/// @brief Tet4 and Tet10 isoparametric shape functions and their gradients on the reference tet.
///
/// The reference tet has corners (0,0,0), (1,0,0), (0,1,0), (0,0,1). A point xi = (xi1, xi2, xi3)
/// has barycentric coordinates lambda = (1 - xi1 - xi2 - xi3, xi1, xi2, xi3); the shape
/// functions are polynomials in lambda (Schoch et al., eq. 14: partition of unity and
/// Kronecker delta property).
#pragma once

#include <Eigen/Core>

namespace kerf {

/// Tet4 shape functions N_a(xi) = lambda_a, a = 0..3.
Eigen::Matrix<double, 4, 1> tet4_shape(const Eigen::Vector3d& xi);

/// Gradients dN_a/dxi of the Tet4 shape functions, 4x3 (row a is grad N_a); constant.
Eigen::Matrix<double, 4, 3> tet4_shape_gradients();

/// Tet10 shape functions: corners N_a = lambda_a (2 lambda_a - 1), mid-edge nodes
/// N_{4+e} = 4 lambda_i lambda_j for edge e = (i, j) of tet_edge_corners.
Eigen::Matrix<double, 10, 1> tet10_shape(const Eigen::Vector3d& xi);

/// Gradients dN_a/dxi of the Tet10 shape functions at xi, 10x3 (row a is grad N_a).
Eigen::Matrix<double, 10, 3> tet10_shape_gradients(const Eigen::Vector3d& xi);

/// Physical gradients dN_a/dx = dN_a/dxi J^{-1}, n x 3, for an element with node positions
/// X (n by 3) and reference gradients dN_dxi (n x 3), where J = X^T dN_dxi = dx/dxi.
/// @param[out] det_J the Jacobian determinant (6 times the volume for a straight-edged tet)
template <int n>
Eigen::Matrix<double, n, 3> physical_shape_gradients(const Eigen::Matrix<double, n, 3>& X,
                                                     const Eigen::Matrix<double, n, 3>& dN_dxi, double& det_J) {
  const Eigen::Matrix3d J = X.transpose() * dN_dxi; // J_ij = dx_i / dxi_j
  det_J = J.determinant();
  return dN_dxi * J.inverse();
}

} // namespace kerf
