#include "kerf/fem/linear_material.hpp"

namespace kerf {

Eigen::Matrix<double, 6, 6> voigt_elasticity_matrix(const LinearMaterial& material) {
  const double lambda = material.lambda();
  const double mu = material.mu();
  Eigen::Matrix<double, 6, 6> C = Eigen::Matrix<double, 6, 6>::Zero();
  C.topLeftCorner<3, 3>().setConstant(lambda); // eq. (6): lambda couples every normal pair
  C.topLeftCorner<3, 3>().diagonal().array() += 2.0 * mu;
  C.bottomRightCorner<3, 3>().diagonal().setConstant(mu);
  return C;
}

} // namespace kerf
