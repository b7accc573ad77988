/// @file cylindrical_tet_integral.hpp
/// @brief The integral of r^alpha g(theta) over a tet, in cylindrical coordinates about a straight line: a reference for the rules near a crack front (chapter 5).
///
/// The near-front rules (front_quadrature.hpp, refined_subtet_rule) need an answer to be
/// measured against that does not come from sub-tets at all. In cylindrical coordinates
/// (r, theta, z) about the front line the integral is int_z I(z) dz, I(z) the integral of
/// r^alpha g(theta) over the tet's section at height z (a triangle or a quadrilateral):
/// - I(z) is a sum over the section's edges of the signed triangles (line point, edge): for an
///   edge at distance d from the line, with the position along it s = d sinh(v) from the foot of
///   the perpendicular, the ray to the edge has length d cosh(v), dtheta = dv / cosh(v), and the
///   radial integral is exact: int r^(alpha + 1) dr dtheta = d^(alpha+2) cosh(v)^(alpha+1) /
///   (alpha + 2) dv, smooth in v however close the edge passes to the line; Gauss-Legendre in v
///   on parts of width <= 1. Edges are split where they cross the cut's half-line
///   (theta = +-pi), so g is smooth on each part;
/// - I(z) is smooth between the heights where the section changes shape (the corners), where the
///   line pierces a face, and where an edge crosses the cut's half-plane, and it varies on the
///   scale delta where an edge passes a distance delta from the line (breakpoints graded
///   geometrically, z_c +- delta 2^k, towards that height z_c); between breakpoints it is
///   integrated by Gauss-Legendre after the substitution z = z0 + (z1 - z0)(3u^2 - 2u^3), which
///   turns the half-integer powers of the distance to the ends, such as (z - z0)^(3/2) where the
///   line leaves the section, into polynomials of u.
#pragma once

#include <Eigen/Core>
#include <functional>

namespace kerf {

/// int over the tet X of r^alpha g(theta) dV, with r the distance to the line through `origin`
/// along c and theta = atan2(x_b, x_a) in (-pi, pi], x_a, x_b the coordinates of x - origin
/// along a and b = c x a.
/// @param X      the tet's corners (rows)
/// @param origin a point of the line (m)
/// @param a      unit, perpendicular to c: theta = 0
/// @param c      unit, along the line
/// @param alpha  the power of r, > -2
/// @param g      the angular factor, evaluated for theta in (-pi, pi)
/// @param points Gauss points per part in v and in z
double cylindrical_tet_integral(const Eigen::Matrix<double, 4, 3>& X, const Eigen::Vector3d& origin, const Eigen::Vector3d& a,
                                const Eigen::Vector3d& c, double alpha, const std::function<double(double)>& g, int points);

} // namespace kerf
