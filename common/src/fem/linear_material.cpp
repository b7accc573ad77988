#include "kerf/fem/linear_material.hpp"

#include <cmath>
#include <stdexcept>

namespace kerf {

void LinearMaterial::check() const {
  if (!(std::isfinite(young) && young > 0.0)) throw std::invalid_argument("LinearMaterial: young must be a positive finite number (Pa)");
  if (!(poisson > -1.0 && poisson <= max_poisson))
    throw std::invalid_argument("LinearMaterial: poisson must lie in (-1, 0.5 - 1e-6]: at 0.5 lambda is infinite");
  if (!(std::isfinite(density) && density >= 0.0))
    throw std::invalid_argument("LinearMaterial: density must be a non-negative finite number (kg/m^3)");
}

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
