#include "kerf/fem/tet_stiffness.hpp"

#include "kerf/fem/positive_jacobian.hpp"
#include "kerf/fem/tet_quadrature.hpp"
#include "kerf/fem/tet_shape_functions.hpp"

#include <Eigen/Dense>

namespace kerf {

Eigen::Matrix<double, 12, 12> tet4_stiffness(const Eigen::Matrix<double, 4, 3>& X, const LinearMaterial& material) {
  double det_J = 0.0;
  const Eigen::Matrix<double, 4, 3> g = physical_shape_gradients<4>(X, tet4_shape_gradients(), det_J);
  require_positive_jacobian(det_J, "tet4_stiffness");
  Eigen::Matrix<double, 12, 12> K = Eigen::Matrix<double, 12, 12>::Zero();
  add_stiffness_integrand<4>(g, det_J / 6.0, material.mu(), material.lambda(), K); // weight = volume
  return K;
}

Eigen::Matrix<double, 30, 30> tet10_stiffness(const Eigen::Matrix<double, 10, 3>& X, const LinearMaterial& material) {
  static const TetQuadratureRule rule = tet_quadrature_rule(2);
  Eigen::Matrix<double, 30, 30> K = Eigen::Matrix<double, 30, 30>::Zero();
  for (std::size_t q = 0; q < rule.points.size(); ++q) {
    double det_J = 0.0;
    const Eigen::Matrix<double, 10, 3> g = physical_shape_gradients<10>(X, tet10_shape_gradients(rule.points[q]), det_J);
    require_positive_jacobian(det_J, "tet10_stiffness");
    add_stiffness_integrand<10>(g, rule.weights[q] * det_J, material.mu(), material.lambda(), K);
  }
  return K;
}

} // namespace kerf
