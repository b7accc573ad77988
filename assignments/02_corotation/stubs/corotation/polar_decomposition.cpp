// Assignment 02: the polar decomposition F = R S, by Higham's iteration and by the SVD, and the
// derivative of its rotation. This file stands in for common/src/corotation/polar_decomposition.cpp
// when assignment 02 is graded (./kerf.sh assignment 02); what to compute is in
// assignments/02_corotation/README.md.
#include "kerf/corotation/polar_decomposition.hpp"

#include <Eigen/Dense> // inverse(), determinant(), partialPivLu()
#include <Eigen/SVD>   // Eigen::JacobiSVD
#include <cmath>
#include <stdexcept>

namespace kerf {

/// Higham's scaled Newton iteration for the orthogonal polar factor (Higham 1986, the method
/// Schoch et al. cite for eq. 31): X_{k+1} = (g X_k + X_k^{-T} / g) / 2 with the Frobenius
/// scaling g = sqrt(|X_k^{-1}|_F / |X_k|_F), from X_0 = F, until |X_{k+1} - X_k|_F <= tolerance.
/// Returns R = the last X, S = R^T F, `iterations` = the Newton steps taken, and `converged`
/// false when det X is 0 or not finite (the iteration cannot start or go on), when
/// max_iterations pass without convergence, or when it converged to a reflection (det R < 0,
/// an inverted F); `higham_failed` = !converged.
PolarDecomposition polar_higham([[maybe_unused]] const Eigen::Matrix3d& F, [[maybe_unused]] double tolerance,
                                [[maybe_unused]] int max_iterations) {
  throw std::logic_error("assignment 02: implement polar_higham (assignments/02_corotation/README.md)");
}

/// The rotation from the singular value decomposition F = U Sigma V^T: R = U V^T, and if
/// det(U V^T) < 0, the column of U that belongs to the smallest singular value changes sign
/// (so does that singular value), which makes R a rotation (det R = +1) and leaves S = V Sigma V^T
/// with one negative eigenvalue: the element is reported inverted, not reflected
/// (Irving, Teran and Fedkiw 2004). Valid for every F, including det F <= 0.
PolarDecomposition polar_svd([[maybe_unused]] const Eigen::Matrix3d& F) {
  throw std::logic_error("assignment 02: implement polar_svd (assignments/02_corotation/README.md)");
}

/// The derivative of the polar rotation: for F = R S and a change dF, dR = R [w]_x with
///   (tr(S) I - S) w = axial(R^T dF - dF^T R),
/// where [w]_x is the cross-product matrix and axial its inverse. Needs tr(S) I - S invertible,
/// i.e. no two singular values summing to zero (false only at or past inversion).
Eigen::Matrix3d polar_rotation_derivative([[maybe_unused]] const PolarDecomposition& polar,
                                          [[maybe_unused]] const Eigen::Matrix3d& dF) {
  throw std::logic_error("assignment 02: implement polar_rotation_derivative (assignments/02_corotation/README.md)");
}

} // namespace kerf
