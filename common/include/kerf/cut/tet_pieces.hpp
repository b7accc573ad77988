/// @file tet_pieces.hpp
/// @brief A tet cut by the triangles of cut surfaces into its pieces, as closed polyhedra made of convex cells (Koschier section 4).
#pragma once

#include "kerf/cut/convex_cell.hpp"

#include <Eigen/Core>
#include <array>
#include <vector>

namespace kerf {

/// One triangle of a cut surface, as the clipping of a tet sees it.
struct CutTriangle {
  std::array<Eigen::Vector3d, 3> corners; ///< in the surface's order: (x1 - x0) x (x2 - x0) points above (H = +1)
  int surface = 0;                        ///< which cut surface of the scene (0-based)
  int triangle = 0;                       ///< which triangle of that surface (0-based)
};

/// How a tet lies against the cut surfaces (Koschier section 4.3, with the cases a cut can
/// touch without separating anything).
enum class SurfaceCutState : signed char {
  uncut,          ///< no cut triangle covers any area inside the tet or on its faces
  touched,        ///< the cut covers part of the tet's faces only (a cut along a face): one piece
  partially_cut,  ///< the cut covers area inside the tet but leaves it in one piece (its front is inside)
  completely_cut, ///< the cut splits the tet into two or more pieces
};

/// The enumerator's name, for reports.
const char* to_string(SurfaceCutState state);

/// A polygon of a piece's boundary: part of a tet face or a side of the cut.
struct PieceBoundaryPolygon {
  std::vector<Eigen::Vector3d> polygon; ///< convex, corners counter-clockwise seen from outside the piece
  FaceOrigin origin;                    ///< tet_face (index = the face) or cut_plane (index = the CutTriangle's position)
  bool on_cut = false;                  ///< covered by a cut triangle (origin may also be a tet face: a cut along a face)
  /// For a polygon on the cut: +1 if the piece lies above the covering triangle (on the side
  /// its normal points to, H = +1), -1 below; 0 for a polygon not on the cut.
  int cut_side = 0;
};

/// One piece: a connected part of the tet minus the cut surfaces.
struct TetPiece {
  std::vector<int> cells;                     ///< the convex cells it is made of (indices into TetPieces::cells)
  double volume = 0.0;                        ///< sum of the cells' volumes (m^3)
  std::vector<PieceBoundaryPolygon> boundary; ///< its closed boundary: the faces of its cells on the tet's
                                              ///< surface or on the cut, outward; sum of area vectors = 0
};

/// A tet cut into pieces.
///
/// The cells partition the tet; a piece is a maximal set of cells connected through faces the
/// cut does not cover. So the pieces are exactly the connected components of the tet minus the
/// cut, however often a folded or kinked surface passes through it, and their volumes sum to
/// the tet's to round-off (the cells' faces close bitwise, see convex_cell.hpp).
struct TetPieces {
  SurfaceCutState state = SurfaceCutState::uncut;
  double volume = 0.0;                   ///< the tet's volume |det J| / 6 (m^3)
  double diameter = 0.0;                 ///< its longest edge (m): the scale of its snap, 1e-12 of it
  std::vector<ConvexCell> cells;         ///< the convex cells
  std::vector<int> cell_piece;           ///< #cells: the piece each cell belongs to
  std::vector<TetPiece> pieces;          ///< at least one
  std::vector<CutTriangle> triangles;    ///< the cut triangles it was split by (FaceOrigin::index counts in this list)
  std::array<std::vector<int>, 4> corner_pieces; ///< for each corner, the pieces whose closure holds it (two or more
                                                 ///< when the cut passes through the corner), in increasing order
  /// For each cell, the planes of its faces that have area (unit outward normal, n . x = offset on
  /// the face): what pieces_containing tests a point against, found once when the tet is split
  /// instead of at every lookup. Empty for pieces put together by hand: then they are found per call.
  std::vector<std::vector<Plane>> cell_planes;
  int num_pieces() const { return static_cast<int>(pieces.size()); }
};

/// The pieces of one straight-edged tet cut by triangles.
///
/// The algorithm (a binary space partition restricted to each triangle's footprint):
/// 1. clip each triangle T to the tet, giving the convex polygon P_T of the cut inside it;
/// 2. every cell that touches P_T is split by the three planes through T's edges
///    perpendicular to T, and then every resulting cell inside T's prism by T's own plane, so
///    that each new face on T's plane lies inside T and each face elsewhere lies outside it;
/// 3. a face is covered by the cut if it was made by a triangle's plane, or (a face made
///    earlier, or one of the tet's faces, that happens to lie in a triangle) its centre lies
///    in a cut triangle of its plane;
/// 4. the pieces are the connected components of the cells through uncovered faces.
///
/// Exactness: whether a corner of the tet lies above, below or on a triangle's plane is decided
/// by CGAL's exact orientation predicate, never by a tolerance, so a cut through a node, along
/// an edge or in a face of the tet is recognised as such. Points made by splits are classified
/// with a snap of 1e-12 times the tet's diameter (distances below it count as on the plane).
/// @param X         the tet's 4 corners (rows), either orientation
/// @param triangles the cut triangles that may meet it (those that do not are harmless)
TetPieces split_tet_by_triangles(const Eigen::Matrix<double, 4, 3>& X, const std::vector<CutTriangle>& triangles);

/// The pieces of `pieces` whose closure holds the point x: one for a point inside a piece, two
/// or more for a point on the cut, none outside the tet.
/// @param x         the point (m)
/// @param tolerance how far outside a cell x may lie and count as in it (m)
std::vector<int> pieces_containing(const TetPieces& pieces, const Eigen::Vector3d& x, double tolerance);

} // namespace kerf
