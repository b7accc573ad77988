#include "kerf/fem/displacement_gradient.hpp"

#include "kerf/fem/tet_shape_functions.hpp"

#include <Eigen/LU>

namespace kerf {

namespace {

template <int n>
Eigen::Matrix3d gradient_of(const TetMesh& mesh, const Eigen::VectorXd& u, Eigen::Index t, const Eigen::Matrix<double, n, 3>& dN_dxi) {
  Eigen::Matrix<double, n, 3> X;
  for (int a = 0; a < n; ++a) X.row(a) = mesh.nodes.row(mesh.tets(t, a));
  double det_J = 0.0;
  const Eigen::Matrix<double, n, 3> dN_dx = physical_shape_gradients<n>(X, dN_dxi, det_J);
  const Eigen::Matrix<double, n, 3> u_e = tet_node_displacements<n>(mesh, u, t);
  return u_e.transpose() * dN_dx;
}

} // namespace

Eigen::Matrix3d displacement_gradient_at(const TetMesh& mesh, const Eigen::VectorXd& u, Eigen::Index t, const Eigen::Vector3d& x) {
  const Eigen::Matrix<double, 4, 3> X = tet_corners(mesh, t);
  Eigen::Matrix3d J;
  for (int i = 0; i < 3; ++i) J.col(i) = (X.row(i + 1) - X.row(0)).transpose();
  const Eigen::Vector3d xi = J.inverse() * (x - X.row(0).transpose());
  if (mesh.order() == 2) return gradient_of<10>(mesh, u, t, tet10_shape_gradients(xi));
  return gradient_of<4>(mesh, u, t, tet4_shape_gradients());
}

} // namespace kerf
