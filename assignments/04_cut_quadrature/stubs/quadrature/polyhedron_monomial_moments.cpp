// Assignment 04, part 2a: the exact integrals of monomials over a closed polyhedron, by the
// divergence theorem (Koschier eq. 18, corrected). This file stands in for
// common/src/quadrature/polyhedron_monomial_moments.cpp when assignment 04 is graded
// (./kerf.sh assignment 04); what to compute is in assignments/04_cut_quadrature/README.md.
#include "kerf/quadrature/polyhedron_moments.hpp"

#include "kerf/fem/tet_quadrature.hpp"             // gauss_jacobi_01: Gauss-Jacobi points on [0, 1], for a collapsed triangle rule
#include "kerf/quadrature/simplex_polynomials.hpp" // monomial_exponents_3d, evaluate_monomials_3d

#include <stdexcept>

namespace kerf {

/// The integrals over a closed polyhedron of the monomials of monomial_exponents_3d(degree),
/// in that order:
///
///   int_V x^a y^b z^c dV = int_dV (x^(a+1) / (a + 1)) y^b z^c n_x dS,
///
/// integrated exactly over each triangle of a fan over each boundary polygon.
/// @param boundary closed surface: planar polygons, corners counter-clockwise seen from outside
///                 (the area vectors point outward)
/// @param degree   0 <= degree <= 12, else std::invalid_argument
/// @return (degree + 1)(degree + 2)(degree + 3) / 6 values, in the coordinates of the corners
Eigen::VectorXd polyhedron_monomial_moments([[maybe_unused]] const std::vector<std::vector<Eigen::Vector3d>>& boundary,
                                            [[maybe_unused]] int degree) {
  throw std::logic_error("assignment 04: implement polyhedron_monomial_moments (assignments/04_cut_quadrature/README.md)");
}

} // namespace kerf
