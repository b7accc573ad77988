#include "kerf/solve/linear_solver.hpp"

#include <Eigen/CholmodSupport>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <stdexcept>

namespace kerf {

namespace {

const char* not_positive_definite =
    "the stiffness matrix is not positive definite: is the body held by enough Dirichlet conditions?";

// CHOLMOD prints a warning to stderr when a matrix is not positive definite; the callers here
// handle that case themselves (an error message, or a fallback tangent), and every other
// failure also surfaces through info(), so CHOLMOD prints nothing.
template <class Decomposition>
void silence_warnings(Decomposition&) {}
template <class Matrix, int UpLo>
void silence_warnings(Eigen::CholmodSupernodalLLT<Matrix, UpLo>& decomposition) {
  decomposition.cholmod().print = 0;
}

// Whether a successful factorisation shows a positive definite matrix. A Cholesky
// factorisation (CHOLMOD) exists only for one, so success says it all; an LDL^T exists for
// indefinite matrices too, and then some pivot D_ii is negative.
template <class Decomposition>
bool pivots_positive(const Decomposition&) {
  return true;
}
template <class Matrix, int UpLo, class Ordering>
bool pivots_positive(const Eigen::SimplicialLDLT<Matrix, UpLo, Ordering>& decomposition) {
  return decomposition.vectorD().size() == 0 || decomposition.vectorD().minCoeff() > 0.0;
}

void require_finite_right_hand_side(const Eigen::VectorXd& b) {
  if (!b.allFinite())
    throw std::invalid_argument("the right-hand side is not finite: an infinite or NaN load or prescribed displacement");
}

/// A direct Cholesky-type solver wrapping an Eigen decomposition (CHOLMOD or SimplicialLDLT).
template <class Decomposition>
class DirectSolver final : public LinearSolver {
public:
  explicit DirectSolver(std::string name) : name_(std::move(name)) { silence_warnings(decomposition_); }
  std::string name() const override { return name_; }
  void analyze_pattern(const Eigen::SparseMatrix<double>& A) override { decomposition_.analyzePattern(A); }
  void factorize(const Eigen::SparseMatrix<double>& A) override {
    decomposition_.factorize(A);
    if (decomposition_.info() != Eigen::Success || !pivots_positive(decomposition_)) throw NotPositiveDefinite(not_positive_definite);
  }
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    require_finite_right_hand_side(b);
    x = decomposition_.solve(b);
    if (decomposition_.info() != Eigen::Success || !x.allFinite()) throw NotPositiveDefinite(not_positive_definite);
  }

private:
  std::string name_;
  Decomposition decomposition_;
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

private:
  std::string name_;
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper, Preconditioner> cg_;
};

} // namespace

std::unique_ptr<LinearSolver> make_linear_solver(const SolverSettings& settings) {
  using Matrix = Eigen::SparseMatrix<double>;
  if (settings.type == "cholmod")
    return std::make_unique<DirectSolver<Eigen::CholmodSupernodalLLT<Matrix, Eigen::Lower>>>("cholmod");
  if (settings.type == "ldlt")
    return std::make_unique<DirectSolver<Eigen::SimplicialLDLT<Matrix, Eigen::Lower, Eigen::AMDOrdering<int>>>>("ldlt");
  if (settings.type == "cg-jacobi")
    return std::make_unique<ConjugateGradientSolver<Eigen::DiagonalPreconditioner<double>>>("cg-jacobi", settings);
  if (settings.type == "cg-ichol")
    return std::make_unique<ConjugateGradientSolver<Eigen::IncompleteCholesky<double, Eigen::Lower, Eigen::AMDOrdering<int>>>>(
        "cg-ichol", settings);
  throw std::invalid_argument("unknown solver '" + settings.type + "' (expected cholmod, ldlt, cg-jacobi or cg-ichol)");
}

} // namespace kerf
