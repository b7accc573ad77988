// Private to the kerf library (not under include/): the barycentric coordinates of a point of
// the reference tet and their gradients, from which the Tet4 and Tet10 shape functions
// (tet_shape_functions.cpp) and their gradients (tet_shape_gradients.cpp) are written. The two
// are separate files so that assignment 01 can hand out the gradients alone.
#pragma once

#include <Eigen/Core>

namespace kerf {

/// lambda = (1 - xi1 - xi2 - xi3, xi1, xi2, xi3) of a point xi of the reference tet.
inline Eigen::Vector4d barycentric_coordinates(const Eigen::Vector3d& xi) { return {1.0 - xi.sum(), xi[0], xi[1], xi[2]}; }

/// d lambda_a / d xi, 4x3: lambda_0 = 1 - xi1 - xi2 - xi3, lambda_k = xi_k.
inline Eigen::Matrix<double, 4, 3> barycentric_gradients() {
  Eigen::Matrix<double, 4, 3> d;
  d << -1, -1, -1,
        1,  0,  0,
        0,  1,  0,
        0,  0,  1;
  return d;
}

} // namespace kerf
