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
/// physical shape gradients there, X the n x 3 reference positions, x the current ones.
/// With F = x^T G = R S:
///   f  += R K (R^T x - X)                                  (eq. 40, node-block-wise rotation)
///   Kt += R K R^T                                          (eq. 38, the warped stiffness)
///   Kt += dR K (R^T x - X) + R K dR^T x  per DOF direction (consistent tangent only)
/// For the polar rotation, f is the gradient of the corotated energy
/// 1/2 (R^T x - X)^T K (R^T x - X), so the consistent tangent is its (symmetric) Hessian.
/// @return the rotation used, with its Higham iteration count
template <int n>
PolarDecomposition add_corotated_point(const Eigen::Matrix<double, 3 * n, 3 * n>& K, const Eigen::Matrix<double, n, 3>& G,
                                       const Eigen::Matrix<double, n, 3>& X, const Eigen::Matrix<double, n, 3>& x,
                                       RotationMethod method, CorotationalTangent tangent,
                                       Eigen::Matrix<double, 3 * n, 1>& f, Eigen::Matrix<double, 3 * n, 3 * n>* Kt) {
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

  // Column (b, q): moving node b along e_q changes F by e_q g_b^T and R by dR.
  for (int b = 0; b < n; ++b)
    for (int q = 0; q < 3; ++q) {
      const Eigen::Matrix3d dF = Eigen::Vector3d::Unit(q) * G.row(b);
      const Eigen::Matrix3d dR = polar_rotation_derivative(polar, dF);
      Eigen::Matrix<double, m, 1> dRt_x;
      for (int a = 0; a < n; ++a) dRt_x.template segment<3>(3 * a) = dR.transpose() * x.row(a).transpose();
      const Eigen::Matrix<double, m, 1> K_dRt_x = K * dRt_x;
      for (int a = 0; a < n; ++a)
        Kt->col(3 * b + q).template segment<3>(3 * a) +=
            dR * Kd.template segment<3>(3 * a) + R * K_dRt_x.template segment<3>(3 * a);
    }
  return polar;
}

} // namespace kerf
