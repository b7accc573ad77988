#include "kerf/xfem/branch_functions.hpp"

#include <cmath>

namespace kerf {

Eigen::Vector4d branch_function_values(double r, double theta) {
  const double s = std::sqrt(r), sh = std::sin(0.5 * theta), ch = std::cos(0.5 * theta), st = std::sin(theta);
  return {s * sh, s * ch, s * sh * st, s * ch * st};
}

Eigen::Matrix<double, 4, 2> branch_function_frame_derivatives(double r, double theta) {
  // With x_a = r cos(theta), x_b = r sin(theta), d/dx_a = cos(theta) d/dr -
  // sin(theta)/r d/dtheta and d/dx_b = sin(theta) d/dr + cos(theta)/r d/dtheta, applied to
  // sqrt(r) g(theta), and simplified with the half-angle identities.
  const double k = 0.5 / std::sqrt(r);
  const double sh = std::sin(0.5 * theta), ch = std::cos(0.5 * theta);
  const double s3 = std::sin(1.5 * theta), c3 = std::cos(1.5 * theta);
  const double st = std::sin(theta), ct = std::cos(theta);
  Eigen::Matrix<double, 4, 2> d;
  d << -k * sh, k * ch,                 //
      k * ch, k * sh,                   //
      -k * s3 * st, k * (sh + s3 * ct), //
      -k * c3 * st, k * (ch + c3 * ct);
  return d;
}

BranchValues branch_functions(const FrontPolar& polar) {
  BranchValues v;
  if (!(polar.r > 0.0)) return v; // on the front: F = 0, gradient unbounded, returned as 0
  v.F = branch_function_values(polar.r, polar.theta);
  const Eigen::Matrix<double, 4, 2> d = branch_function_frame_derivatives(polar.r, polar.theta);
  v.dF_dx = d.col(0) * polar.grad_x_a.transpose() + d.col(1) * polar.grad_x_b.transpose();
  return v;
}

BranchValues shifted_branch_functions(double N_i, const Eigen::Vector3d& grad_N_i, const BranchValues& at_x,
                                      const Eigen::Vector4d& at_node) {
  BranchValues v;
  const Eigen::Vector4d difference = at_x.F - at_node;
  v.F = N_i * difference;
  v.dF_dx = difference * grad_N_i.transpose() + N_i * at_x.dF_dx;
  return v;
}

} // namespace kerf
