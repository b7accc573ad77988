#include "kerf/corotation/polar_decomposition.hpp"

#include <Eigen/Dense>
#include <Eigen/SVD>
#include <cmath>

namespace kerf {

PolarDecomposition polar_higham(const Eigen::Matrix3d& F, double tolerance, int max_iterations) {
  PolarDecomposition result;
  Eigen::Matrix3d X = F;
  result.converged = false;
  for (int k = 0; k < max_iterations; ++k) {
    const double det = X.determinant();
    if (!(std::abs(det) > 1e-300) || !std::isfinite(det)) break; // singular: the iteration is undefined
    const Eigen::Matrix3d X_inverse_T = X.inverse().transpose();
    const double g = std::sqrt(X_inverse_T.norm() / X.norm());
    const Eigen::Matrix3d next = 0.5 * (g * X + X_inverse_T / g);
    result.iterations = k + 1;
    const double change = (next - X).norm();
    X = next;
    // Newton's step squares the error: each singular value s of X_k goes to (g s + 1 / (g s)) / 2,
    // so |s - 1| becomes about |s - 1|^2 / 2, and |X_{k+1} - X_k| is about the error of X_k. Once
    // change^2 is below tolerance / 100, X_{k+1} is within tolerance / 200 of the polar factor: the
    // step that would only confirm it is skipped (one of the usual five or six).
    if (change <= tolerance || change * change <= 0.01 * tolerance) {
      result.converged = true;
      break;
    }
  }
  result.R = X;
  result.S = X.transpose() * F;
  // An inverted F converges to a reflection: report it as not converged to a rotation.
  if (result.converged && X.determinant() < 0.0) result.converged = false;
  result.higham_failed = !result.converged;
  return result;
}

PolarDecomposition polar_svd(const Eigen::Matrix3d& F) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(F, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d U = svd.matrixU();
  const Eigen::Matrix3d V = svd.matrixV();
  Eigen::Vector3d sigma = svd.singularValues(); // sorted, largest first
  if ((U * V.transpose()).determinant() < 0.0) {
    U.col(2) *= -1.0;
    sigma[2] *= -1.0;
  }
  PolarDecomposition result;
  result.R = U * V.transpose();
  result.S = V * sigma.asDiagonal() * V.transpose();
  return result;
}

Eigen::Matrix3d polar_rotation_derivative(const PolarDecomposition& polar, const Eigen::Matrix3d& dF) {
  const Eigen::Matrix3d A = polar.R.transpose() * dF - dF.transpose() * polar.R; // = [w]_x S + S [w]_x, doubled skew part
  const Eigen::Vector3d axial(A(2, 1), A(0, 2), A(1, 0));
  const Eigen::Matrix3d M = polar.S.trace() * Eigen::Matrix3d::Identity() - polar.S;
  const Eigen::Vector3d w = M.partialPivLu().solve(axial);
  Eigen::Matrix3d W;
  W << 0, -w[2], w[1], w[2], 0, -w[0], -w[1], w[0], 0;
  return polar.R * W;
}

} // namespace kerf
