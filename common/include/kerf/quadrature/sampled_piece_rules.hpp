/// @file sampled_piece_rules.hpp
/// @brief Rules that ignore the cut's geometry and keep the points of a fixed sampling that fall inside the piece.
///
/// Both sample the characteristic function of the piece with equal weights, so their error is
/// dominated by the cells that straddle the piece's boundary: O(h) for the volume in the worst
/// case (h the spacing), smaller on average because the straddling cells' errors have both
/// signs. Away from the boundary each is a midpoint rule, O(h^2).
#pragma once

#include "kerf/quadrature/piece_quadrature_rule.hpp"

namespace kerf {

/// The piece holding x: the piece of the first convex cell (in the order of pieces.cells) whose
/// face planes all have x on their inner side or on them; -1 outside every cell. Taking the
/// first cell gives a point on a shared face to exactly one piece, so the sampled rules of all
/// pieces of a tet together use every sample once.
int piece_of_point(const TetPieces& pieces, const Eigen::Vector3d& x);

/// Paulus's oversampling (Paulus et al., section 3.6; the counts are those of their public code):
/// the reference tet cut into n^3 congruent sub-tets (the Kuhn/Freudenthal split of a lattice of n
/// segments per edge), one point at each sub-tet's centroid with the weight V / n^3; the points in
/// the piece are kept.
PieceQuadratureRule lattice_rule(const Eigen::Matrix<double, 4, 3>& X, const TetPieces& pieces, int piece, int n);

/// Kaufmann's regular sampling (Koschier Table 1's comparator): the centres of n^3 equal cells
/// of the tet's axis-aligned bounding box, each with the weight of its cell's volume; the
/// centres in the piece are kept.
PieceQuadratureRule regular_rule(const Eigen::Matrix<double, 4, 3>& X, const TetPieces& pieces, int piece, int n);

} // namespace kerf
