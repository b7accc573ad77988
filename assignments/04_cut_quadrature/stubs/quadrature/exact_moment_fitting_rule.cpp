// Assignment 04, part 2b: the quadrature rule "exact", moment fitting on fixed points with
// exact moments (Koschier eqs. 16-17). This file stands in for
// common/src/quadrature/exact_moment_fitting_rule.cpp when assignment 04 is graded
// (./kerf.sh assignment 04); what to compute is in assignments/04_cut_quadrature/README.md.
#include "kerf/quadrature/moment_fitting.hpp" // tet_moment_fitting_system, fit_reference_weights

#include "kerf/quadrature/polyhedron_moments.hpp" // polyhedron_monomial_moments, ReferenceMap, reference_boundary

#include <stdexcept>

namespace kerf {

/// The rule "exact" for piece `piece` of a cut tet: the moments of the piece by the divergence
/// theorem (in reference coordinates), fitted on the system of `degree` (eq. 17, minimum-norm
/// weights w = A^+ b), the system's reference points mapped to physical coordinates and the
/// weights multiplied by |det J|. It integrates every polynomial of degree <= `degree` over
/// the piece to round-off.
/// @param X      the tet's 4 corners (rows)
/// @param pieces the tet's pieces (split_tet_by_triangles)
/// @param piece  which of them
/// @param degree 1..6
PieceQuadratureRule exact_moment_fitting_rule([[maybe_unused]] const Eigen::Matrix<double, 4, 3>& X,
                                              [[maybe_unused]] const TetPieces& pieces, [[maybe_unused]] int piece,
                                              [[maybe_unused]] int degree) {
  throw std::logic_error("assignment 04: implement exact_moment_fitting_rule (assignments/04_cut_quadrature/README.md)");
}

} // namespace kerf
