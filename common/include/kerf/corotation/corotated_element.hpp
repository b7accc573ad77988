/// @file corotated_element.hpp
/// @brief Corotated element force f = R K (R^T x - X) and its tangent (Schoch et al., eqs. 36-40).
#pragma once

#include "kerf/corotation/corotation_statistics.hpp"
#include "kerf/corotation/polar_decomposition.hpp"

#include <Eigen/Core>
#include <Eigen/LU>
#include <cmath>

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

/// d = R^T (x_a - x_0) - (X_a - X_0) for every node a: the displacement in the element's
/// unrotated frame, measured from node 0. K annihilates translations, so this gives the same
/// K d as R^T x - X does, but without the round-off of absolute coordinates: a mesh 1000 m from
/// the origin loses eps |X| = 2e-13 m in R^T x - X, more than the displacements of a stiff body
/// under a small load, and Newton's residual would stall there. Here only eps times the element
/// size is lost, which is what the round-off floor of the quasi-static solver assumes.
template <int n>
Eigen::Matrix<double, 3 * n, 1> corotated_displacement(const Eigen::Matrix3d& R, const Eigen::Matrix<double, n, 3>& X,
                                                       const Eigen::Matrix<double, n, 3>& u) {
  Eigen::Matrix<double, 3 * n, 1> d;
  for (int a = 0; a < n; ++a) {
    const Eigen::Vector3d X_a0 = (X.row(a) - X.row(0)).transpose();
    const Eigen::Vector3d x_a0 = X_a0 + (u.row(a) - u.row(0)).transpose();
    d.template segment<3>(3 * a) = R.transpose() * x_a0 - X_a0;
  }
  return d;
}

/// Adds one rotation point's corotated force and tangent to f and Kt (n nodes, 3n DOFs).
///
/// K is the linear stiffness that belongs to this point (for a Tet4 the whole element
/// stiffness of chapter 1; for a Tet10 one quadrature point's share of it), symmetric (only
/// its blocks on and above the diagonal are read: R K R^T is symmetric too), G its n x 3
/// physical shape gradients there, X the n x 3 reference positions, u the nodes' n x 3
/// displacements, and `weight` the volume the point stands for (V for a Tet4, w_q |det J| for
/// a Tet10). With F = I + u^T G = R S (exactly x^T G, since the rows of G sum to zero):
///   f  += R K d,  d = R^T x - X                  (eq. 40, node-block-wise rotation)
///   Kt += R K R^T                                (eq. 38, the warped stiffness)
///   Kt += the terms from dR/dx                   (consistent tangent only)
/// d is formed relative to node 0 (corotated_displacement), so that the answer does not depend
/// on where the mesh sits.
/// For the polar rotation, R K d is the gradient of the corotated energy 1/2 d^T K d; on node a
/// it equals weight P g_a with the stress P = R sigma(S - I), sigma(e) = 2 mu e + lambda tr(e) I.
/// Differentiating P with R moving, dR = R W, W = [w]_x, gives the extra terms
///   dP = R (W sigma + mu (S W - W S)),   (tr(S) I - S) w = g_b x r_q
/// for a move of node b along e_q (r_q is row q of R). This costs a few 3x3 products per
/// column instead of a 3n x 3n product, and it is exactly the derivative of f.
///
/// tr(S) I - S has the eigenvalues s_i + s_j of pairs of signed singular values, so it is
/// singular where two of them cancel: only past inversion (the SVD rotation gives one negative
/// stretch), for example on an element's way back from inversion. There dR/dx is unbounded and
/// the terms would be inf or NaN, so we leave them out for that point (its block stays the
/// warped one, eq. 38) and count it in `statistics` (dropped_rotation_terms). "Singular" means
/// |det| <= 1e-6 |tr(S) I - S|_F^3, i.e. the smallest eigenvalue is below about 1e-6 of the
/// largest, where the terms are a million times their usual size and no longer a useful tangent.
/// Defined (src/corotation/corotated_point.cpp) for n = 4, a Tet4, and n = 10, one quadrature
/// point of a Tet10: the only elements Kerf has.
/// @return the rotation used, with its Higham iteration count; `statistics`, when given,
///         records the point (inversion, Higham failure, dropped terms)
template <int n>
PolarDecomposition add_corotated_point(const Eigen::Matrix<double, 3 * n, 3 * n>& K, const Eigen::Matrix<double, n, 3>& G,
                                       const Eigen::Matrix<double, n, 3>& X, const Eigen::Matrix<double, n, 3>& u,
                                       double weight, double mu, double lambda, RotationMethod method,
                                       CorotationalTangent tangent, Eigen::Matrix<double, 3 * n, 1>& f,
                                       Eigen::Matrix<double, 3 * n, 3 * n>* Kt, CorotationStatistics* statistics = nullptr);

} // namespace kerf
