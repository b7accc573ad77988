#include "kerf/dynamics/critical_time_step.hpp"

#include <cmath>
#include <random>
#include <stdexcept>

namespace kerf {

LargestEigenvalue largest_eigenvalue(const Eigen::SparseMatrix<double>& M_ff, const Eigen::SparseMatrix<double>& K_ff,
                                     double tolerance, int max_iterations, const SolverSettings& solver_settings) {
  if (M_ff.rows() != K_ff.rows() || M_ff.rows() == 0)
    throw std::invalid_argument("largest_eigenvalue: M and K must be non-empty and of one size");
  const std::unique_ptr<LinearSolver> solver = make_linear_solver(solver_settings);
  solver->analyze_pattern(M_ff);
  solver->factorize(M_ff);
  std::mt19937 random(1);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::VectorXd x(M_ff.rows());
  for (Eigen::Index i = 0; i < x.size(); ++i) x[i] = uniform(random);
  x /= std::sqrt(x.dot(M_ff * x));
  LargestEigenvalue result;
  Eigen::VectorXd y = Eigen::VectorXd::Zero(x.size());
  for (result.iterations = 1; result.iterations <= max_iterations; ++result.iterations) {
    const Eigen::VectorXd Kx = K_ff * x;
    const double lambda = x.dot(Kx); // x^T M x = 1
    solver->solve(Kx, y);
    const double norm = std::sqrt(y.dot(M_ff * y));
    if (!(norm > 0.0)) throw std::runtime_error("largest_eigenvalue: K x = 0 (K is zero on the start vector's span)");
    x = y / norm;
    if (std::abs(lambda - result.lambda) <= tolerance * lambda) {
      result.lambda = lambda;
      result.converged = true;
      return result;
    }
    result.lambda = lambda;
  }
  result.iterations = max_iterations;
  return result;
}

double central_difference_critical_step(double lambda) {
  if (!(lambda > 0.0)) throw std::invalid_argument("central_difference_critical_step: omega_max^2 must be positive");
  return 2.0 / std::sqrt(lambda);
}

} // namespace kerf
