/// @file rayleigh_damping.hpp
/// @brief Rayleigh damping C = alpha M + beta K (Schoch et al. eq. 20).
#pragma once

#include <Eigen/SparseCore>

namespace kerf {

/// C = alpha M + beta K (eq. 20, where S writes D for C and F for the elastic term).
///
/// A mode of frequency omega (K phi = omega^2 M phi) is damped with the ratio
/// xi = alpha / (2 omega) + beta omega / 2: alpha damps the slow modes (and a rigid motion: it is
/// a drag on every velocity, rigid ones included), beta the fast ones. The papers give no values.
///
/// With corotation K is the current rotated stiffness K_R = R K R^T of the step (as
/// in SOFA and Vega: the papers do not say), so that beta damps the rate of strain and not a
/// rigid rotation; rebuild C whenever K_R is rebuilt.
/// @param M mass (any size, square)
/// @param K stiffness of the same size
/// @param alpha mass-proportional coefficient, 1/s
/// @param beta  stiffness-proportional coefficient, s
Eigen::SparseMatrix<double> rayleigh_damping(const Eigen::SparseMatrix<double>& M, const Eigen::SparseMatrix<double>& K,
                                             double alpha, double beta);

} // namespace kerf
