/// @file polar_decomposition.hpp
/// @brief The rotation of a deformation gradient, F = R S: Higham's iteration and an SVD that survives inversion.
#pragma once

#include <Eigen/Core>

namespace kerf {

/// F = R S with R a rotation (R^T R = I, det R = +1) and S symmetric.
struct PolarDecomposition {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity(); ///< the rotation
  Eigen::Matrix3d S = Eigen::Matrix3d::Identity(); ///< the stretch, R^T F
  int iterations = 0;                               ///< Higham: Newton steps taken; SVD: 0
  bool converged = true;                            ///< Higham: false if det F <= 0 or no convergence
  bool higham_failed = false;                       ///< Higham's iteration was tried and gave no rotation; stays set
                                                    ///< when the SVD's rotation stands in for it (RotationMethod::automatic)
};

/// Higham's scaled Newton iteration for the orthogonal polar factor (Higham 1986, the method
/// Schoch et al. cite for eq. 31): X_{k+1} = (g X_k + X_k^{-T} / g) / 2 with the Frobenius
/// scaling g = sqrt(|X_k^{-1}|_F / |X_k|_F), from X_0 = F, until |X_{k+1} - X_k|_F <= tolerance,
/// or until the quadratic convergence guarantees X_{k+1} is that close: |X_{k+1} - X_k|_F^2 <=
/// tolerance / 100 (the step after it would change X by less than tolerance / 200).
///
/// It converges quadratically to the orthogonal factor of F whenever F is invertible; but that
/// factor has det = sign(det F): for an inverted element (det F < 0) it is a reflection, not a
/// rotation, and for det F = 0 the iteration is undefined. Then `converged` is false and R is
/// whatever the iteration reached (its det may be -1). The SVD variant below is the fix.
PolarDecomposition polar_higham(const Eigen::Matrix3d& F, double tolerance = 1e-12, int max_iterations = 30);

/// The rotation from the singular value decomposition F = U Sigma V^T: R = U V^T, and if
/// det(U V^T) < 0, the column of U that belongs to the smallest singular value changes sign
/// (so does that singular value), which makes R a rotation (det R = +1) and leaves S = V Sigma V^T
/// with one negative eigenvalue: the element is reported inverted, not reflected
/// (Irving, Teran and Fedkiw 2004). Valid for every F, including det F <= 0.
PolarDecomposition polar_svd(const Eigen::Matrix3d& F);

/// The derivative of the polar rotation: for F = R S and a change dF, dR = R [w]_x with
///   (tr(S) I - S) w = axial(R^T dF - dF^T R),
/// where [w]_x is the cross-product matrix and axial its inverse. Needs tr(S) I - S invertible,
/// i.e. no two singular values summing to zero (false only at or past inversion).
Eigen::Matrix3d polar_rotation_derivative(const PolarDecomposition& polar, const Eigen::Matrix3d& dF);

} // namespace kerf
