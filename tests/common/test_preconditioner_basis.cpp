// cg-jacobi in another basis (solve/linear_solver.hpp, PreconditionerBasis): Jacobi's scaling of
// S^T A S, the answer of A x = b all the same (against a dense Cholesky), and independent
// components, each solved to the tolerance relative to its own right-hand side.
#include "kerf/solve/linear_solver.hpp"

#include <Eigen/Dense>
#include <doctest/doctest.h>
#include <cmath>
#include <random>
#include <vector>

namespace {

// A random symmetric positive definite matrix of two diagonal blocks [0, split) and [split, n),
// each a random graph of couplings made diagonally dominant; both triangles stored.
Eigen::SparseMatrix<double> two_block_spd(int n, int split, std::mt19937& rng) {
  std::uniform_real_distribution<double> value(-1.0, 1.0), chance(0.0, 1.0);
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < j; ++i)
      if ((i < split) == (j < split) && chance(rng) < 0.2) dense(i, j) = dense(j, i) = value(rng);
  for (int i = 0; i < n; ++i) dense(i, i) = dense.row(i).cwiseAbs().sum() + 0.01 + chance(rng);
  Eigen::SparseMatrix<double> A = dense.sparseView();
  A.makeCompressed();
  return A;
}

// A unit lower triangular basis that mixes unknowns of the same block only (as the part basis
// mixes a node's u_i into its enrichments a_k = w_k - w_i).
Eigen::SparseMatrix<double> mixing_basis(int n, int split, std::mt19937& rng) {
  std::uniform_real_distribution<double> value(-1.0, 1.0), chance(0.0, 1.0);
  std::vector<Eigen::Triplet<double>> entries;
  for (int j = 0; j < n; ++j) {
    entries.emplace_back(j, j, 1.0);
    for (int i = j + 1; i < n; ++i)
      if ((i < split) == (j < split) && chance(rng) < 0.1) entries.emplace_back(i, j, value(rng));
  }
  Eigen::SparseMatrix<double> S(n, n);
  S.setFromTriplets(entries.begin(), entries.end());
  return S;
}

Eigen::VectorXd solve_with(kerf::LinearSolver& solver, const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& b) {
  solver.analyze_pattern(A);
  solver.factorize(A);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size());
  solver.solve(b, x);
  return x;
}

} // namespace

TEST_CASE("cg-jacobi preconditioned in a basis solves A x = b: the same x as a dense Cholesky") {
  std::mt19937 rng(11);
  const int n = 90, split = 60;
  const Eigen::SparseMatrix<double> A = two_block_spd(n, split, rng);
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = std::sin(1.0 + i);
  const Eigen::VectorXd exact = Eigen::MatrixXd(A).llt().solve(b);
  const auto solver = kerf::make_linear_solver({"cg-jacobi", 1e-12, 1000});
  solver->set_preconditioner_basis({mixing_basis(n, split, rng), {}});
  const Eigen::VectorXd x = solve_with(*solver, A, b);
  // A diagonally dominant matrix has kappa below ~1e3 here: residual 1e-12 gives an error
  // below ~1e-9 relative.
  CHECK((x - exact).norm() < 1e-9 * exact.norm());
}

TEST_CASE("cg-jacobi's components are solved each to the tolerance of its own right-hand side") {
  // Two independent blocks, the second's right-hand side 1e-8 of the first's: one CG for both
  // stops when the whole residual is 1e-6 of |b|, which leaves the second block's solution wrong
  // by about 100 % of itself; with the blocks as two components each meets 1e-6 of its own.
  std::mt19937 rng(12);
  const int n = 90, split = 60;
  const Eigen::SparseMatrix<double> A = two_block_spd(n, split, rng);
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = (i < split ? 1.0 : 1e-8) * std::cos(0.3 + i);
  const Eigen::VectorXd exact = Eigen::MatrixXd(A).llt().solve(b);
  const auto second = [&](const Eigen::VectorXd& v) { return v.tail(n - split); };
  std::vector<int> component(static_cast<std::size_t>(n), 0);
  for (int i = split; i < n; ++i) component[static_cast<std::size_t>(i)] = 1;
  const Eigen::SparseMatrix<double> S = mixing_basis(n, split, rng);

  const auto together = kerf::make_linear_solver({"cg-jacobi", 1e-6, 1000});
  together->set_preconditioner_basis({S, {}});
  const double error_together = (second(solve_with(*together, A, b)) - second(exact)).norm() / second(exact).norm();
  const auto apart = kerf::make_linear_solver({"cg-jacobi", 1e-6, 1000});
  apart->set_preconditioner_basis({S, component});
  const double error_apart = (second(solve_with(*apart, A, b)) - second(exact)).norm() / second(exact).norm();
  MESSAGE("the small block's relative error: one CG " << error_together << ", two components " << error_apart);
  // Residual 1e-6 of its own right-hand side, kappa below ~1e3: an error below 1e-3.
  CHECK(error_apart < 1e-3);
  CHECK(error_together > 1e-2);
}

TEST_CASE("cg-jacobi refuses a basis that does not fit") {
  const auto solver = kerf::make_linear_solver({"cg-jacobi", 1e-8, 100});
  CHECK_THROWS_AS(solver->set_preconditioner_basis({Eigen::SparseMatrix<double>(3, 4), {}}), std::invalid_argument);
  Eigen::SparseMatrix<double> identity(3, 3);
  identity.setIdentity();
  CHECK_THROWS_AS(solver->set_preconditioner_basis({identity, {0, 1}}), std::invalid_argument);
  CHECK_THROWS_AS(solver->set_preconditioner_basis({identity, {0, -1, 0}}), std::invalid_argument);
  solver->set_preconditioner_basis({identity, {}});
  Eigen::SparseMatrix<double> A(6, 6);
  A.setIdentity();
  solver->analyze_pattern(A);
  CHECK_THROWS_AS(solver->factorize(A), std::invalid_argument);
  // Direct solvers take a basis and ignore it.
  const auto direct = kerf::make_linear_solver({"cholmod"});
  direct->set_preconditioner_basis({identity, {}});
  const Eigen::VectorXd x = solve_with(*direct, A, Eigen::VectorXd::Ones(6));
  CHECK((x - Eigen::VectorXd::Ones(6)).norm() < 1e-14);
}

TEST_CASE("cg-jacobi in a basis, warm started: the same x as a dense Cholesky; an indefinite matrix is refused") {
  std::mt19937 rng(5);
  const int n = 60, split = 40;
  const Eigen::SparseMatrix<double> A = two_block_spd(n, split, rng);
  Eigen::VectorXd b(n), start(n);
  for (int i = 0; i < n; ++i) {
    b[i] = std::cos(0.3 * i);
    start[i] = 0.1 * std::sin(2.0 * i);
  }
  const Eigen::VectorXd exact = Eigen::MatrixXd(A).llt().solve(b);
  const auto solver = kerf::make_linear_solver({"cg-jacobi", 1e-12, 1000});
  solver->set_preconditioner_basis({mixing_basis(n, split, rng), std::vector<int>(n, 0)});
  solver->analyze_pattern(A);
  solver->factorize(A);
  Eigen::VectorXd x = start; // a guess that is not the answer: the correction is added to it
  solver->solve(b, x);
  CHECK((x - exact).norm() < 1e-9 * exact.norm());

  // [[1, 2], [2, 1]] has eigenvalues 3 and -1 and a positive diagonal, which Jacobi needs. With
  // b = (1, -1), the eigenvector of -1, CG's first step meets p^T A p = -2 < 0 and lands on
  // x = -b, where A x = b holds and x^T A x = -2: the solve must say the matrix is not positive
  // definite, not hand back x. The same in the unknowns (no basis) and in a basis that mixes the
  // two unknowns (S = [[1, 0], [0.5, 1]]), from zero and from a warm start.
  Eigen::SparseMatrix<double> indefinite(2, 2);
  indefinite.insert(0, 0) = 1.0;
  indefinite.insert(0, 1) = 2.0;
  indefinite.insert(1, 0) = 2.0;
  indefinite.insert(1, 1) = 1.0;
  indefinite.makeCompressed();
  Eigen::SparseMatrix<double> mixing(2, 2);
  mixing.insert(0, 0) = 1.0;
  mixing.insert(1, 0) = 0.5;
  mixing.insert(1, 1) = 1.0;
  mixing.makeCompressed();
  for (const bool with_basis : {false, true})
    for (const double warm : {0.0, 0.01}) {
      CAPTURE(with_basis);
      CAPTURE(warm);
      const auto cg = kerf::make_linear_solver({"cg-jacobi", 1e-10, 100});
      if (with_basis) cg->set_preconditioner_basis({mixing, {}});
      cg->analyze_pattern(indefinite);
      cg->factorize(indefinite);
      Eigen::VectorXd y = Eigen::VectorXd::Constant(2, warm);
      CHECK_THROWS_AS(cg->solve(Eigen::Vector2d(1.0, -1.0), y), kerf::NotPositiveDefinite);
    }
}
