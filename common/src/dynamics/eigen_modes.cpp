#include "kerf/dynamics/eigen_modes.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <limits>
#include <random>
#include <stdexcept>

namespace kerf {

EigenModes lowest_eigenmodes(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M, int count,
                             double shift, double tolerance, int max_iterations, const SolverSettings& solver_settings) {
  const Eigen::Index n = K.rows();
  if (K.cols() != n || M.rows() != n || M.cols() != n)
    throw std::invalid_argument("lowest_eigenmodes: K and M must be square and of the same size");
  if (count < 1 || count > n) throw std::invalid_argument("lowest_eigenmodes: count must be between 1 and the size of K");
  const auto q = static_cast<Eigen::Index>(std::min<Eigen::Index>(n, std::max(2 * count, count + 8)));

  const Eigen::SparseMatrix<double> shifted = K - shift * M;
  const auto solver = make_linear_solver(solver_settings);
  solver->analyze_pattern(shifted);
  solver->factorize(shifted);

  std::mt19937 generator(20260611u);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::MatrixXd X(n, q);
  for (Eigen::Index j = 0; j < q; ++j)
    for (Eigen::Index i = 0; i < n; ++i) X(i, j) = uniform(generator);

  EigenModes modes;
  Eigen::VectorXd previous = Eigen::VectorXd::Constant(count, std::numeric_limits<double>::infinity());
  Eigen::MatrixXd X_bar(n, q);
  Eigen::VectorXd column(n);
  for (modes.iterations = 1; modes.iterations <= max_iterations; ++modes.iterations) {
    const Eigen::MatrixXd MX = M * X;
    for (Eigen::Index j = 0; j < q; ++j) {
      column.setZero();
      solver->solve(MX.col(j), column);
      X_bar.col(j) = column;
    }
    const Eigen::MatrixXd K_r = X_bar.transpose() * (K * X_bar);
    const Eigen::MatrixXd M_r = X_bar.transpose() * (M * X_bar);
    // Symmetrise against round-off before the dense generalized solve (Cholesky of M_r).
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ritz(0.5 * (K_r + K_r.transpose()),
                                                                          0.5 * (M_r + M_r.transpose()));
    if (ritz.info() != Eigen::Success) throw std::runtime_error("lowest_eigenmodes: the Ritz problem failed (M not positive definite?)");
    X = X_bar * ritz.eigenvectors(); // M-orthonormal: Q^T M_r Q = I
    modes.lambda = ritz.eigenvalues().head(count);
    // Relative to |lambda|, or to its distance from the shift where that is larger: a rigid
    // mode's lambda = 0 (found with a negative shift) settles at round-off, never relatively.
    const Eigen::ArrayXd scale = modes.lambda.cwiseAbs().array().max((modes.lambda.array() - shift).abs());
    modes.converged = ((modes.lambda - previous).cwiseAbs().array() <= tolerance * scale).all();
    previous = modes.lambda;
    if (modes.converged) break;
  }
  modes.iterations = std::min(modes.iterations, max_iterations);
  modes.phi = X.leftCols(count);
  return modes;
}

} // namespace kerf
