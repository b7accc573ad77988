#include "kerf/quadrature/simplex_polynomials.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <cmath>
#include <stdexcept>

namespace kerf {

std::vector<std::array<int, 3>> monomial_exponents_3d(int degree) {
  if (degree < 0) throw std::invalid_argument("monomial_exponents_3d: negative degree");
  std::vector<std::array<int, 3>> exponents;
  for (int d = 0; d <= degree; ++d)
    for (int a = d; a >= 0; --a)
      for (int b = d - a; b >= 0; --b) exponents.push_back({a, b, d - a - b});
  return exponents;
}

std::vector<std::array<int, 2>> monomial_exponents_2d(int degree) {
  if (degree < 0) throw std::invalid_argument("monomial_exponents_2d: negative degree");
  std::vector<std::array<int, 2>> exponents;
  for (int d = 0; d <= degree; ++d)
    for (int a = d; a >= 0; --a) exponents.push_back({a, d - a});
  return exponents;
}

namespace {
// x^0 .. x^n, so that a monomial costs three look-ups.
Eigen::MatrixXd powers(const double* x, int dimension, int n) {
  Eigen::MatrixXd p(dimension, n + 1);
  for (int i = 0; i < dimension; ++i) {
    p(i, 0) = 1.0;
    for (int k = 1; k <= n; ++k) p(i, k) = p(i, k - 1) * x[i];
  }
  return p;
}
int max_exponent(const auto& exponents) {
  int n = 0;
  for (const auto& e : exponents)
    for (int k : e) n = std::max(n, k);
  return n;
}
double factorial(int n) { return std::tgamma(n + 1.0); }
} // namespace

Eigen::VectorXd evaluate_monomials_3d(const std::vector<std::array<int, 3>>& exponents, const Eigen::Vector3d& x) {
  const Eigen::MatrixXd p = powers(x.data(), 3, max_exponent(exponents));
  Eigen::VectorXd values(static_cast<Eigen::Index>(exponents.size()));
  for (std::size_t k = 0; k < exponents.size(); ++k)
    values[static_cast<Eigen::Index>(k)] = p(0, exponents[k][0]) * p(1, exponents[k][1]) * p(2, exponents[k][2]);
  return values;
}

Eigen::VectorXd evaluate_monomials_2d(const std::vector<std::array<int, 2>>& exponents, const Eigen::Vector2d& u) {
  const Eigen::MatrixXd p = powers(u.data(), 2, max_exponent(exponents));
  Eigen::VectorXd values(static_cast<Eigen::Index>(exponents.size()));
  for (std::size_t k = 0; k < exponents.size(); ++k)
    values[static_cast<Eigen::Index>(k)] = p(0, exponents[k][0]) * p(1, exponents[k][1]);
  return values;
}

double reference_tet_monomial_integral(int a, int b, int c) {
  return factorial(a) * factorial(b) * factorial(c) / factorial(a + b + c + 3);
}

double reference_triangle_monomial_integral(int a, int b) { return factorial(a) * factorial(b) / factorial(a + b + 2); }

namespace {
// C = L^-1 for the Gram matrix G = L L^T: then C G C^T = I, the rows of C are the coefficients
// of orthonormal polynomials, and C is lower triangular (Gram-Schmidt in the given order).
Eigen::MatrixXd orthonormalising_coefficients(const Eigen::MatrixXd& gram) {
  const Eigen::LLT<Eigen::MatrixXd> llt(gram);
  if (llt.info() != Eigen::Success) throw std::runtime_error("orthonormal basis: the Gram matrix is not positive definite");
  const Eigen::MatrixXd L = llt.matrixL();
  return L.triangularView<Eigen::Lower>().solve(Eigen::MatrixXd::Identity(gram.rows(), gram.cols()));
}
} // namespace

OrthonormalBasis3d orthonormal_basis_reference_tet(int degree) {
  OrthonormalBasis3d basis;
  basis.exponents = monomial_exponents_3d(degree);
  const auto M = static_cast<Eigen::Index>(basis.exponents.size());
  Eigen::MatrixXd gram(M, M);
  for (Eigen::Index i = 0; i < M; ++i)
    for (Eigen::Index j = 0; j < M; ++j) {
      const auto& a = basis.exponents[static_cast<std::size_t>(i)];
      const auto& b = basis.exponents[static_cast<std::size_t>(j)];
      gram(i, j) = reference_tet_monomial_integral(a[0] + b[0], a[1] + b[1], a[2] + b[2]);
    }
  basis.coefficients = orthonormalising_coefficients(gram);
  return basis;
}

OrthonormalBasis2d orthonormal_basis_reference_triangle(int degree) {
  OrthonormalBasis2d basis;
  basis.exponents = monomial_exponents_2d(degree);
  const auto M = static_cast<Eigen::Index>(basis.exponents.size());
  Eigen::MatrixXd gram(M, M);
  for (Eigen::Index i = 0; i < M; ++i)
    for (Eigen::Index j = 0; j < M; ++j) {
      const auto& a = basis.exponents[static_cast<std::size_t>(i)];
      const auto& b = basis.exponents[static_cast<std::size_t>(j)];
      gram(i, j) = reference_triangle_monomial_integral(a[0] + b[0], a[1] + b[1]);
    }
  basis.coefficients = orthonormalising_coefficients(gram);
  return basis;
}

} // namespace kerf
