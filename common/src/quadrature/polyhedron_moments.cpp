#include "kerf/quadrature/polyhedron_moments.hpp"

#include "kerf/fem/tet_quadrature.hpp"
#include "kerf/quadrature/simplex_polynomials.hpp"

#include <Eigen/Dense>
#include <Eigen/LU>
#include <algorithm>
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

Eigen::VectorXd polygon_monomial_moments(const std::vector<Eigen::Vector2d>& polygon, int degree) {
  if (degree < 0 || degree > 12) throw std::invalid_argument("polygon_monomial_moments: degree must be in 0..12");
  const std::vector<std::array<int, 2>> exponents = monomial_exponents_2d(degree);
  std::vector<std::array<int, 2>> shifted = exponents;
  for (auto& e : shifted) ++e[0];
  std::vector<double> points, weights;
  gauss_jacobi_01((degree + 3) / 2, 0, points, weights); // exact for the edge integrand's degree + 1
  Eigen::VectorXd moments = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(exponents.size()));
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const Eigen::Vector2d& a = polygon[k];
    const Eigen::Vector2d& b = polygon[(k + 1) % polygon.size()];
    const double dv = b.y() - a.y();
    if (dv == 0.0) continue;
    for (std::size_t q = 0; q < points.size(); ++q)
      moments += (weights[q] * dv) * evaluate_monomials_2d(shifted, a + points[q] * (b - a));
  }
  for (std::size_t k = 0; k < exponents.size(); ++k) moments[static_cast<Eigen::Index>(k)] /= exponents[k][0] + 1.0;
  return moments;
}

ReferenceMap::ReferenceMap(const Eigen::Matrix<double, 4, 3>& X) {
  origin = X.row(0).transpose();
  for (int i = 0; i < 3; ++i) jacobian.col(i) = (X.row(i + 1) - X.row(0)).transpose();
  det = jacobian.determinant();
  if (det == 0.0) throw std::invalid_argument("ReferenceMap: the tet has no volume");
  inverse = jacobian.inverse();
}

std::vector<std::vector<Eigen::Vector3d>> reference_boundary(const ReferenceMap& map, const TetPiece& piece) {
  std::vector<std::vector<Eigen::Vector3d>> boundary;
  boundary.reserve(piece.boundary.size());
  for (const PieceBoundaryPolygon& b : piece.boundary) {
    std::vector<Eigen::Vector3d> polygon;
    polygon.reserve(b.polygon.size());
    for (const Eigen::Vector3d& x : b.polygon) polygon.push_back(map.to_reference(x));
    if (map.det < 0.0) std::reverse(polygon.begin(), polygon.end());
    boundary.push_back(std::move(polygon));
  }
  return boundary;
}

} // namespace kerf
