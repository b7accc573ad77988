/// @file gauss_piece_rules.hpp
/// @brief Two rules built from Gauss rules on tets: the uncut tet's rule scaled by the volume ratio, and Gauss on sub-tetrahedra.
#pragma once

#include "kerf/quadrature/piece_quadrature_rule.hpp"

namespace kerf {

/// The whole tet's Gauss rule of `degree` (tet_quadrature_rule) with every weight multiplied by
/// V_piece / V (Schoch eqs. 54-63). Exact for a constant integrand only: the Tet4 stiffness
/// B^T C B, and with it corotated Tet4. It does not integrate the Tet4 consistent mass
/// (degree 2) nor Tet10 stiffness: the points do not see where the piece is.
PieceQuadratureRule volume_ratio_rule(const Eigen::Matrix<double, 4, 3>& X, const TetPieces& pieces, int piece, int degree);

/// The Gauss rule of `degree` on every tet of the fan of every convex cell of the piece
/// (convex_cell_tetrahedra; Schoch section 5.2, Paulus's sub-tetrahedra). Exact for
/// polynomials of `degree`, for any piece, since the cells partition it; the points lie inside.
/// It costs (number of sub-tets) x (points of the Gauss rule).
PieceQuadratureRule subtet_rule(const TetPieces& pieces, int piece, int degree);

/// Appends the Gauss rule of `degree` on every tet of the cell's fan (convex_cell_tetrahedra) to
/// `rule`: subtet_rule's work for one convex cell, for rules that treat some cells otherwise.
void append_cell_gauss_rule(const ConvexCell& cell, int degree, PieceQuadratureRule& rule);

/// The 8 children of the tet T (rows: corners) by its edges' midpoints, Bey's regular
/// refinement: 4 at the corners, 4 from the inner octahedron split along a diagonal, each of
/// volume V / 8 and positively oriented if T is.
std::vector<Eigen::Matrix<double, 4, 3>> refine_tet(const Eigen::Matrix<double, 4, 3>& T);

/// subtet_rule with every sub-tet refined `refinements` times first, each time into 8 tets by its
/// edges' midpoints (4 at the corners, 4 from the inner octahedron split along a diagonal): for
/// integrands that are not polynomials, such as the branch functions near a crack front
/// (chapter 5), whose error falls with the size of the sub-tets rather than with the degree.
/// It costs 8^refinements times subtet_rule's points.
/// @param refinements >= 0 (0 is subtet_rule)
PieceQuadratureRule refined_subtet_rule(const TetPieces& pieces, int piece, int degree, int refinements);

} // namespace kerf
