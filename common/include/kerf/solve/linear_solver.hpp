/// @file linear_solver.hpp
/// @brief Sparse symmetric positive definite solvers behind one small interface.
#pragma once

#include <Eigen/SparseCore>
#include <memory>
#include <string>

namespace kerf {

/// Which solver, and how hard an iterative one works.
struct SolverSettings {
  /// "cholmod" (supernodal Cholesky, the default), "ldlt" (Eigen's SimplicialLDLT, a teaching
  /// fallback), "cg-jacobi" or "cg-ichol" (conjugate gradients with a Jacobi or an incomplete
  /// Cholesky preconditioner).
  std::string type = "cholmod";
  double tolerance = 1e-10;  ///< CG: stop when |b - A x| <= tolerance |b|
  int max_iterations = 10000; ///< CG: give up (with an error) after this many iterations
};

/// A solver for A x = b with A sparse, symmetric positive definite, both triangles stored.
///
/// The three calls separate what depends on the pattern (ordering, symbolic factorisation),
/// on the values (numeric factorisation, preconditioner) and on the right-hand side, so that a
/// time-stepping chapter pays for each only when it changes.
class LinearSolver {
public:
  virtual ~LinearSolver() = default;
  /// The solver's name as in SolverSettings::type.
  virtual std::string name() const = 0;
  /// Symbolic analysis of A's pattern; call again only when the pattern changes.
  virtual void analyze_pattern(const Eigen::SparseMatrix<double>& A) = 0;
  /// Numeric factorisation (or preconditioner set-up) for A's values. Throws
  /// std::runtime_error if A is not positive definite (e.g. too few Dirichlet conditions).
  virtual void factorize(const Eigen::SparseMatrix<double>& A) = 0;
  /// Solves A x = b. On entry x is the initial guess of an iterative solver (ignored by direct
  /// ones); throws std::runtime_error if CG does not converge.
  virtual void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) = 0;
  /// Iterations of the last solve (1 for a direct solver).
  virtual int iterations() const { return 1; }
};

/// Makes the solver named in `settings` (std::invalid_argument for an unknown name).
std::unique_ptr<LinearSolver> make_linear_solver(const SolverSettings& settings);

} // namespace kerf
