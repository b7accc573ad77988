// The 3x3 block storage that cg-jacobi multiplies by (solve/symmetric_block_matrix.hpp), checked
// against Eigen's own product with the upper triangle, selfadjointView<Upper>, on random
// symmetric matrices: sizes that are and are not multiples of 3, blocks with some of their
// entries stored, both triangles stored or only the upper one; and cg-jacobi, which now uses it,
// against Eigen's ConjugateGradient with the Jacobi preconditioner it replaced: the same
// iterations and the same solution to round-off.
#include "kerf/solve/linear_solver.hpp"
#include "kerf/solve/symmetric_block_matrix.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <doctest/doctest.h>
#include <random>
#include <vector>

namespace {

// A random sparse symmetric positive definite matrix: a random graph of couplings of random
// sign and size, made diagonally dominant. With `both_triangles` false only its upper triangle
// is stored (what selfadjointView<Upper> and the block matrix read).
Eigen::SparseMatrix<double> random_spd(int n, double density, bool both_triangles, std::mt19937& rng) {
  std::uniform_real_distribution<double> value(-1.0, 1.0), chance(0.0, 1.0);
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::VectorXd row_sum = Eigen::VectorXd::Zero(n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < j; ++i) {
      if (chance(rng) > density) continue;
      const double a = value(rng);
      entries.emplace_back(i, j, a);
      if (both_triangles) entries.emplace_back(j, i, a);
      row_sum[i] += std::abs(a);
      row_sum[j] += std::abs(a);
    }
  for (int i = 0; i < n; ++i) entries.emplace_back(i, i, 1.0 + row_sum[i] + chance(rng));
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  A.makeCompressed();
  return A;
}

// A banded one: couplings only between unknowns at most 3 apart, a long chain whose condition
// number grows as n^2, so that CG needs many iterations; scaled as D A D with D spread over two
// orders of magnitude, which the Jacobi preconditioner undoes.
Eigen::SparseMatrix<double> banded_spd(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> value(-1.0, 1.0), scale(0.1, 10.0);
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < std::min(n, i + 4); ++j) dense(i, j) = dense(j, i) = value(rng);
  for (int i = 0; i < n; ++i) dense(i, i) = dense.row(i).cwiseAbs().sum() + 1e-3;
  Eigen::VectorXd D(n);
  for (int i = 0; i < n; ++i) D[i] = scale(rng);
  Eigen::SparseMatrix<double> A = (D.asDiagonal() * dense * D.asDiagonal()).sparseView();
  A.makeCompressed();
  return A;
}

} // namespace

TEST_CASE("SymmetricBlockMatrix multiplies as Eigen's selfadjointView<Upper> does") {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (const int n : {1, 2, 3, 4, 5, 30, 31, 32, 300}) {
    for (const bool both_triangles : {true, false}) {
      CAPTURE(n);
      CAPTURE(both_triangles);
      const Eigen::SparseMatrix<double> A = random_spd(n, 0.1, both_triangles, rng);
      kerf::SymmetricBlockMatrix B;
      B.analyze_pattern(A);
      B.set_values(A);
      CHECK(B.size() == n);
      CHECK(B.padded_size() == 3 * ((n + 2) / 3));
      CHECK(B.has_pattern_of(A));
      Eigen::VectorXd x = Eigen::VectorXd::Zero(B.padded_size());
      for (int i = 0; i < n; ++i) x[i] = normal(rng);
      // Garbage in the padding must not leak into the product.
      for (Eigen::Index i = n; i < B.padded_size(); ++i) x[i] = 1e30;
      Eigen::VectorXd y;
      B.multiply(x, y);
      const Eigen::VectorXd expected = A.selfadjointView<Eigen::Upper>() * x.head(n);
      // The same sums in another order: round-off of a few ulps of the largest term.
      CHECK((y.head(n) - expected).norm() <= 1e-14 * expected.norm());
      CHECK(y.tail(B.padded_size() - n).isZero(0.0));
      CHECK((B.diagonal().head(n) - A.diagonal()).norm() == 0.0);
      // Entries below the diagonal are ignored: perturbing them changes nothing.
      if (both_triangles && n > 1) {
        Eigen::SparseMatrix<double> changed = A;
        for (int j = 0; j < n; ++j)
          for (Eigen::SparseMatrix<double>::InnerIterator it(changed, j); it; ++it)
            if (it.row() > j) it.valueRef() += 5.0;
        B.set_values(changed);
        Eigen::VectorXd y_changed;
        B.multiply(x, y_changed);
        CHECK((y_changed - y).norm() == 0.0);
      }
    }
  }
}

TEST_CASE("SymmetricBlockMatrix recognises a matrix of another pattern") {
  std::mt19937 rng(11);
  const Eigen::SparseMatrix<double> A = random_spd(30, 0.1, true, rng);
  kerf::SymmetricBlockMatrix B;
  B.analyze_pattern(A);
  const Eigen::SparseMatrix<double> other = random_spd(30, 0.1, true, rng);
  CHECK_FALSE(B.has_pattern_of(other));
  CHECK_FALSE(B.has_pattern_of(random_spd(33, 0.1, true, rng)));
  Eigen::SparseMatrix<double> scaled = 2.0 * A;
  scaled.makeCompressed();
  CHECK(B.has_pattern_of(scaled));
}

TEST_CASE("cg-jacobi iterates as Eigen's Jacobi-preconditioned ConjugateGradient") {
  std::mt19937 rng(3);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (const int n : {31, 300}) {
    CAPTURE(n);
    const Eigen::SparseMatrix<double> A = banded_spd(n, rng);
    Eigen::VectorXd b(n);
    for (int i = 0; i < n; ++i) b[i] = normal(rng);
    const auto solver = kerf::make_linear_solver({"cg-jacobi", 1e-10, 1000});
    solver->analyze_pattern(A);
    solver->factorize(A);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
    solver->solve(b, x);

    Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Upper, Eigen::DiagonalPreconditioner<double>> eigen_cg;
    eigen_cg.setTolerance(1e-10);
    eigen_cg.setMaxIterations(1000);
    eigen_cg.compute(A);
    const Eigen::VectorXd x_eigen = eigen_cg.solve(b);
    CHECK(solver->iterations() == eigen_cg.iterations());
    CHECK(solver->iterations() > 10);
    // Both stop at |b - A x| < 1e-10 |b|; the same iterates up to round-off in the products.
    CHECK((A * x - b).norm() < 1e-10 * b.norm());
    CHECK((x - x_eigen).norm() < 1e-12 * x_eigen.norm());
    // From a guess that already solves the system: no iteration.
    solver->solve(b, x);
    CHECK(solver->iterations() == 0);
  }
}

TEST_CASE("cg-jacobi takes a new pattern even when analyze_pattern is skipped") {
  std::mt19937 rng(5);
  const auto solver = kerf::make_linear_solver({"cg-jacobi", 1e-12, 1000});
  const Eigen::SparseMatrix<double> A = random_spd(20, 0.2, true, rng);
  const Eigen::SparseMatrix<double> B = random_spd(23, 0.2, true, rng);
  solver->analyze_pattern(A);
  solver->factorize(B);
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(23);
  Eigen::VectorXd x;
  solver->solve(b, x);
  CHECK((B * x - b).norm() < 1e-12 * b.norm());
  // A right-hand side of the wrong size is an error, not a read past the end.
  CHECK_THROWS_AS(solver->solve(Eigen::VectorXd::Ones(20), x), std::invalid_argument);
}
