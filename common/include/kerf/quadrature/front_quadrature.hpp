/// @file front_quadrature.hpp
/// @brief A quadrature rule for a piece of a tet that the crack front passes through, exact in the radial direction for the branch integrands: sub-tets with an edge or a corner on the front, collapsed onto it (notes 5.5; Bechet et al. 2005, Park et al. 2009).
///
/// Near a front the XFEM integrands are not polynomials: the branch functions go like sqrt(r),
/// their gradients like 1/sqrt(r), the stiffness like 1/r (notes 5.5). Gauss rules on sub-tets
/// (refined_subtet_rule) converge, but slowly, since the integrand is singular on the front.
///
/// The collapsed rule. Each convex cell of the piece that touches the front along a segment
/// S = [q0, q1] (or at one point q0) is cut into tets that have S as an edge or q0 as a corner:
/// the cones from q0 over the cell's faces that do not hold q0, and, in a face that holds q1, the
/// cones from q1 over its edges (the cone decomposition of a convex polytope from a point of it,
/// applied twice). The other cells get ordinary Gauss tets. Then:
/// - a tet (q0, q1, P2, P3) with the edge on the front is mapped from the unit cube by
///   x = (1 - rho) A(s) + rho B(t), A(s) = q0 + s (q1 - q0), B(t) = P2 + t (P3 - P2), with
///   dV = 6 V rho (1 - rho) ds dt drho. For a straight front, x - foot(x) = rho (B(t) - foot(B(t))),
///   so r = rho R(t) and theta = Theta(t) exactly: the singularity sits in rho alone;
/// - a tet (q0, P1, P2, P3) with a corner on the front: x = q0 + rho (y(u, v) - q0), y on the
///   face (P1, P2, P3), dV = 6 V rho^2 drho du dv, and again r = rho R(u, v), theta = Theta(u, v);
/// - rho = sigma^2 in both (drho = 2 sigma dsigma): then sqrt(r), 1/sqrt(r) and 1/r times the
///   Jacobian are polynomials in sigma (sigma^3 R^1/2 ..., sigma^2 R^-1/2 ..., sigma R^-1 ...), so
///   Gauss-Legendre in sigma integrates every branch integrand's radial part exactly (with n
///   points: N_i N_j / r, the Tet4 stiffness's worst term, is of degree 7 in sigma, exact for
///   n >= 4; a polynomial of degree p in x for n >= p + 3), and the other directions see smooth
///   functions (the cells are split at the cut, so Theta does not jump);
/// - the front may still pass close to the rest of a sub-tet (a corner of the tet just beside
///   the front's line, or the front leaving the tet near an edge of a face). r is then small,
///   though not zero, somewhere on the opposite edge or face, and Gauss converges slowly there.
///   So each opposite edge (face) is split in halves (quarters) until every part lies at least
///   its own length from the front's line, at most 12 times: the parts shrink geometrically
///   towards the near point, and Gauss converges at a fixed rate on each. Without this grading
///   the error of 1/r on the tests' tet stalls near 1e-4 at n = 8.
/// This is the "almost polar" integration of Bechet et al. (2005) and Laborde et al. (2005),
/// in the 3D form of tets with an edge on the front (Park et al. 2009), with the square-root
/// substitution of the radius.
///
/// Limitations: a cell that several front segments touch (a kink of the front inside one tet)
/// is collapsed onto the longest; the others' singularities are integrated by Gauss only. The
/// exactness in rho holds for a straight front; on a curved one r / rho varies slowly with rho.
#pragma once

#include "kerf/cut/crack_front.hpp"
#include "kerf/cut/tet_pieces.hpp"
#include "kerf/quadrature/piece_quadrature_rule.hpp"

#include <Eigen/Core>

namespace kerf {

/// How often the collapsed rule halves a face or edge near the front's line at most, by default.
inline constexpr int default_front_grading = 12;

/// The collapsed rule of piece `piece` of tet X with n Gauss points in each direction of each
/// collapsed sub-tet (n^3 per sub-tet), and Gauss rules of degree 2n - 1 on the cells the front
/// does not touch.
/// @param X      the tet's corners (rows)
/// @param pieces split_tet_by_triangles(X, ...) (a tet the front crosses is one piece, made of
///               the cells on either side of the cut and ahead of the front)
/// @param piece  which piece
/// @param fronts the fronts (only their segments inside X matter, front_in_tet)
/// @param n      points per direction, 1 <= n <= 8
/// @param grading how often at most a face or edge near the front's line is halved towards it,
///               0 <= grading <= default_front_grading
/// @throws std::invalid_argument for n or grading out of range
PieceQuadratureRule front_collapsed_rule(const Eigen::Matrix<double, 4, 3>& X, const TetPieces& pieces, int piece,
                                         const CrackFronts& fronts, int n, int grading = default_front_grading);

/// A rule for a piece of a tet near the front that the front does not cross (a blending tet,
/// or a tet behind the front with branch nodes): the functions are smooth there, but at a
/// distance d from the front their derivatives grow like d^-1/2 - k, steep for Gauss across a
/// tet of size h > d. So each sub-tet of the piece's cells is refined (refine_tet) while it is
/// larger than its distance to the front, at most `max_depth` times, and gets the Gauss rule of
/// `degree` (a geometric grading towards the front, as for the collapsed rule's near edges).
/// @param pieces    the tet's pieces (split_tet_by_triangles(X, {}) for an uncut tet)
/// @param max_depth >= 0; 0 gives subtet_rule
PieceQuadratureRule near_front_graded_rule(const TetPieces& pieces, int piece, const CrackFronts& fronts, int degree, int max_depth);

} // namespace kerf
