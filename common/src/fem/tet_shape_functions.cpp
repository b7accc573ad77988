#include "kerf/fem/tet_shape_functions.hpp"

#include "fem/barycentric_coordinates.hpp"
#include "kerf/mesh/tet_mesh.hpp"

namespace kerf {

Eigen::Matrix<double, 4, 1> tet4_shape(const Eigen::Vector3d& xi) { return barycentric_coordinates(xi); }

Eigen::Matrix<double, 10, 1> tet10_shape(const Eigen::Vector3d& xi) {
  const Eigen::Vector4d L = barycentric_coordinates(xi);
  Eigen::Matrix<double, 10, 1> N;
  for (int a = 0; a < 4; ++a) N[a] = L[a] * (2.0 * L[a] - 1.0);
  for (int e = 0; e < 6; ++e) N[4 + e] = 4.0 * L[tet_edge_corners[e][0]] * L[tet_edge_corners[e][1]];
  return N;
}

} // namespace kerf
