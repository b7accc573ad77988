/// @file linear_solver.hpp
/// @brief Sparse symmetric positive definite solvers behind one small interface.
#pragma once

#include <Eigen/SparseCore>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace kerf {

/// A matrix that was meant to be symmetric positive definite is not: a negative or zero pivot
/// (CHOLMOD, LDLT), a non-positive diagonal entry (the CG preconditioners), or a CG solution x
/// with b . x = x^T A x <= 0, which no positive definite A allows. Callers that can do something
/// about it (the quasi-static solver's warped-tangent fallback) catch this type.
class NotPositiveDefinite : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// Which solver, and how hard an iterative one works.
struct SolverSettings {
  /// "cholmod" (supernodal Cholesky, the default), "ldlt" (Eigen's SimplicialLDLT, a teaching
  /// fallback), "cg-jacobi" or "cg-ichol" (conjugate gradients with a Jacobi or an incomplete
  /// Cholesky preconditioner), "cg-cholmod" (conjugate gradients preconditioned by the CHOLMOD
  /// factor of an earlier matrix, kerf::ReusedFactorisationCg).
  std::string type = "cholmod";
  double tolerance = 1e-10;  ///< CG: stop when |b - A x| <= tolerance |b|
  int max_iterations = 10000; ///< cg-jacobi, cg-ichol: give up (with an error) after this many iterations
  int refresh_iterations = 10; ///< cg-cholmod: refactorise after a solve that needs more iterations
  /// CHOLMOD's fill-reducing ordering: "nested-dissection" (the default), "metis", "amd" or
  /// "cholmod" (CHOLMOD's own choice); see kerf::CholmodSolver.
  std::string ordering = "nested-dissection";
  /// cg-jacobi on a cut body (chapters 6 and 7): "parts", Jacobi's scaling in the part basis with
  /// each independent piece its own system (dynamics/part_basis.hpp, the default), or
  /// "unknowns", in the unknowns [u; a] themselves. Other solvers and uncut bodies ignore it.
  std::string basis = "parts";
};

/// A basis for "cg-jacobi" to precondition in: x = S w, S square and invertible (the unknowns'
/// size). Jacobi then scales S^T A S by its diagonal D, which preconditions A by S D^-1 S^T.
///
/// `component` (one label per column of S, 0 .. C - 1, or empty for one) is the caller's promise
/// that S^T A S couples no two unknowns of different labels: the system is C independent ones,
/// and conjugate gradients run on each with its own step lengths (in lockstep, one product with
/// A for all), each until its own residual is small relative to its own right-hand side.
///
/// Why: chapter 6's cut bodies solve in [u; a], in which no diagonal scaling separates a node's
/// two functions when one of its parts is thin, nor a piece the cut freed from the body it was cut
/// off; in the part basis (dynamics/part_basis.hpp) both come apart, and a freed piece is a
/// component of its own, which the body's iterations never move (one CG for all would, through
/// its step lengths, by the round-off of the piece's residual times the CG polynomial there).
struct PreconditionerBasis {
  Eigen::SparseMatrix<double> S;
  std::vector<int> component;
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
  /// NotPositiveDefinite if that shows A is not positive definite. Every solver looks at its
  /// own evidence: CHOLMOD's Cholesky fails on a non-positive pivot, LDLT's pivots D are
  /// checked to be positive (Eigen's SimplicialLDLT itself only stops on an exactly zero one,
  /// and would happily factorise an indefinite matrix), CG checks that the diagonal is positive.
  /// A singular positive semidefinite matrix (a body no Dirichlet condition holds) can still
  /// factorise with pivots of round-off size: check that before, with count_free_rigid_motions.
  virtual void factorize(const Eigen::SparseMatrix<double>& A) = 0;
  /// Solves A x = b. On entry x is the initial guess of an iterative solver (ignored by direct
  /// ones). Throws std::invalid_argument if b is not finite, NotPositiveDefinite if the result
  /// proves A indefinite (CG: b . x <= 0) or is not finite, and std::runtime_error if CG does
  /// not converge.
  virtual void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) = 0;
  /// Iterations of the last solve (1 for a direct solver).
  virtual int iterations() const { return 1; }
  /// The basis an iterative solver's preconditioner works in (PreconditionerBasis). Kept until
  /// set again; a new size of the unknowns needs a new basis. "cg-jacobi" uses it; every other
  /// solver ignores it: a direct solve's answer does not depend on the basis, and the other CGs
  /// keep their own preconditioners.
  virtual void set_preconditioner_basis(const PreconditionerBasis& basis) { static_cast<void>(basis); }
  /// Numeric factorisations (or preconditioner set-ups) done so far: one per factorize() call,
  /// except for "cg-cholmod", which factorises only when its old factor stops paying.
  virtual int factorisations() const = 0;
};

/// Makes the solver named in `settings` (std::invalid_argument for an unknown name).
std::unique_ptr<LinearSolver> make_linear_solver(const SolverSettings& settings);

/// A x = b once: make the solver, analyse, factorise, solve (x starts from 0), what every
/// static solve of chapters 1, 3 and 4 does with its assembled K_ff.
Eigen::VectorXd solve_once(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& b, const SolverSettings& settings);

} // namespace kerf
