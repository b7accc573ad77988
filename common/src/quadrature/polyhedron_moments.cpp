#include "kerf/quadrature/polyhedron_moments.hpp"

#include "kerf/fem/tet_quadrature.hpp"
#include "kerf/quadrature/simplex_polynomials.hpp"

#include <Eigen/Dense>
#include <Eigen/LU>
#include <algorithm>
#include <stdexcept>

namespace kerf {

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
