#include "kerf/corotation/corotated_element.hpp"

#include <Eigen/Dense>

namespace kerf {

PolarDecomposition element_rotation(const Eigen::Matrix3d& F, RotationMethod method) {
  if (method == RotationMethod::svd) return polar_svd(F);
  PolarDecomposition polar = polar_higham(F);
  if (method == RotationMethod::automatic && !polar.converged) {
    const int iterations = polar.iterations;
    polar = polar_svd(F);
    polar.iterations = iterations;
    polar.higham_failed = true; // counted as a failure of Higham's iteration, though the SVD rescued the point
  }
  return polar;
}

} // namespace kerf
