#include "kerf/solve/reused_factorisation_cg.hpp"

#include "solve/solver_checks.hpp"

#include <stdexcept>

namespace kerf {

ReusedFactorisationCg::ReusedFactorisationCg(double tolerance, int refresh_iterations, const std::string& ordering)
    : cholmod_(ordering), tolerance_(tolerance), refresh_iterations_(refresh_iterations) {
  if (!(tolerance > 0.0 && tolerance < 1.0)) throw std::invalid_argument("cg-cholmod: the tolerance must be in (0, 1)");
  if (refresh_iterations < 1) throw std::invalid_argument("cg-cholmod: refresh_iterations must be positive");
}

void ReusedFactorisationCg::analyze_pattern(const Eigen::SparseMatrix<double>& A) {
  cholmod_.analyze_pattern(A);
  factor_is_stale_ = true;
  factor_matches_A_ = false;
}

void ReusedFactorisationCg::factorize(const Eigen::SparseMatrix<double>& A) {
  A_ = A;
  factor_matches_A_ = false;
  if (factor_is_stale_) refactorise();
}

void ReusedFactorisationCg::refactorise() {
  cholmod_.factorize(A_);
  ++factorisations_;
  factor_is_stale_ = false;
  factor_matches_A_ = true;
}

void ReusedFactorisationCg::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  if (A_.rows() == 0 && b.size() > 0) throw std::logic_error("cg-cholmod: solve before factorize");
  if (b.size() != A_.rows()) throw std::invalid_argument("cg-cholmod: the right-hand side does not have the matrix's size");
  solver_checks::require_finite_right_hand_side(b);
  if (x.size() != b.size()) x = Eigen::VectorXd::Zero(b.size());
  iterations_ = 0;
  if (factor_matches_A_) { // the factor is exact: no iteration needed
    cholmod_.solve(b, x);
    iterations_ = 1;
    return;
  }
  const double target = tolerance_ * b.norm();
  const int give_up_after = 2 * refresh_iterations_;

  // Preconditioned conjugate gradients (Saad, Iterative Methods, alg. 9.1), z = (L L^T)^{-1} r.
  Eigen::VectorXd r = b - A_ * x;
  Eigen::VectorXd z(b.size()), p(b.size()), Ap(b.size());
  bool converged = r.norm() <= target;
  if (!converged) {
    cholmod_.solve(r, z);
    p = z;
    double rz = r.dot(z);
    while (iterations_ < give_up_after) {
      Ap = A_ * p;
      const double curvature = p.dot(Ap);
      if (!(curvature > 0.0)) throw NotPositiveDefinite(solver_checks::not_positive_definite);
      const double alpha = rz / curvature;
      x += alpha * p;
      r -= alpha * Ap;
      ++iterations_;
      if (r.norm() <= target) {
        converged = true;
        break;
      }
      cholmod_.solve(r, z);
      const double rz_next = r.dot(z);
      p = z + (rz_next / rz) * p;
      rz = rz_next;
    }
  }
  if (!x.allFinite()) throw NotPositiveDefinite(solver_checks::not_positive_definite);
  if (iterations_ > refresh_iterations_) factor_is_stale_ = true;
  if (!converged) {
    // Twice the refresh count spent: A has moved too far from the factored matrix.
    // Factorise A itself and solve with it; the iterations so far are lost.
    refactorise();
    cholmod_.solve(b, x);
    ++iterations_;
  }
}

} // namespace kerf
