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

/// A direct Cholesky-type solver wrapping an Eigen decomposition (CHOLMOD or SimplicialLDLT).
template <class Decomposition>
class DirectSolver final : public LinearSolver {
public:
  explicit DirectSolver(std::string name) : name_(std::move(name)) { silence_warnings(decomposition_); }
  std::string name() const override { return name_; }
  void analyze_pattern(const Eigen::SparseMatrix<double>& A) override { decomposition_.analyzePattern(A); }
  void factorize(const Eigen::SparseMatrix<double>& A) override {
    decomposition_.factorize(A);
    if (decomposition_.info() != Eigen::Success) throw std::runtime_error(not_positive_definite);
  }
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    x = decomposition_.solve(b);
    if (decomposition_.info() != Eigen::Success || !x.allFinite()) throw std::runtime_error(not_positive_definite);
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
    cg_.factorize(A);
    if (cg_.info() != Eigen::Success) throw std::runtime_error(not_positive_definite);
  }
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    if (x.size() != b.size()) x = Eigen::VectorXd::Zero(b.size());
    x = cg_.solveWithGuess(b, x);
    if (cg_.info() != Eigen::Success || !x.allFinite())
      throw std::runtime_error(name_ + " did not converge in " + std::to_string(cg_.iterations()) +
                               " iterations (relative residual " + std::to_string(cg_.error()) + ")");
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
