// polyhedron_monomial_moments (polyhedron_moments.hpp): the exact moments of a closed polyhedron
// by the divergence theorem, in a file of its own, so that chapter 4's assignment can replace it
// (assignments/04_cut_quadrature/).
#include "kerf/quadrature/polyhedron_moments.hpp"

#include "kerf/fem/tet_quadrature.hpp"
#include "kerf/quadrature/simplex_polynomials.hpp"

#include <Eigen/Dense>
#include <stdexcept>

namespace kerf {

namespace {

// The collapsed (Duffy) Gauss rule on the reference triangle: u with weight (1 - u) by
// Gauss-Jacobi, v = t (1 - u) with t Gauss-Legendre; n points each way is exact for degree
// 2n - 1. Weights sum to 1/2.
struct TriangleRule {
  std::vector<Eigen::Vector2d> points;
  std::vector<double> weights;
};
TriangleRule collapsed_triangle_rule(int degree) {
  const int n = (degree + 2) / 2;
  std::vector<double> pu, wu, pt, wt;
  gauss_jacobi_01(n, 1, pu, wu);
  gauss_jacobi_01(n, 0, pt, wt);
  TriangleRule rule;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      rule.points.emplace_back(pu[i], pt[j] * (1.0 - pu[i]));
      rule.weights.push_back(wu[i] * wt[j]);
    }
  return rule;
}

} // namespace

Eigen::VectorXd polyhedron_monomial_moments(const std::vector<std::vector<Eigen::Vector3d>>& boundary, int degree) {
  if (degree < 0 || degree > 12) throw std::invalid_argument("polyhedron_monomial_moments: degree must be in 0..12");
  const std::vector<std::array<int, 3>> exponents = monomial_exponents_3d(degree);
  // The flux x^(a+1) / (a+1) y^b z^c has degree <= degree + 1.
  const TriangleRule rule = collapsed_triangle_rule(degree + 1);
  const std::vector<std::array<int, 3>> shifted = [&] {
    std::vector<std::array<int, 3>> s = exponents;
    for (auto& e : s) ++e[0];
    return s;
  }();
  Eigen::VectorXd scale(static_cast<Eigen::Index>(exponents.size()));
  for (std::size_t k = 0; k < exponents.size(); ++k) scale[static_cast<Eigen::Index>(k)] = 1.0 / (exponents[k][0] + 1.0);
  Eigen::VectorXd moments = Eigen::VectorXd::Zero(scale.size());
  for (const std::vector<Eigen::Vector3d>& polygon : boundary) {
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {
      const Eigen::Vector3d& p0 = polygon[0];
      const Eigen::Vector3d e1 = polygon[k] - p0, e2 = polygon[k + 1] - p0;
      // int_tri g n_x dS = 2 A_x int_ref g, with A = e1 x e2 / 2 the outward area vector.
      const double twice_area_x = e1.cross(e2).x();
      if (twice_area_x == 0.0) continue;
      Eigen::VectorXd sum = Eigen::VectorXd::Zero(scale.size());
      for (std::size_t q = 0; q < rule.points.size(); ++q) {
        const Eigen::Vector3d x = p0 + rule.points[q].x() * e1 + rule.points[q].y() * e2;
        sum += rule.weights[q] * evaluate_monomials_3d(shifted, x);
      }
      moments += twice_area_x * sum;
    }
  }
  return moments.cwiseProduct(scale);
}

} // namespace kerf
