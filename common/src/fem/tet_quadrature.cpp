#include "kerf/fem/tet_quadrature.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <stdexcept>

namespace kerf {

void gauss_jacobi_01(int n, int alpha, std::vector<double>& points, std::vector<double>& weights) {
  // Golub-Welsch: the nodes of the n-point Gauss rule for the weight (1 - s)^alpha on [-1, 1]
  // are the eigenvalues of the symmetric tridiagonal Jacobi matrix of the three-term recurrence
  // of the Jacobi polynomials P_k^(alpha, 0); the weights are mu_0 times the squared first
  // components of the normalised eigenvectors.
  const double a = alpha, b = 0.0;
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(n, n);
  for (int k = 0; k < n; ++k) {
    const double s = 2.0 * k + a + b;
    T(k, k) = (k == 0) ? (b - a) / (a + b + 2.0) : (b * b - a * a) / (s * (s + 2.0));
    if (k + 1 < n) {
      const double k1 = k + 1.0, s1 = 2.0 * k1 + a + b;
      const double off = std::sqrt(4.0 * k1 * (k1 + a) * (k1 + b) * (k1 + a + b) / (s1 * s1 * (s1 + 1.0) * (s1 - 1.0)));
      T(k, k + 1) = T(k + 1, k) = off;
    }
  }
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(T);
  // mu_0 = int_{-1}^{1} (1 - s)^alpha ds = 2^(alpha + 1) / (alpha + 1).
  const double mu0 = std::pow(2.0, a + 1.0) / (a + 1.0);
  points.resize(static_cast<std::size_t>(n));
  weights.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    const double v0 = eigen.eigenvectors()(0, k);
    // Map s in [-1, 1] to t = (1 + s) / 2 in [0, 1]: (1 - t)^alpha dt = 2^-(alpha + 1) (1 - s)^alpha ds.
    points[static_cast<std::size_t>(k)] = 0.5 * (1.0 + eigen.eigenvalues()[k]);
    weights[static_cast<std::size_t>(k)] = mu0 * v0 * v0 / std::pow(2.0, a + 1.0);
  }
}

TetQuadratureRule tet_quadrature_rule(int degree) {
  if (degree < 1 || degree > 15) throw std::invalid_argument("tet_quadrature_rule: degree must be in 1..15");
  TetQuadratureRule rule;
  rule.degree = degree;
  if (degree == 1) {
    rule.points = {Eigen::Vector3d::Constant(0.25)};
    rule.weights = {1.0 / 6.0};
    return rule;
  }
  if (degree == 2) {
    // Barycentric (a, b, b, b) and its permutations, a = (5 + 3 sqrt 5) / 20, b = (5 - sqrt 5) / 20.
    const double a = (5.0 + 3.0 * std::sqrt(5.0)) / 20.0, b = (5.0 - std::sqrt(5.0)) / 20.0;
    rule.points = {Eigen::Vector3d(b, b, b), Eigen::Vector3d(a, b, b), Eigen::Vector3d(b, a, b), Eigen::Vector3d(b, b, a)};
    rule.weights.assign(4, 1.0 / 24.0);
    return rule;
  }
  // Stroud's conical product: xi1 = u, xi2 = v (1 - u), xi3 = w (1 - u)(1 - v), whose Jacobian
  // is (1 - u)^2 (1 - v). A polynomial of total degree d in xi has degree <= d in each of u, v, w,
  // so Gauss-Jacobi rules with weights (1 - u)^2 and (1 - v) and Gauss-Legendre in w with
  // n = ceil((d + 1) / 2) points each are exact.
  const int n = (degree + 2) / 2;
  std::vector<double> pu, wu, pv, wv, pw, ww;
  gauss_jacobi_01(n, 2, pu, wu);
  gauss_jacobi_01(n, 1, pv, wv);
  gauss_jacobi_01(n, 0, pw, ww);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const double u = pu[i], v = pv[j], w = pw[k];
        rule.points.emplace_back(u, v * (1.0 - u), w * (1.0 - u) * (1.0 - v));
        rule.weights.push_back(wu[i] * wv[j] * ww[k]);
      }
  return rule;
}

} // namespace kerf
