#include "kerf/fem/evaluate_displacement.hpp"

#include "kerf/fem/tet_shape_functions.hpp"

#include <limits>

namespace kerf {

Eigen::Vector3d evaluate_displacement(const TetMesh& mesh, const Eigen::VectorXd& u, Eigen::Index t, const Eigen::Vector3d& xi) {
  const Eigen::VectorXd N = mesh.order() == 2 ? Eigen::VectorXd(tet10_shape(xi)) : Eigen::VectorXd(tet4_shape(xi));
  Eigen::Vector3d value = Eigen::Vector3d::Zero();
  for (int a = 0; a < mesh.nodes_per_tet(); ++a) value += N[a] * u.segment<3>(3 * mesh.tets(t, a));
  return value;
}

Eigen::MatrixXd evaluate_displacement_at(const TetMesh& mesh, const Eigen::VectorXd& u, const Eigen::MatrixXd& points,
                                         Eigen::Index& num_outside) {
  const PointLocator locator(mesh);
  Eigen::MatrixXd values(points.rows(), 3);
  num_outside = 0;
  for (Eigen::Index p = 0; p < points.rows(); ++p) {
    const PointLocation where = locator.locate(points.row(p).transpose());
    if (where.tet < 0) {
      values.row(p).setConstant(std::numeric_limits<double>::quiet_NaN());
      ++num_outside;
    } else {
      values.row(p) = evaluate_displacement(mesh, u, where.tet, where.xi).transpose();
    }
  }
  return values;
}

} // namespace kerf
