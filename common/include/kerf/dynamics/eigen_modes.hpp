/// @file eigen_modes.hpp
/// @brief The lowest natural frequencies and modes, K phi = omega^2 M phi, by shift-invert subspace iteration on one sparse factorisation.
#pragma once

#include "kerf/solve/linear_solver.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace kerf {

/// The lowest eigenpairs found, in increasing order.
struct EigenModes {
  Eigen::VectorXd lambda; ///< omega_k^2 (1/s^2), increasing; the natural frequencies are sqrt(lambda) / (2 pi) Hz
  Eigen::MatrixXd phi;    ///< the modes as columns, M-orthonormal: phi^T M phi = I, phi^T K phi = diag(lambda)
  int iterations = 0;     ///< subspace iterations done
  bool converged = false; ///< whether every wanted lambda settled to the tolerance
};

/// The `count` smallest lambda of K phi = lambda M phi (K symmetric positive semi-definite, M
/// symmetric positive definite, both on the free DOFs) nearest above `shift`, by subspace
/// iteration with shift-invert and Rayleigh-Ritz (Bathe, Finite Element Procedures, 1996,
/// section 11.6):
///
///   X_bar = (K - shift M)^-1 M X,                 one factorisation, q solves per iteration
///   K_r = X_bar^T K X_bar,  M_r = X_bar^T M X_bar,  K_r Q = M_r Q Lambda   (dense, q x q)
///   X = X_bar Q,
///
/// on q = max(2 count, count + 8) vectors (Bathe's choice), the start block pseudo-random with a
/// fixed seed (reproducible, and almost surely not orthogonal to a wanted mode). Eigenvalue k
/// converges like (lambda_k / lambda_{q+1})^(2 iterations) after the shift; we stop when every
/// wanted lambda changes by less than `tolerance` times max(|lambda|, |lambda - shift|) between
/// two iterations (the second term lets a rigid mode, lambda = 0, converge). The shift
/// must not be an eigenvalue; 0 serves a clamped body (K positive definite), a small negative
/// shift a free one. Bathe's Sturm sequence check, which proves no eigenvalue was skipped, is
/// not done: a test against an independent solver (CalculiX *FREQUENCY) stands in for it.
/// @throws std::invalid_argument on mismatched sizes or count < 1 or count too large for the matrix
EigenModes lowest_eigenmodes(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M, int count,
                             double shift = 0.0, double tolerance = 1e-12, int max_iterations = 500,
                             const SolverSettings& solver_settings = {});

} // namespace kerf
