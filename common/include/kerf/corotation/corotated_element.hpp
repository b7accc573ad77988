/// @file corotated_element.hpp
/// @brief Corotated element force f = R K (R^T x - X) and its tangent (Schoch et al., eqs. 36-40).
#pragma once

#include "kerf/corotation/polar_decomposition.hpp"

#include <Eigen/Core>

namespace kerf {

/// How the rotation of an element (or of a quadrature point) is extracted from F.
enum class RotationMethod {
  higham, ///< Higham's iteration only (the paper's choice): fails for det F <= 0
  svd,    ///< the SVD rotation: always a rotation, also for inverted elements
  automatic ///< Higham's iteration, falling back to the SVD where it does not give a rotation
};

/// Which tangent stiffness the element returns.
enum class CorotationalTangent {
  warped,    ///< R K R^T (eq. 38): the linear stiffness turned with the element; ignores dR/dx
  consistent ///< the exact derivative of f: R K R^T plus the terms from dR/dx
};

/// The rotation of F by `method`. `inverted` is set when det F <= 0.
PolarDecomposition element_rotation(const Eigen::Matrix3d& F, RotationMethod method);

/// Adds one rotation point's corotated force and tangent to f and Kt (n nodes, 3n DOFs).
///
/// K is the linear stiffness that belongs to this point (for a Tet4 the whole element
/// stiffness of chapter 1; for a Tet10 one quadrature point's share of it), G its n x 3
/// physical shape gradients there, X the n x 3 reference positions, x the current ones, and
/// `weight` the volume the point stands for (V for a Tet4, w_q |det J| for a Tet10).
/// With F = x^T G = R S:
///   f  += R K (R^T x - X)                        (eq. 40, node-block-wise rotation)
///   Kt += R K R^T                                (eq. 38, the warped stiffness)
///   Kt += the terms from dR/dx                   (consistent tangent only)
/// For the polar rotation, R K (R^T x - X) is the gradient of the corotated energy
/// 1/2 (R^T x - X)^T K (R^T x - X); on node a it equals weight P g_a with the stress
/// P = R sigma(S - I), sigma(e) = 2 mu e + lambda tr(e) I. Differentiating P with R moving,
/// dR = R W, W = [w]_x, gives the extra terms
///   dP = R (W sigma + mu (S W - W S)),   (tr(S) I - S) w = g_b x r_q
/// for a move of node b along e_q (r_q is row q of R). This costs a few 3x3 products per
/// column instead of a 3n x 3n product, and it is exactly the derivative of f.
/// @return the rotation used, with its Higham iteration count
template <int n>
PolarDecomposition add_corotated_point(const Eigen::Matrix<double, 3 * n, 3 * n>& K, const Eigen::Matrix<double, n, 3>& G,
                                       const Eigen::Matrix<double, n, 3>& X, const Eigen::Matrix<double, n, 3>& x,
                                       double weight, double mu, double lambda, RotationMethod method,
                                       CorotationalTangent tangent, Eigen::Matrix<double, 3 * n, 1>& f,
                                       Eigen::Matrix<double, 3 * n, 3 * n>* Kt) {
  constexpr int m = 3 * n;
  const Eigen::Matrix3d F = x.transpose() * G;
  const PolarDecomposition polar = element_rotation(F, method);
  const Eigen::Matrix3d& R = polar.R;

  // d = R^T x - X, the displacement in the element's unrotated frame.
  Eigen::Matrix<double, m, 1> d;
  for (int a = 0; a < n; ++a) d.template segment<3>(3 * a) = R.transpose() * x.row(a).transpose() - X.row(a).transpose();
  const Eigen::Matrix<double, m, 1> Kd = K * d;
  for (int a = 0; a < n; ++a) f.template segment<3>(3 * a) += R * Kd.template segment<3>(3 * a);
  if (!Kt) return polar;

  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      Kt->template block<3, 3>(3 * a, 3 * b) += R * K.template block<3, 3>(3 * a, 3 * b) * R.transpose();
  if (tangent == CorotationalTangent::warped) return polar;

  const Eigen::Matrix3d& S = polar.S;
  const Eigen::Matrix3d strain = 0.5 * (S + S.transpose()) - Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d sigma = 2.0 * mu * strain + lambda * strain.trace() * Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d M_inverse = (S.trace() * Eigen::Matrix3d::Identity() - S).inverse();
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

} // namespace kerf
