#include "kerf/fem/tet_shape_functions.hpp"

#include "kerf/mesh/tet_mesh.hpp"

namespace kerf {

namespace {

Eigen::Vector4d barycentric(const Eigen::Vector3d& xi) { return {1.0 - xi.sum(), xi[0], xi[1], xi[2]}; }

// d lambda_a / d xi, 4x3: lambda_0 = 1 - xi1 - xi2 - xi3, lambda_k = xi_k.
Eigen::Matrix<double, 4, 3> barycentric_gradients() {
  Eigen::Matrix<double, 4, 3> d;
  d << -1, -1, -1,
        1,  0,  0,
        0,  1,  0,
        0,  0,  1;
  return d;
}

} // namespace

Eigen::Matrix<double, 4, 1> tet4_shape(const Eigen::Vector3d& xi) { return barycentric(xi); }

Eigen::Matrix<double, 4, 3> tet4_shape_gradients() { return barycentric_gradients(); }

Eigen::Matrix<double, 10, 1> tet10_shape(const Eigen::Vector3d& xi) {
  const Eigen::Vector4d L = barycentric(xi);
  Eigen::Matrix<double, 10, 1> N;
  for (int a = 0; a < 4; ++a) N[a] = L[a] * (2.0 * L[a] - 1.0);
  for (int e = 0; e < 6; ++e) N[4 + e] = 4.0 * L[tet_edge_corners[e][0]] * L[tet_edge_corners[e][1]];
  return N;
}

Eigen::Matrix<double, 10, 3> tet10_shape_gradients(const Eigen::Vector3d& xi) {
  const Eigen::Vector4d L = barycentric(xi);
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
