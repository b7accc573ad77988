/// @file tet_quadrature.hpp
/// @brief Quadrature rules on the reference tetrahedron with a stated degree of exactness.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace kerf {

/// A rule sum_q w_q f(xi_q) for the integral of f over the reference tet (volume 1/6).
/// It integrates every polynomial of total degree <= `degree` exactly (to round-off).
struct TetQuadratureRule {
  int degree = 0;                      ///< degree of exactness
  std::vector<Eigen::Vector3d> points; ///< reference coordinates xi_q
  std::vector<double> weights;         ///< w_q, summing to 1/6
};

/// A rule exact to at least `degree` (1 <= degree <= 15):
/// - degree 1: the centroid (1 point);
/// - degree 2: the symmetric 4-point rule of Hammer and Stroud (weights 1/24);
/// - degree >= 3: Stroud's conical product rule, n = ceil((degree + 1) / 2) Gauss-Jacobi
///   points in each of three collapsed directions (n^3 points, all weights positive).
TetQuadratureRule tet_quadrature_rule(int degree);

/// Gauss-Jacobi points and weights on [0, 1] for the weight (1 - t)^alpha, by the
/// Golub-Welsch eigenvalue method; exact for polynomials of degree 2n - 1 times that weight.
void gauss_jacobi_01(int n, int alpha, std::vector<double>& points, std::vector<double>& weights);

} // namespace kerf
