#include "kerf/solve/linear_solver.hpp"

#include "kerf/solve/cholmod_solver.hpp"
#include "kerf/solve/reused_factorisation_cg.hpp"
#include "kerf/solve/symmetric_block_matrix.hpp"
#include "solve/solver_checks.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <limits>
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

/// Conjugate gradients with the Jacobi preconditioner ("cg-jacobi"), multiplying by A in 3x3
/// blocks (SymmetricBlockMatrix). The iteration is Eigen's ConjugateGradient's, step for step
/// (Saad, Iterative Methods, alg. 9.1: the same stopping test |r|^2 < tolerance^2 |b|^2, the same
/// iteration count, the same reported error), so that it solves as "cg-ichol" and the Eigen CG
/// before it did; only the product, the bottleneck of the algorithm, is our own.
class JacobiCg final : public LinearSolver {
public:
  explicit JacobiCg(const SolverSettings& settings) : tolerance_(settings.tolerance), max_iterations_(settings.max_iterations) {}
  std::string name() const override { return "cg-jacobi"; }
  void analyze_pattern(const Eigen::SparseMatrix<double>& A) override { A_.analyze_pattern(A); }
  void factorize(const Eigen::SparseMatrix<double>& A) override {
    // A caller may skip analyze_pattern() after the pattern changed: it is checked, not trusted.
    if (!A_.has_pattern_of(A)) A_.analyze_pattern(A);
    A_.set_values(A);
    // A positive definite matrix has a positive diagonal (A_ii = e_i^T A e_i): Jacobi divides by it.
    const Eigen::VectorXd diagonal = A_.diagonal().head(A.rows());
    if (A.rows() > 0 && !(diagonal.minCoeff() > 0.0)) throw NotPositiveDefinite(not_positive_definite);
    ++factorisations_;
    inverse_diagonal_ = Eigen::VectorXd::Zero(A_.padded_size());
    inverse_diagonal_.head(A.rows()) = diagonal.cwiseInverse();
  }
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    require_finite_right_hand_side(b);
    const Eigen::Index n = A_.size(), padded = A_.padded_size();
    if (b.size() != n) throw std::invalid_argument("cg-jacobi: the right-hand side does not have the matrix's size");
    if (x.size() != n) x = Eigen::VectorXd::Zero(n);
    // The vectors padded to whole blocks (their padding stays 0).
    Eigen::VectorXd b_padded = Eigen::VectorXd::Zero(padded), x_padded = Eigen::VectorXd::Zero(padded);
    b_padded.head(n) = b;
    x_padded.head(n) = x;
    Eigen::VectorXd residual(padded), p(padded), z(padded), Ap(padded);
    A_.multiply(x_padded, Ap);
    residual = b_padded - Ap;
    const double b_norm2 = b.squaredNorm();
    iterations_ = 0;
    error_ = 0.0;
    if (b_norm2 == 0.0) {
      x.setZero();
      return;
    }
    const double threshold = std::max(tolerance_ * tolerance_ * b_norm2, std::numeric_limits<double>::min());
    double residual_norm2 = residual.squaredNorm();
    if (residual_norm2 >= threshold) {
      p = inverse_diagonal_.cwiseProduct(residual);
      double rz = residual.dot(p);
      int i = 0;
      while (i < max_iterations_) {
        A_.multiply(p, Ap);
        const double alpha = rz / p.dot(Ap);
        x_padded += alpha * p;
        residual -= alpha * Ap;
        residual_norm2 = residual.squaredNorm();
        if (residual_norm2 < threshold) break;
        z = inverse_diagonal_.cwiseProduct(residual);
        const double rz_old = rz;
        rz = residual.dot(z);
        p = z + (rz / rz_old) * p;
        ++i;
      }
      iterations_ = i;
    }
    error_ = std::sqrt(residual_norm2 / b_norm2);
    x = x_padded.head(n);
    if (!x.allFinite()) throw NotPositiveDefinite(not_positive_definite);
    if (!(error_ <= tolerance_))
      throw std::runtime_error("cg-jacobi did not converge in " + std::to_string(iterations_) + " iterations (relative residual " +
                               std::to_string(error_) + ")");
    // With the residual r = b - A x, x^T A x = b . x - x . r <= b . x + |x| |r|: if even this
    // bound is <= 0, A is proven not positive definite (as for Eigen's CG below).
    if (b.dot(x) + x.norm() * error_ * b.norm() <= 0.0) throw NotPositiveDefinite(not_positive_definite);
  }
  int iterations() const override { return iterations_; }
  int factorisations() const override { return factorisations_; }

private:
  SymmetricBlockMatrix A_;
  Eigen::VectorXd inverse_diagonal_;
  double tolerance_;
  int max_iterations_;
  int iterations_ = 0;
  double error_ = 0.0;
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
  if (settings.type == "cg-jacobi") return std::make_unique<JacobiCg>(settings);
  if (settings.type == "cg-ichol")
    return std::make_unique<ConjugateGradientSolver<Eigen::IncompleteCholesky<double, Eigen::Lower, Eigen::AMDOrdering<int>>>>(
        "cg-ichol", settings);
  throw std::invalid_argument("unknown solver '" + settings.type + "' (expected cholmod, ldlt, cg-jacobi, cg-ichol or cg-cholmod)");
}

} // namespace kerf
