// Tet quadrature: every rule integrates every polynomial up to its stated degree exactly, on the
// reference tet and on a distorted one, against the closed form
//   int_T lambda0^a lambda1^b lambda2^c lambda3^d dV = 6 V a! b! c! d! / (a + b + c + d + 3)!.
#include "kerf/fem/tet_quadrature.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

namespace {

double factorial(int n) { return std::tgamma(n + 1.0); }

// Integrates lambda^e over the tet with corners X (4x3) using the rule, through the affine map.
double integrate_barycentric_monomial(const kerf::TetQuadratureRule& rule, const Eigen::Matrix<double, 4, 3>& X,
                                      const Eigen::Vector4i& e) {
  Eigen::Matrix3d J;
  for (int c = 0; c < 3; ++c) J.col(c) = (X.row(c + 1) - X.row(0)).transpose();
  const double det_J = std::abs(J.determinant());
  double sum = 0.0;
  for (std::size_t q = 0; q < rule.points.size(); ++q) {
    const Eigen::Vector3d& xi = rule.points[q];
    // The physical point is x0 + J xi; its barycentric coordinates in the physical tet are the
    // reference ones, which is what we must recover from x itself to test the map too.
    const Eigen::Vector3d x = X.row(0).transpose() + J * xi;
    const Eigen::Vector3d xi_back = J.lu().solve(x - X.row(0).transpose());
    const Eigen::Vector4d lambda(1.0 - xi_back.sum(), xi_back[0], xi_back[1], xi_back[2]);
    double value = 1.0;
    for (int i = 0; i < 4; ++i) value *= std::pow(lambda[i], e[i]);
    sum += rule.weights[q] * det_J * value;
  }
  return sum;
}

} // namespace

TEST_CASE("tet quadrature rules are exact up to their stated degree") {
  Eigen::Matrix<double, 4, 3> reference, distorted;
  reference << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  distorted << 0.1, -0.2, 0.05, 2.0, 0.3, -0.1, 0.4, 1.5, 0.2, -0.3, 0.6, 0.9;
  for (int degree = 1; degree <= 8; ++degree) {
    const kerf::TetQuadratureRule rule = kerf::tet_quadrature_rule(degree);
    CAPTURE(degree);
    double weight_sum = 0.0;
    for (double w : rule.weights) {
      CHECK(w > 0.0); // positive weights: no cancellation, stable for any integrand
      weight_sum += w;
    }
    CHECK(weight_sum == kerf_test::relative(1.0 / 6.0, 1e-14));
    for (const auto& X : {reference, distorted}) {
      Eigen::Matrix3d J;
      for (int c = 0; c < 3; ++c) J.col(c) = (X.row(c + 1) - X.row(0)).transpose();
      const double volume = std::abs(J.determinant()) / 6.0;
      for (int a = 0; a <= degree; ++a)
        for (int b = 0; a + b <= degree; ++b)
          for (int c = 0; a + b + c <= degree; ++c)
            for (int d = 0; a + b + c + d <= degree; ++d) {
              const double exact = 6.0 * volume * factorial(a) * factorial(b) * factorial(c) * factorial(d) /
                                   factorial(a + b + c + d + 3);
              const double computed = integrate_barycentric_monomial(rule, X, {a, b, c, d});
              CAPTURE(a);
              CAPTURE(b);
              CAPTURE(c);
              CAPTURE(d);
              CHECK(computed == kerf_test::relative(exact, 1e-12));
            }
    }
  }
}

TEST_CASE("a rule is not exact one degree above its stated degree") {
  // The test above could pass for a rule that is secretly of higher degree; this one shows the
  // stated degree is the real one for the two tabulated rules (centroid, Hammer-Stroud).
  Eigen::Matrix<double, 4, 3> reference;
  reference << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  for (int degree : {1, 2}) {
    const kerf::TetQuadratureRule rule = kerf::tet_quadrature_rule(degree);
    const int n = degree + 1;
    const double exact = 6.0 / 6.0 * factorial(n) / factorial(n + 3);
    CHECK(std::abs(integrate_barycentric_monomial(rule, reference, {n, 0, 0, 0}) - exact) > 1e-6 * exact);
  }
}

TEST_CASE("the conical product rules of degrees 9 to 15 are exact on every monomial of their degree") {
  // tet_quadrature_rule accepts degrees up to 15; the test above stops at 8. Here, for 9..15:
  // - on the reference tet, every monomial x^a y^b z^c with a + b + c <= degree against
  //     int_T x^a y^b z^c dV = a! b! c! / (a + b + c + 3)!
  //   (the Dirichlet integral; the points are used as they are, no map);
  // - on a distorted tet, every barycentric monomial of total degree <= degree against
  //   6 V a! b! c! d! / (a + b + c + d + 3)!, the coordinates recovered from the physical points.
  // Tolerance 1e-12 relative: the rules have positive weights (checked), so each sum is of
  // terms of one sign and its relative round-off is ~n_points eps = 512 * 1.1e-16 ~ 6e-14
  // at worst, plus the Golub-Welsch points' own error (~1e-15 relative).
  Eigen::Matrix<double, 4, 3> distorted;
  distorted << 0.1, -0.2, 0.05, 2.0, 0.3, -0.1, 0.4, 1.5, 0.2, -0.3, 0.6, 0.9;
  Eigen::Matrix3d J;
  for (int c = 0; c < 3; ++c) J.col(c) = (distorted.row(c + 1) - distorted.row(0)).transpose();
  const double volume = std::abs(J.determinant()) / 6.0;
  for (int degree = 9; degree <= 15; ++degree) {
    CAPTURE(degree);
    const kerf::TetQuadratureRule rule = kerf::tet_quadrature_rule(degree);
    CHECK(rule.degree >= degree);
    const auto n = static_cast<std::size_t>((degree + 2) / 2); // ceil((degree + 1) / 2)
    CHECK(rule.points.size() == n * n * n);
    double weight_sum = 0.0;
    for (double w : rule.weights) {
      CHECK(w > 0.0);
      weight_sum += w;
    }
    CHECK(weight_sum == kerf_test::relative(1.0 / 6.0, 1e-14));
    double worst_reference = 0.0, worst_distorted = 0.0;
    // Reference tet, Cartesian monomials.
    for (int a = 0; a <= degree; ++a)
      for (int b = 0; a + b <= degree; ++b)
        for (int c = 0; a + b + c <= degree; ++c) {
          const double exact = factorial(a) * factorial(b) * factorial(c) / factorial(a + b + c + 3);
          double sum = 0.0;
          for (std::size_t q = 0; q < rule.points.size(); ++q) {
            const Eigen::Vector3d& xi = rule.points[q];
            sum += rule.weights[q] * std::pow(xi[0], a) * std::pow(xi[1], b) * std::pow(xi[2], c);
          }
          worst_reference = std::max(worst_reference, std::abs(sum - exact) / exact);
        }
    // Distorted tet, barycentric monomials: the physical points and their barycentric
    // coordinates, solved back from x (so the map is tested too), once per point.
    std::vector<Eigen::Vector4d> lambdas;
    for (const Eigen::Vector3d& xi : rule.points) {
      const Eigen::Vector3d x = distorted.row(0).transpose() + J * xi;
      const Eigen::Vector3d back = J.lu().solve(x - distorted.row(0).transpose());
      lambdas.emplace_back(1.0 - back.sum(), back[0], back[1], back[2]);
    }
    for (int a = 0; a <= degree; ++a)
      for (int b = 0; a + b <= degree; ++b)
        for (int c = 0; a + b + c <= degree; ++c)
          for (int d = 0; a + b + c + d <= degree; ++d) {
            const double exact = 6.0 * volume * factorial(a) * factorial(b) * factorial(c) * factorial(d) / factorial(a + b + c + d + 3);
            double sum = 0.0;
            for (std::size_t q = 0; q < lambdas.size(); ++q) {
              const Eigen::Vector4d& l = lambdas[q];
              sum += rule.weights[q] * std::abs(J.determinant()) * std::pow(l[0], a) * std::pow(l[1], b) * std::pow(l[2], c) *
                     std::pow(l[3], d);
            }
            worst_distorted = std::max(worst_distorted, std::abs(sum - exact) / exact);
          }
    MESSAGE("degree " << degree << " (" << rule.points.size() << " points): worst relative error " << worst_reference
                      << " on the reference tet, " << worst_distorted << " on the distorted tet");
    CHECK(worst_reference <= 1e-12);
    CHECK(worst_distorted <= 1e-12);
    // And the degree is real: an n-point Gauss-Jacobi product is exact to 2n - 1 and no more,
    // so some monomial of degree 2n is integrated with an error far above round-off.
    double worst_above = 0.0;
    const int above = 2 * static_cast<int>(n);
    for (int a = 0; a <= above; ++a)
      for (int b = 0; a + b <= above; ++b) {
        const int c = above - a - b;
        const double exact = factorial(a) * factorial(b) * factorial(c) / factorial(above + 3);
        double sum = 0.0;
        for (std::size_t q = 0; q < rule.points.size(); ++q) {
          const Eigen::Vector3d& xi = rule.points[q];
          sum += rule.weights[q] * std::pow(xi[0], a) * std::pow(xi[1], b) * std::pow(xi[2], c);
        }
        worst_above = std::max(worst_above, std::abs(sum - exact) / exact);
      }
    CHECK(worst_above > 1e-8);
  }
}
