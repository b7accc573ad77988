#include "kerf/solve/linear_solver.hpp"

#include "kerf/solve/cholmod_solver.hpp"
#include "kerf/solve/reused_factorisation_cg.hpp"
#include "solve/solver_checks.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <stdexcept>

namespace kerf {

namespace {

using solver_checks::not_positive_definite;
using solver_checks::require_finite_right_hand_side;

/// Eigen's SimplicialLDLT, with its pivots checked: an LDL^T exists for indefinite matrices
/// too, and then some pivot D_ii is negative (Eigen itself stops only on an exactly zero one).
class LdltSolver final : public LinearSolver {
public:
  std::string name() const override { return "ldlt"; }
  void analyze_pattern(const Eigen::SparseMatrix<double>& A) override { ldlt_.analyzePattern(A); }
  void factorize(const Eigen::SparseMatrix<double>& A) override {
    ++factorisations_;
    ldlt_.factorize(A);
    const bool pivots_positive = ldlt_.vectorD().size() == 0 || ldlt_.vectorD().minCoeff() > 0.0;
    if (ldlt_.info() != Eigen::Success || !pivots_positive) throw NotPositiveDefinite(not_positive_definite);
  }
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    require_finite_right_hand_side(b);
    x = ldlt_.solve(b);
    if (ldlt_.info() != Eigen::Success || !x.allFinite()) throw NotPositiveDefinite(not_positive_definite);
  }

  int factorisations() const override { return factorisations_; }

private:
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> ldlt_;
  int factorisations_ = 0;
};

/// Preconditioned conjugate gradients; the preconditioner is built in factorize().
template <class Preconditioner>
class ConjugateGradientSolver final : public LinearSolver {
public:
  ConjugateGradientSolver(std::string name, const SolverSettings& settings) : name_(std::move(name)) {
    cg_.setTolerance(settings.tolerance);
    cg_.setMaxIterations(settings.max_iterations);
  }
  std::string name() const override { return name_; }
  void analyze_pattern(const Eigen::SparseMatrix<double>& A) override { cg_.analyzePattern(A); }
  void factorize(const Eigen::SparseMatrix<double>& A) override {
    // A positive definite matrix has a positive diagonal (A_ii = e_i^T A e_i); Jacobi would
    // divide by the diagonal and the incomplete Cholesky fail on it.
    if (A.rows() > 0 && !(A.diagonal().minCoeff() > 0.0)) throw NotPositiveDefinite(not_positive_definite);
    ++factorisations_;
    cg_.factorize(A);
    if (cg_.info() != Eigen::Success) throw NotPositiveDefinite(not_positive_definite);
  }
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    require_finite_right_hand_side(b);
    if (x.size() != b.size()) x = Eigen::VectorXd::Zero(b.size());
    x = cg_.solveWithGuess(b, x);
    if (!x.allFinite()) throw NotPositiveDefinite(not_positive_definite);
    if (cg_.info() != Eigen::Success)
      throw std::runtime_error(name_ + " did not converge in " + std::to_string(cg_.iterations()) +
                               " iterations (relative residual " + std::to_string(cg_.error()) + ")");
    // With the residual r = b - A x, x^T A x = b . x - x . r <= b . x + |x| |r|, and
    // |r| = error |b|. A positive definite A has x^T A x > 0: if even this bound is <= 0, A is
    // proven not positive definite (CG on such a matrix can still "converge").
    if (b.dot(x) + x.norm() * cg_.error() * b.norm() <= 0.0 && b.squaredNorm() > 0.0)
      throw NotPositiveDefinite(not_positive_definite);
  }
  int iterations() const override { return static_cast<int>(cg_.iterations()); }
  int factorisations() const override { return factorisations_; }

private:
  std::string name_;
  int factorisations_ = 0;
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Upper, Preconditioner> cg_;
};

} // namespace

Eigen::VectorXd solve_once(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& b, const SolverSettings& settings) {
  auto solver = make_linear_solver(settings);
  solver->analyze_pattern(A);
  solver->factorize(A);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size());
  solver->solve(b, x);
  return x;
}

std::unique_ptr<LinearSolver> make_linear_solver(const SolverSettings& settings) {
  if (settings.type == "cholmod") return std::make_unique<CholmodSolver>(settings.ordering);
  if (settings.type == "cg-cholmod") return std::make_unique<ReusedFactorisationCg>(settings.tolerance, settings.refresh_iterations,
                                                                                         settings.ordering);
  if (settings.type == "ldlt") return std::make_unique<LdltSolver>();
  if (settings.type == "cg-jacobi")
    return std::make_unique<ConjugateGradientSolver<Eigen::DiagonalPreconditioner<double>>>("cg-jacobi", settings);
  if (settings.type == "cg-ichol")
    return std::make_unique<ConjugateGradientSolver<Eigen::IncompleteCholesky<double, Eigen::Lower, Eigen::AMDOrdering<int>>>>(
        "cg-ichol", settings);
  throw std::invalid_argument("unknown solver '" + settings.type + "' (expected cholmod, ldlt, cg-jacobi, cg-ichol or cg-cholmod)");
}

} // namespace kerf
