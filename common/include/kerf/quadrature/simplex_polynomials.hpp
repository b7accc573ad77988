/// @file simplex_polynomials.hpp
/// @brief Monomials and orthonormal polynomial bases on the reference tetrahedron and triangle (Koschier section 5, step 1).
///
/// Moment fitting (moment_fitting.hpp) solves a small linear system whose rows are basis
/// polynomials evaluated at fixed points. With raw monomials that system is badly conditioned
/// (x^2 and x look alike on [0, 1]); Koschier makes the basis orthonormal on the reference
/// simplex by Gram-Schmidt, which "greatly improves the matrix condition number of eq. (17)".
/// We do the same by a Cholesky factor of the monomials' Gram matrix, which is Gram-Schmidt in
/// matrix form.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

namespace kerf {

/// The exponents (a, b, c) of the monomials x^a y^b z^c of total degree <= `degree`, graded
/// (all of degree 0, then 1, ...) and within a degree in decreasing a, then b:
/// 1; x, y, z; x^2, xy, xz, y^2, yz, z^2; ... There are (d + 1)(d + 2)(d + 3) / 6 of them.
std::vector<std::array<int, 3>> monomial_exponents_3d(int degree);

/// The exponents (a, b) of the monomials u^a v^b of total degree <= `degree`, ordered the same way
/// ((d + 1)(d + 2) / 2 of them).
std::vector<std::array<int, 2>> monomial_exponents_2d(int degree);

/// Every monomial of `exponents` at the point x: #exponents values.
Eigen::VectorXd evaluate_monomials_3d(const std::vector<std::array<int, 3>>& exponents, const Eigen::Vector3d& x);
Eigen::VectorXd evaluate_monomials_2d(const std::vector<std::array<int, 2>>& exponents, const Eigen::Vector2d& u);

/// int over the reference tet {x, y, z >= 0, x + y + z <= 1} of x^a y^b z^c = a! b! c! / (a + b + c + 3)!.
double reference_tet_monomial_integral(int a, int b, int c);

/// int over the reference triangle {u, v >= 0, u + v <= 1} of u^a v^b = a! b! / (a + b + 2)!.
double reference_triangle_monomial_integral(int a, int b);

/// Polynomials P_i = sum_k C(i, k) m_k (m_k the monomials of `exponents`) that are orthonormal in
/// L2 of the reference simplex: int P_i P_j = delta_ij. C = L^-1 with L L^T the monomials' Gram
/// matrix (Cholesky), i.e. Gram-Schmidt on the monomials in their graded order, so P_1 is the
/// constant sqrt(1 / |simplex|).
struct OrthonormalBasis3d {
  std::vector<std::array<int, 3>> exponents; ///< M monomials
  Eigen::MatrixXd coefficients;              ///< C, M x M, lower triangular
  /// The M basis polynomials at x.
  Eigen::VectorXd evaluate(const Eigen::Vector3d& x) const { return coefficients * evaluate_monomials_3d(exponents, x); }
};
struct OrthonormalBasis2d {
  std::vector<std::array<int, 2>> exponents;
  Eigen::MatrixXd coefficients;
  Eigen::VectorXd evaluate(const Eigen::Vector2d& u) const { return coefficients * evaluate_monomials_2d(exponents, u); }
};

/// The orthonormal basis of the polynomials of degree <= `degree` on the reference tet.
OrthonormalBasis3d orthonormal_basis_reference_tet(int degree);

/// The orthonormal basis of the polynomials of degree <= `degree` on the reference triangle.
OrthonormalBasis2d orthonormal_basis_reference_triangle(int degree);

} // namespace kerf
