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
///
/// With a basis (PreconditionerBasis) it is the same algorithm on S^T A S w = S^T b with Jacobi's
/// scaling D = diag(S^T A S), run on each of the basis's components with its own step lengths,
/// the correction summed in the basis and added as S dw (so no S^-1 is needed for the starting
/// guess): Saad's alg. 9.1
/// with the preconditioner S D^-1 S^T, once per independent system. Its stopping test is each
/// component's |r_w| <= tolerance |b_w| in that basis, which implies the whole system's.
class JacobiCg final : public LinearSolver {
public:
  explicit JacobiCg(const SolverSettings& settings) : tolerance_(settings.tolerance), max_iterations_(settings.max_iterations) {}
  std::string name() const override { return "cg-jacobi"; }
  void analyze_pattern(const Eigen::SparseMatrix<double>& A) override { A_.analyze_pattern(A); }
  void set_preconditioner_basis(const PreconditionerBasis& basis) override {
    const Eigen::Index n = basis.S.rows();
    if (basis.S.cols() != n) throw std::invalid_argument("cg-jacobi: the preconditioner's basis must be square");
    if (!basis.component.empty() && static_cast<Eigen::Index>(basis.component.size()) != n)
      throw std::invalid_argument("cg-jacobi: the basis's components must label every column");
    S_ = basis.S;
    S_.makeCompressed();
    // S = I + E with E small for the part basis (a few entries per enriched node): the products
    // with S and S^T cost |E| beyond a copy, not |S|.
    Eigen::SparseMatrix<double> identity(n, n);
    identity.setIdentity();
    E_ = S_ - identity;
    E_.prune(0.0);
    E_transpose_ = E_.transpose();
    component_ = basis.component.empty() ? std::vector<int>(static_cast<std::size_t>(n), 0) : basis.component;
    num_components_ = 0;
    for (const int c : component_) {
      if (c < 0) throw std::invalid_argument("cg-jacobi: a basis component label is negative");
      num_components_ = std::max(num_components_, c + 1);
    }
  }
  void factorize(const Eigen::SparseMatrix<double>& A) override {
    // A caller may skip analyze_pattern() after the pattern changed: it is checked, not trusted.
    if (!A_.has_pattern_of(A)) A_.analyze_pattern(A);
    A_.set_values(A);
    if (S_.size() > 0 && S_.rows() != A.rows())
      throw std::invalid_argument("cg-jacobi: the preconditioner's basis is not of the matrix's size");
    // A positive definite matrix has a positive diagonal (e^T A e > 0 for every e, the basis
    // vectors s_j included): Jacobi divides by it.
    const Eigen::VectorXd diagonal = S_.size() > 0 ? diagonal_in_basis(A) : Eigen::VectorXd(A_.diagonal().head(A.rows()));
    if (A.rows() > 0 && !(diagonal.minCoeff() > 0.0)) throw NotPositiveDefinite(not_positive_definite);
    ++factorisations_;
    inverse_diagonal_ = Eigen::VectorXd::Zero(S_.size() > 0 ? A.rows() : A_.padded_size());
    inverse_diagonal_.head(A.rows()) = diagonal.cwiseInverse();
  }
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    require_finite_right_hand_side(b);
    const Eigen::Index n = A_.size();
    if (b.size() != n) throw std::invalid_argument("cg-jacobi: the right-hand side does not have the matrix's size");
    if (x.size() != n) x = Eigen::VectorXd::Zero(n);
    const bool converged = S_.size() > 0 ? solve_in_basis(b, x) : solve_in_unknowns(b, x);
    if (!x.allFinite()) throw NotPositiveDefinite(not_positive_definite);
    if (!converged)
      throw std::runtime_error("cg-jacobi did not converge in " + std::to_string(iterations_) + " iterations (relative residual " +
                               std::to_string(error_) + ")");
  }
  int iterations() const override { return iterations_; }
  int factorisations() const override { return factorisations_; }

private:
  // Eigen's iteration (the class comment), on the unknowns themselves. Returns whether it met
  // the tolerance.
  bool solve_in_unknowns(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
    const Eigen::Index n = A_.size(), padded = A_.padded_size();
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
      return true;
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
    // With the residual r = b - A x, x^T A x = b . x - x . r <= b . x + |x| |r|: if even this
    // bound is <= 0, A is proven not positive definite (as for Eigen's CG below).
    if (b.dot(x) + x.norm() * error_ * b.norm() <= 0.0) throw NotPositiveDefinite(not_positive_definite);
    return error_ <= tolerance_;
  }

  // The same iteration in the basis, one per component (the class comment). Vectors named _w
  // live in the basis (size n), the others are the unknowns padded to whole blocks; all are the
  // solver's own, sized once, so that an iteration allocates nothing. Returns whether every
  // component met the tolerance.
  bool solve_in_basis(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
    const Eigen::Index n = A_.size(), padded = A_.padded_size();
    const auto C = static_cast<std::size_t>(num_components_);
    if (q_.size() != padded) {
      q_ = Eigen::VectorXd::Zero(padded);
      Aq_.resize(padded);
    }
    for (Eigen::VectorXd* v : {&r_w_, &b_w_, &g_w_, &z_w_, &p_w_, &Ap_w_, &dx_w_})
      if (v->size() != n) v->resize(n);
    // w_out = S^T v = v + E^T v and w_out = S w = w + E w (S = I + E).
    const auto S_transpose_times = [&](const auto& v, Eigen::VectorXd& w_out) {
      w_out = v;
      w_out.noalias() += E_transpose_ * v;
    };
    const auto S_times = [&](const Eigen::VectorXd& w, auto&& v_out) {
      v_out = w;
      v_out.noalias() += E_ * w;
    };
    // A x0 of the starting guess x0 = x, and g_w = S^T A x0, r_w = S^T b - g_w.
    q_.head(n) = x;
    A_.multiply(q_, Aq_);
    const double x0_A_x0 = x.dot(Aq_.head(n));
    S_transpose_times(Aq_.head(n), g_w_);
    S_transpose_times(b, b_w_);
    r_w_ = b_w_ - g_w_;
    // Per component: a dot product u . v over its unknowns (one component: the whole vector).
    const auto per_component = [&](const Eigen::VectorXd& u, const Eigen::VectorXd& v, std::vector<double>& sum) {
      sum.assign(C, 0.0);
      if (C == 1) {
        sum[0] = u.dot(v);
        return;
      }
      for (Eigen::Index j = 0; j < n; ++j) sum[static_cast<std::size_t>(component_[static_cast<std::size_t>(j)])] += u[j] * v[j];
    };
    std::vector<double> b_norm2, residual_norm2, threshold(C), rz, rz_new, pAp, alpha(C), beta(C);
    per_component(b_w_, b_w_, b_norm2);
    per_component(r_w_, r_w_, residual_norm2);
    std::vector<char> active(C);
    for (std::size_t c = 0; c < C; ++c) {
      threshold[c] = std::max(tolerance_ * tolerance_ * b_norm2[c], std::numeric_limits<double>::min());
      active[c] = residual_norm2[c] >= threshold[c];
    }
    const auto any_active = [&] { return std::find(active.begin(), active.end(), 1) != active.end(); };
    // target += sign value[c] v on each active component c (the converged ones then stay where they are).
    const auto add_scaled = [&](double sign, const std::vector<double>& value, const Eigen::VectorXd& v, Eigen::VectorXd& target) {
      if (C == 1) {
        if (active[0]) target += (sign * value[0]) * v;
        return;
      }
      for (Eigen::Index j = 0; j < n; ++j) {
        const auto c = static_cast<std::size_t>(component_[static_cast<std::size_t>(j)]);
        if (active[c]) target[j] += sign * value[c] * v[j];
      }
    };
    iterations_ = 0;
    dx_w_.setZero();
    if (any_active()) {
      // The correction is summed in the basis and mapped to the unknowns once, at the end.
      z_w_ = inverse_diagonal_.cwiseProduct(r_w_);
      p_w_ = z_w_;
      per_component(r_w_, z_w_, rz);
      int i = 0;
      while (i < max_iterations_) {
        S_times(p_w_, q_.head(n));
        A_.multiply(q_, Aq_);
        S_transpose_times(Aq_.head(n), Ap_w_);
        per_component(p_w_, Ap_w_, pAp);
        for (std::size_t c = 0; c < C; ++c) alpha[c] = active[c] ? rz[c] / pAp[c] : 0.0;
        add_scaled(1.0, alpha, p_w_, dx_w_);
        add_scaled(-1.0, alpha, Ap_w_, r_w_);
        per_component(r_w_, r_w_, residual_norm2);
        for (std::size_t c = 0; c < C; ++c) active[c] = active[c] && residual_norm2[c] >= threshold[c];
        if (!any_active()) break;
        z_w_ = inverse_diagonal_.cwiseProduct(r_w_);
        per_component(r_w_, z_w_, rz_new);
        for (std::size_t c = 0; c < C; ++c) beta[c] = active[c] ? rz_new[c] / rz[c] : 0.0;
        rz.swap(rz_new);
        // p = z + beta p on the active components; the others' p is not read again.
        if (C == 1) {
          p_w_ = z_w_ + beta[0] * p_w_;
        } else {
          for (Eigen::Index j = 0; j < n; ++j) p_w_[j] = z_w_[j] + beta[static_cast<std::size_t>(component_[static_cast<std::size_t>(j)])] * p_w_[j];
        }
        ++i;
      }
      iterations_ = i;
    }
    double b_total = 0.0, r_total = 0.0;
    for (std::size_t c = 0; c < C; ++c) {
      b_total += b_norm2[c];
      r_total += residual_norm2[c];
    }
    // x = x0 + S dw.
    S_times(dx_w_, q_.head(n));
    x += q_.head(n);
    if (b_total == 0.0) {
      x.setZero();
      error_ = 0.0;
      return true;
    }
    error_ = std::sqrt(r_total / b_total);
    // A proof of indefiniteness as in the unknowns, without another product: with x = x0 + S w
    // and S^T A S w = b_w - g_w - r_w (r_w the iteration's residual in the basis),
    // x^T A x = x0^T A x0 + w . g_w + w . b_w - w . r_w <= x0^T A x0 + w . (g_w + b_w) + |w| |r_w|.
    if (x0_A_x0 + dx_w_.dot(g_w_ + b_w_) + dx_w_.norm() * r_w_.norm() <= 0.0) throw NotPositiveDefinite(not_positive_definite);
    return !any_active();
  }

  // The diagonal of S^T A S: s_j^T A s_j = sum over the entries a, b of column j of
  // s_a s_b A(r_a, r_b). A column of one entry (most of them) takes A's diagonal; the others look
  // A up in its upper triangle only (the step's matrices may store no more).
  Eigen::VectorXd diagonal_in_basis(const Eigen::SparseMatrix<double>& A) const {
    const Eigen::VectorXd A_diagonal = A_.diagonal();
    Eigen::VectorXd d = Eigen::VectorXd::Zero(S_.cols());
    for (Eigen::Index j = 0; j < S_.cols(); ++j) {
      const Eigen::Index begin = S_.outerIndexPtr()[j], end = S_.outerIndexPtr()[j + 1];
      if (end - begin == 1) {
        const double s = S_.valuePtr()[begin];
        d[j] = s * s * A_diagonal[S_.innerIndexPtr()[begin]];
        continue;
      }
      for (Eigen::Index a = begin; a < end; ++a)
        for (Eigen::Index c = begin; c < end; ++c) {
          const Eigen::Index row = S_.innerIndexPtr()[a], column = S_.innerIndexPtr()[c];
          d[j] += S_.valuePtr()[a] * S_.valuePtr()[c] * A.coeff(std::min(row, column), std::max(row, column));
        }
    }
    return d;
  }

  SymmetricBlockMatrix A_;
  Eigen::SparseMatrix<double> S_; // the preconditioner's basis; empty: the unknowns themselves
  Eigen::SparseMatrix<double> E_, E_transpose_; // S - I and its transpose
  std::vector<int> component_;    // per column of S_, its component
  int num_components_ = 0;
  Eigen::VectorXd inverse_diagonal_;
  // solve_in_basis's vectors, kept from solve to solve: the unknowns padded to whole blocks (q_,
  // Aq_) and the basis's (r_w_ residual, b_w_ = S^T b, g_w_ = S^T A x0, z_w_, p_w_, Ap_w_, dx_w_).
  Eigen::VectorXd q_, Aq_, r_w_, b_w_, g_w_, z_w_, p_w_, Ap_w_, dx_w_;
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
