// The corotated force and tangent of one rotation point (Schoch et al., eqs. 36-40), out of the
// header so that it is one file of its own: chapter 2's assignment replaces this file
// (assignments/02_corotation/). Its two instantiations are the only element types Kerf has.
#include "kerf/corotation/corotated_element.hpp"

#include <Eigen/Dense>
#include <cmath>

namespace kerf {

template <int n>
PolarDecomposition add_corotated_point(const Eigen::Matrix<double, 3 * n, 3 * n>& K, const Eigen::Matrix<double, n, 3>& G,
                                       const Eigen::Matrix<double, n, 3>& X, const Eigen::Matrix<double, n, 3>& u,
                                       double weight, double mu, double lambda, RotationMethod method,
                                       CorotationalTangent tangent, Eigen::Matrix<double, 3 * n, 1>& f,
                                       Eigen::Matrix<double, 3 * n, 3 * n>* Kt, CorotationStatistics* statistics) {
  constexpr int m = 3 * n;
  const Eigen::Matrix3d F = Eigen::Matrix3d::Identity() + u.transpose() * G;
  const PolarDecomposition polar = element_rotation(F, method);
  if (statistics) statistics->record(polar, F, weight);
  const Eigen::Matrix3d& R = polar.R;

  const Eigen::Matrix<double, m, 1> Kd = K * corotated_displacement<n>(R, X, u);
  for (int a = 0; a < n; ++a) f.template segment<3>(3 * a) += R * Kd.template segment<3>(3 * a);
  if (!Kt) return polar;

  // K is symmetric, and so is R K R^T: each block above the diagonal is turned once and its
  // transpose is the block below (10 of a Tet4's 16 blocks turned, 55 of a Tet10 point's 100).
  for (int b = 0; b < n; ++b)
    for (int a = 0; a <= b; ++a) {
      const Eigen::Matrix3d block = R * K.template block<3, 3>(3 * a, 3 * b) * R.transpose();
      Kt->template block<3, 3>(3 * a, 3 * b) += block;
      if (a != b) Kt->template block<3, 3>(3 * b, 3 * a) += block.transpose();
    }
  if (tangent == CorotationalTangent::warped) return polar;

  const Eigen::Matrix3d& S = polar.S;
  const Eigen::Matrix3d M = S.trace() * Eigen::Matrix3d::Identity() - S;
  const double size = M.norm();
  if (!(std::abs(M.determinant()) > 1e-6 * size * size * size)) {
    if (statistics) ++statistics->dropped_rotation_terms;
    return polar;
  }
  const Eigen::Matrix3d strain = 0.5 * (S + S.transpose()) - Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d sigma = 2.0 * mu * strain + lambda * strain.trace() * Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d M_inverse = M.inverse();
  for (int b = 0; b < n; ++b)
    for (int q = 0; q < 3; ++q) {
      const Eigen::Vector3d w = M_inverse * G.row(b).transpose().cross(R.row(q).transpose());
      Eigen::Matrix3d W;
      W << 0, -w[2], w[1], w[2], 0, -w[0], -w[1], w[0], 0;
      const Eigen::Matrix3d dP = weight * R * (W * sigma + mu * (S * W - W * S));
      for (int a = 0; a < n; ++a) Kt->col(3 * b + q).template segment<3>(3 * a) += dP * G.row(a).transpose();
    }
  return polar;
}

template PolarDecomposition add_corotated_point<4>(const Eigen::Matrix<double, 12, 12>&, const Eigen::Matrix<double, 4, 3>&,
                                                   const Eigen::Matrix<double, 4, 3>&, const Eigen::Matrix<double, 4, 3>&, double,
                                                   double, double, RotationMethod, CorotationalTangent,
                                                   Eigen::Matrix<double, 12, 1>&, Eigen::Matrix<double, 12, 12>*,
                                                   CorotationStatistics*);
template PolarDecomposition add_corotated_point<10>(const Eigen::Matrix<double, 30, 30>&, const Eigen::Matrix<double, 10, 3>&,
                                                    const Eigen::Matrix<double, 10, 3>&, const Eigen::Matrix<double, 10, 3>&, double,
                                                    double, double, RotationMethod, CorotationalTangent,
                                                    Eigen::Matrix<double, 30, 1>&, Eigen::Matrix<double, 30, 30>*,
                                                    CorotationStatistics*);

} // namespace kerf
