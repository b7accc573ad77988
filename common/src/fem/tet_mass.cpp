#include "kerf/fem/tet_mass.hpp"

#include "kerf/fem/positive_jacobian.hpp"
#include "kerf/fem/tet_quadrature.hpp"
#include "kerf/fem/tet_shape_functions.hpp"

#include <Eigen/Dense>

namespace kerf {

Eigen::Matrix4d tet4_mass(const Eigen::Matrix<double, 4, 3>& X, double density) {
  double det_J = 0.0;
  physical_shape_gradients<4>(X, tet4_shape_gradients(), det_J);
  require_positive_jacobian(det_J, "tet4_mass");
  const double volume = det_J / 6.0;
  return density * volume / 20.0 * (Eigen::Matrix4d::Ones() + Eigen::Matrix4d::Identity());
}

Eigen::Matrix<double, 10, 10> tet10_mass(const Eigen::Matrix<double, 10, 3>& X, double density) {
  static const TetQuadratureRule rule = tet_quadrature_rule(4);
  Eigen::Matrix<double, 10, 10> m = Eigen::Matrix<double, 10, 10>::Zero();
  for (std::size_t q = 0; q < rule.points.size(); ++q) {
    double det_J = 0.0;
    physical_shape_gradients<10>(X, tet10_shape_gradients(rule.points[q]), det_J);
    require_positive_jacobian(det_J, "tet10_mass");
    const Eigen::Matrix<double, 10, 1> N = tet10_shape(rule.points[q]);
    m += (density * rule.weights[q] * det_J) * N * N.transpose();
  }
  return m;
}

} // namespace kerf
