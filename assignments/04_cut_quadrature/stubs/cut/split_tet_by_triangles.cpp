// Assignment 04, part 1: a tet cut into its pieces by the triangles of the cut surfaces.
// This file stands in for common/src/cut/split_tet_by_triangles.cpp when assignment 04 is
// graded (./kerf.sh assignment 04); what to compute is in assignments/04_cut_quadrature/README.md.
#include "kerf/cut/tet_pieces.hpp"

// The tools you build on (all the library's, all tested):
#include "kerf/cut/convex_cell.hpp" // tet_cell, split_cell, polygon_section, split_polygon, polygon_area_vector,
                                    // convex_cell_volume: a convex cell kept as its face polygons, split by a plane
#include "cut/cell_face_planes.hpp" // SnappedPlaneSide, face_plane, has_area: a cell face's plane, and whether it has area

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h> // CGAL::orientation: the exact side of a corner

#include <stdexcept>

namespace kerf {

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
///
/// What the result must hold (tet_pieces.hpp says it field by field): `volume` |det J| / 6,
/// `diameter` the longest edge, the `cells` and `cell_piece`, every piece with its cells, its
/// volume and its closed `boundary` (the cells' faces on the tet's surface or on the cut,
/// outward, with `on_cut` and `cut_side`), `corner_pieces`, `triangles` (the input), and
/// `state`: completely_cut with two or more pieces, else partially_cut if a covered face lies
/// inside the tet, else touched if a covered face lies on its surface, else uncut.
/// @param X         the tet's 4 corners (rows), either orientation
/// @param triangles the cut triangles that may meet it (those that do not are harmless)
TetPieces split_tet_by_triangles([[maybe_unused]] const Eigen::Matrix<double, 4, 3>& X,
                                 [[maybe_unused]] const std::vector<CutTriangle>& triangles) {
  throw std::logic_error("assignment 04: implement split_tet_by_triangles (assignments/04_cut_quadrature/README.md)");
}

} // namespace kerf
