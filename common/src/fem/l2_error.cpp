#include "kerf/fem/l2_error.hpp"

#include "kerf/fem/tet_quadrature.hpp"
#include "kerf/fem/tet_shape_functions.hpp"

#include <Eigen/Dense>
#include <cmath>

namespace kerf {

namespace {

/// Calls visit(t, x, N, weight) at every quadrature point of every tet, with weight = w |det J|.
template <class Visit>
void for_each_quadrature_point(const TetMesh& mesh, int degree, Visit&& visit) {
  const TetQuadratureRule rule = tet_quadrature_rule(degree);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const Eigen::Vector3d x0 = mesh.nodes.row(mesh.tets(t, 0)).transpose();
    Eigen::Matrix3d J;
    for (int c = 0; c < 3; ++c) J.col(c) = mesh.nodes.row(mesh.tets(t, c + 1)).transpose() - x0;
    const double det_J = std::abs(J.determinant());
    for (std::size_t q = 0; q < rule.points.size(); ++q) {
      const Eigen::Vector3d& xi = rule.points[q];
      const Eigen::VectorXd N = mesh.order() == 2 ? Eigen::VectorXd(tet10_shape(xi)) : Eigen::VectorXd(tet4_shape(xi));
      visit(t, Eigen::Vector3d(x0 + J * xi), N, rule.weights[q] * det_J);
    }
  }
}

} // namespace

double l2_error(const TetMesh& mesh, const Eigen::VectorXd& u_h, const VectorField& exact, int degree) {
  double sum = 0.0;
  for_each_quadrature_point(mesh, degree, [&](Eigen::Index t, const Eigen::Vector3d& x, const Eigen::VectorXd& N, double w) {
    Eigen::Vector3d value = Eigen::Vector3d::Zero();
    for (int a = 0; a < mesh.nodes_per_tet(); ++a) value += N[a] * u_h.segment<3>(3 * mesh.tets(t, a));
    sum += w * (value - exact(x)).squaredNorm();
  });
  return std::sqrt(sum);
}

double l2_norm(const TetMesh& mesh, const VectorField& field, int degree) {
  double sum = 0.0;
  for_each_quadrature_point(mesh, degree, [&](Eigen::Index, const Eigen::Vector3d& x, const Eigen::VectorXd&, double w) {
    sum += w * field(x).squaredNorm();
  });
  return std::sqrt(sum);
}

Eigen::VectorXd assemble_body_force(const TetMesh& mesh, const VectorField& body_force, int degree) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * mesh.num_nodes());
  for_each_quadrature_point(mesh, degree, [&](Eigen::Index t, const Eigen::Vector3d& x, const Eigen::VectorXd& N, double w) {
    const Eigen::Vector3d b = body_force(x);
    for (int a = 0; a < mesh.nodes_per_tet(); ++a) f.segment<3>(3 * mesh.tets(t, a)) += (w * N[a]) * b;
  });
  return f;
}

} // namespace kerf
