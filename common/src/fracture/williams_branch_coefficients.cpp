#include "kerf/fracture/williams_branch_coefficients.hpp"

#include <cmath>
#include <numbers>

namespace kerf {

std::array<Eigen::Vector3d, 4> williams_branch_coefficients(const StraightFrontFrame& front,
                                                            const StressIntensityFactors& K,
                                                            const LinearMaterial& material) {
  const double kappa = 3.0 - 4.0 * material.poisson;
  const double unit = 1.0 / (2.0 * material.mu() * std::sqrt(2.0 * std::numbers::pi));
  const double A_I = unit * K.K_I, A_II = unit * K.K_II, A_III = unit * K.K_III;
  const Eigen::Vector3d a = front.R.col(0), b = front.R.col(1), c = front.R.col(2);
  return {A_I * (kappa + 1.0) * b + A_II * (kappa + 1.0) * a + 4.0 * A_III * c,
          A_I * (kappa - 1.0) * a - A_II * (kappa - 1.0) * b, A_I * a + A_II * b, -A_I * b + A_II * a};
}

} // namespace kerf
