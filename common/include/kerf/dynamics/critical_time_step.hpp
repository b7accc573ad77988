/// @file critical_time_step.hpp
/// @brief The largest eigenvalue omega_max^2 of M^-1 K by power iteration, and the central difference's critical step 2 / omega_max.
#pragma once

#include "kerf/solve/linear_solver.hpp"

#include <Eigen/SparseCore>

namespace kerf {

/// The result of the power iteration.
struct LargestEigenvalue {
  double lambda = 0.0; ///< omega_max^2, 1/s^2: the last Rayleigh quotient x^T K x / x^T M x
  int iterations = 0;  ///< iterations done
  bool converged = false; ///< whether the quotient settled to the tolerance before max_iterations
};

/// omega_max^2, the largest lambda of K x = lambda M x, by power iteration on M^-1 K:
/// x <- M^-1 K x, normalised in the M norm, until two Rayleigh quotients agree to `tolerance`
/// (relative). The start vector is pseudo-random with a fixed seed, so it has a part along the
/// top mode almost surely, and the run is reproducible.
///
/// The Rayleigh quotient never exceeds lambda_max, and it converges like (lambda_2 / lambda_1)^(2k):
/// slowly when the top of the spectrum is crowded (a fine mesh). An unconverged estimate errs on
/// the unsafe side (too small a lambda, too large a critical step): check `converged`.
/// @param M_ff mass on the free DOFs, symmetric positive definite
/// @param K_ff stiffness on the free DOFs, symmetric positive semi-definite, same size
LargestEigenvalue largest_eigenvalue(const Eigen::SparseMatrix<double>& M_ff, const Eigen::SparseMatrix<double>& K_ff,
                                     double tolerance = 1e-12, int max_iterations = 20000,
                                     const SolverSettings& solver_settings = {});

/// The central difference's critical step 2 / omega_max (s) for lambda = omega_max^2. Rayleigh
/// damping in the form the Newmark step takes it (v_{n+1} implicit, gamma = 1/2) does not lower
/// it (Hughes 2000, section 9.1: Omega_crit = 2 for gamma = 1/2 whatever the damping ratio); the
/// half-step velocity form of explicit codes would need (2 / omega)(sqrt(1 + xi^2) - xi).
double central_difference_critical_step(double lambda);

} // namespace kerf
