/// @file front_quadrature.hpp
/// @brief A quadrature rule for a piece of a tet that the crack front passes through, exact in the radial direction for the branch integrands: sub-tets with an edge or a corner on the front, collapsed onto it (Bechet et al. 2005, Park et al. 2009), graded by an error estimate within a budget.
///
/// Near a front the XFEM integrands are not polynomials: the branch functions go like sqrt(r),
/// their gradients like 1/sqrt(r), the stiffness like 1/r. Gauss rules on sub-tets
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
///   So the rule is graded, adaptively: the part whose estimated error is largest is improved,
///   a collapsed sub-tet by splitting its opposite face in four (its edge in two), a Gauss
///   sub-tet of a cell the front does not touch by a point more per direction or, at n points
///   and nearer the front than its size, by refine_tet, until the piece's estimated error is
///   below front_rule_tolerance(n) of V / h. The estimate is the classic one of adaptive
///   quadrature, a part's rule against the same rule on its children, for the stiffness's worst
///   integrand (1/r with the angular content of the branch functions' products). Where the line
///   passes close to a face the parts shrink geometrically towards it; where it does not, nothing
///   is split. On the tests' tet the error of sin(3 theta / 2)^2 / r with n = 4 is 3.9e-2
///   ungraded, 1.3e-8 graded (12 288 points; the fixed grading this rule replaces, every part
///   halved until as far from the line as it is large: 5.9e-7 with 21 824).
///
/// The cost is bounded, not only the error: a piece gets at most front_rule_max_points(n)
/// (192 collapsed sub-tets of n^3 points). A front of many short segments through a tet that a
/// sheet of many small triangles cuts crosses dozens of small cells, and the fixed grading, 12
/// halvings near each of their faces, gave one tet 4.9 million points and chapter 5's program a
/// std::bad_alloc. Where the budget stops the grading, the piece keeps the estimated error it has
/// reached: on tests/chapter_05/test_many_segment_front.cpp's sheet a median of 1.5e-3 of V / h,
/// mostly Gauss cells that touch the front within the clipping's tolerance only; against an
/// independent graded reference the integral of 1/r over such tets is as close as the fixed
/// grading's (5e-6 to 7e-5 of it, the fixed rule's 9e-6 to 8e-5, the reference good to 1e-5).
/// Collapsed sub-tets with an edge on the front take n / 2 points along it, where the integrand
/// is the element's polynomial (exact for N_i N_j of a Tet4 with n = 4, of a Tet10 with 6).
///
/// Limitations: a cell that several front segments touch (a kink of the front inside one tet)
/// is collapsed onto the longest; the others' singularities are integrated by Gauss only. The
/// exactness in rho holds for a straight front; on a curved one r / rho varies slowly with rho.
#pragma once

#include "kerf/cut/crack_front.hpp"
#include "kerf/cut/tet_pieces.hpp"
#include "kerf/quadrature/piece_quadrature_rule.hpp"

#include <Eigen/Core>
#include <cmath>
#include <cstddef>

namespace kerf {

/// How often the grading may split one part (a collapsed sub-tet's face or edge, a Gauss
/// sub-tet) at most, by default.
inline constexpr int default_front_grading = 12;

/// The grading's goal with n points per direction: the piece's estimated error for 1/r at most
/// this fraction of V / h (V the tet's volume, h its longest edge; int_tet 1/r >= V / h when the
/// front crosses the tet): rho^(-2(n + 1)), rho = 3 + sqrt(8), what n + 1 Gauss points leave on
/// a part as far from a singularity as it is large (2.6e-8 for n = 4, 2.2e-11 for 6, 1.9e-14 for
/// 8). The rule of a fixed grading before it stopped each part there with n points; the sum over
/// the parts, and int 1/r being several V / h, take the factor rho^2 = 34 of margin.
inline double front_rule_tolerance(int n) { return std::pow(3.0 + std::sqrt(8.0), -2.0 * (n + 1)); }

/// The most points the grading gives one piece with n points per direction (it stops there, at
/// the estimated error it has reached): 192 collapsed sub-tets of n^3, 12 288 with n = 4. A piece
/// starts with its unsplit cones and its Gauss cells' fewest points, which may be more.
inline std::size_t front_rule_max_points(int n) { return 192 * static_cast<std::size_t>(n * n * n); }

/// The blending rules' goal as chapter 5's programs set it (scene_crack_tip.cpp), a fraction of
/// V / h: looser than the strict default of near_front_graded_rule, and below what the rule of a
/// fixed grading left in those tets (Gauss of degree 6 on sub-tets refined once towards the
/// front, the programs' rule before: up to 1e-4 in uncut tets and 6e-3 in tets a sheet of small
/// triangles cuts, on a sample of 37 blending tets of a 6144-tet box cut by a wavy sheet of 840
/// triangles, against a graded reference).
inline constexpr double default_blending_tolerance = 1e-5;

/// The collapsed rule of piece `piece` of tet X with n Gauss points in the radial and angular
/// directions of each collapsed sub-tet (n^3 per sub-tet with a corner on the front, n^2 (n / 2)
/// with an edge on it), and Gauss on the fans of the cells the front does not touch, from n / 2
/// points per direction (exact for degree n - 3, like the collapsed sub-tets) up to n; graded
/// adaptively (the file comment).
/// @param X      the tet's corners (rows)
/// @param pieces split_tet_by_triangles(X, ...) (a tet the front crosses is one piece, made of
///               the cells on either side of the cut and ahead of the front)
/// @param piece  which piece
/// @param fronts the fronts (only their segments inside X matter, front_in_tet)
/// @param n      points per direction, 1 <= n <= 8
/// @param grading how often at most one part may be split, 0 <= grading <= default_front_grading
///               (0: no grading)
/// @throws std::invalid_argument for n or grading out of range
PieceQuadratureRule front_collapsed_rule(const Eigen::Matrix<double, 4, 3>& X, const TetPieces& pieces, int piece,
                                         const CrackFronts& fronts, int n, int grading = default_front_grading);

/// A rule for a piece of a tet near the front that the front does not cross (a blending tet,
/// or a tet behind the front with branch nodes): the functions are smooth there, but at a
/// distance d from the front their derivatives grow like d^-1/2 - k, steep for Gauss across a
/// tet of size h > d. The sub-tets of the piece's cells start with the fewest Gauss points per
/// direction that integrate the element's polynomials exactly; the one whose estimated error
/// for 1/r is largest (its rule against the same rule on its 8 children) gets a point more per
/// direction, up to the rule of `degree`, and then, if it is larger than its distance to the
/// front, is refined (refine_tet, at most `max_depth` times), until the piece's estimated error
/// is below `tolerance` of V / h. Never more points than the Gauss rule of `degree` on every
/// sub-tet refined towards the front `max_depth` times (the rule of a fixed grading); far fewer
/// on a piece made of many small cells (a tet a sheet of small triangles cuts), whose small
/// sub-tets need few points each.
/// @param pieces    the tet's pieces (split_tet_by_triangles(X, {}) for an uncut tet)
/// @param degree    the Gauss degree near the front (1 or 2: that rule on every sub-tet)
/// @param max_depth >= 0
/// @param tolerance the goal, a fraction of V / h (V the tet's volume, h its longest edge); 0:
///                  front_rule_tolerance((degree + 2) / 2), what `degree` leaves on a sub-tet
///                  one size away from the front, with the margin of the collapsed rule's goal
/// @param polynomial_degree the degree every sub-tet integrates exactly: N_a N_b, 2 on a Tet4
///                  (the default's 4 serves a Tet10 too)
/// @throws std::invalid_argument for max_depth, tolerance or polynomial_degree below 0
PieceQuadratureRule near_front_graded_rule(const TetPieces& pieces, int piece, const CrackFronts& fronts, int degree, int max_depth,
                                           double tolerance = 0.0, int polynomial_degree = 4);

} // namespace kerf
