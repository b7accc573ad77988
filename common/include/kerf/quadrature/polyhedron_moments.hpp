/// @file polyhedron_moments.hpp
/// @brief Exact integrals of monomials over a closed polyhedron (and a polygon) from its boundary, by the divergence theorem.
///
/// The right-hand side of moment fitting (Koschier eq. 17) is the integral of each basis
/// polynomial over the piece. Koschier obtains it from fitted face and interface rules
/// (koschier_moment_fitting.hpp); here we compute it exactly, as Mirtich (1996) does for rigid
/// bodies and as Paulus et al. (section 6) propose. With eq. 18 corrected (the antiderivative in
/// one component, so that its divergence is the monomial itself and not d times it):
///
///   int_V x^a y^b z^c dV = int_dV (x^(a+1) / (a + 1)) y^b z^c n_x dS,
///
/// and the boundary integrand is a polynomial of degree a + b + c + 1, which a collapsed Gauss
/// rule on each triangle of a fan over each boundary polygon integrates exactly. So the result
/// is exact to round-off for any closed polyhedron, convex or not: a kinked or folded piece is
/// no harder than a tet.
#pragma once

#include "kerf/cut/tet_pieces.hpp"

#include <Eigen/Core>
#include <vector>

namespace kerf {

/// The integrals over a closed polyhedron of the monomials of monomial_exponents_3d(degree).
/// @param boundary closed surface: planar polygons, corners counter-clockwise seen from outside
///                 (the area vectors point outward)
/// @param degree   0 <= degree <= 12
/// @return (degree + 1)(degree + 2)(degree + 3) / 6 values, in the coordinates of the corners
Eigen::VectorXd polyhedron_monomial_moments(const std::vector<std::vector<Eigen::Vector3d>>& boundary, int degree);

/// The integrals over a polygon in the plane of the monomials of monomial_exponents_2d(degree),
/// by Green's theorem (int u^a v^b dA = closed integral of u^(a+1) / (a + 1) v^b dv) with
/// Gauss-Legendre on each edge (exact). Positive for a counter-clockwise polygon; it need not
/// be convex.
Eigen::VectorXd polygon_monomial_moments(const std::vector<Eigen::Vector2d>& polygon, int degree);

/// The affine map x = X0 + J xi of a tet onto the reference tet: corner i of X goes to reference
/// corner i ((0,0,0), (1,0,0), (0,1,0), (0,0,1)), so face f of X (opposite corner f) goes to the
/// reference face opposite corner f. J = [X1 - X0, X2 - X0, X3 - X0] (3x3).
struct ReferenceMap {
  Eigen::Vector3d origin;    ///< X0 (m)
  Eigen::Matrix3d jacobian;  ///< J (m)
  Eigen::Matrix3d inverse;   ///< J^-1 (1/m)
  double det = 0.0;          ///< det J: six times the tet's signed volume (m^3)
  explicit ReferenceMap(const Eigen::Matrix<double, 4, 3>& X);
  Eigen::Vector3d to_reference(const Eigen::Vector3d& x) const { return inverse * (x - origin); }
  Eigen::Vector3d to_physical(const Eigen::Vector3d& xi) const { return origin + jacobian * xi; }
};

/// A piece's boundary polygons in reference coordinates, reversed when det J < 0 so that they
/// still run counter-clockwise seen from outside.
std::vector<std::vector<Eigen::Vector3d>> reference_boundary(const ReferenceMap& map, const TetPiece& piece);

} // namespace kerf
