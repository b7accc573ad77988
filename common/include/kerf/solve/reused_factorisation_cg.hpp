/// @file reused_factorisation_cg.hpp
/// @brief Conjugate gradients preconditioned by a Cholesky factorisation of an earlier matrix.
#pragma once

#include "kerf/solve/cholmod_solver.hpp"

#include <Eigen/SparseCore>
#include <string>

namespace kerf {

/// A x = b for a sequence of matrices that change a little from one call to the next, as the
/// tangents of Newton's method and of time stepping do: conjugate gradients on the current A,
/// preconditioned by the CHOLMOD factor L L^T of an earlier one, refactorised only when that
/// stops paying (SolverSettings::type "cg-cholmod").
///
/// With M = L L^T, PCG converges in a number of iterations set by the spread of the eigenvalues
/// of M^{-1} A: one iteration when M = A, a few while A has moved little. An iteration costs
/// a product with A and two triangular solves with L, a fraction of a factorisation: on chapter
/// 2's benchmark beam (6534 unknowns) one factorisation costs about as much as a dozen iterations.
/// The rule, in iterations so that it does not depend on the machine's load: a solve that needs
/// more than `refresh_iterations` makes the next factorize() refactorise; a solve that has not
/// converged after twice as many refactorises at once and finishes with the new factor.
///
/// The first factorize() always factorises. Like every LinearSolver, factorize() throws
/// NotPositiveDefinite for a matrix CHOLMOD cannot factorise, and solve() throws it when a
/// search direction p has p^T A p <= 0, which proves A indefinite.
class ReusedFactorisationCg final : public LinearSolver {
public:
  /// `tolerance`: stop when |b - A x| <= tolerance |b|; `refresh_iterations`: see above;
  /// `ordering`: CHOLMOD's (CholmodSolver).
  explicit ReusedFactorisationCg(double tolerance = 1e-10, int refresh_iterations = 10,
                                 const std::string& ordering = "nested-dissection");

  std::string name() const override { return "cg-cholmod"; }
  void analyze_pattern(const Eigen::SparseMatrix<double>& A) override;
  /// Keeps a copy of A for the iterations; factorises it if there is no factor yet or the
  /// last solve asked for a fresh one.
  void factorize(const Eigen::SparseMatrix<double>& A) override;
  /// PCG from the initial guess x.
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override;
  int iterations() const override { return iterations_; }
  int factorisations() const override { return factorisations_; }

private:
  void refactorise();

  CholmodSolver cholmod_;
  Eigen::SparseMatrix<double> A_; ///< the matrix of the last factorize()
  double tolerance_;
  int refresh_iterations_;
  bool factor_is_stale_ = true;   ///< refactorise at the next factorize()
  bool factor_matches_A_ = false; ///< the factor is of A_ itself
  int iterations_ = 0;
  int factorisations_ = 0;
};

} // namespace kerf
