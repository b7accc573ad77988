// The gradients of the Tet4 and Tet10 shape functions on the reference tet, apart from the
// functions themselves (tet_shape_functions.cpp): assignment 01 replaces this file.
#include "kerf/fem/tet_shape_functions.hpp"

#include "fem/barycentric_coordinates.hpp"
#include "kerf/mesh/tet_mesh.hpp"

namespace kerf {

Eigen::Matrix<double, 4, 3> tet4_shape_gradients() { return barycentric_gradients(); }

Eigen::Matrix<double, 10, 3> tet10_shape_gradients(const Eigen::Vector3d& xi) {
  const Eigen::Vector4d L = barycentric_coordinates(xi);
  const Eigen::Matrix<double, 4, 3> dL = barycentric_gradients();
  Eigen::Matrix<double, 10, 3> dN;
  for (int a = 0; a < 4; ++a) dN.row(a) = (4.0 * L[a] - 1.0) * dL.row(a);
  for (int e = 0; e < 6; ++e) {
    const int i = tet_edge_corners[e][0], j = tet_edge_corners[e][1];
    dN.row(4 + e) = 4.0 * (L[i] * dL.row(j) + L[j] * dL.row(i));
  }
  return dN;
}

} // namespace kerf
