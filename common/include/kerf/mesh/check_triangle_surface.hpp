/// @file check_triangle_surface.hpp
/// @brief Validate a cut surface read from a file, weld its vertices and orient its triangles consistently.
#pragma once

#include "kerf/mesh/triangle_surface.hpp"

#include <string>

namespace kerf {

/// What check_triangle_surface() changed in a surface, and what it found out about its shape.
struct SurfaceCheck {
  Eigen::Index merged_vertices = 0;   ///< vertices dropped because another one had the same position
  Eigen::Index unused_vertices = 0;   ///< vertices dropped because no triangle used them
  Eigen::Index flipped_triangles = 0; ///< triangles reversed to agree with their neighbours
  Eigen::Index components = 0;        ///< connected components (triangles joined across edges)
  Eigen::Index boundary_edges = 0;    ///< edges of one triangle only: the cut's front, later
};

/// Checks a triangle surface that came from outside, welds it and orients it, so that it keeps
/// the promises of TriangleSurface.
///
/// In this order (indices in the messages are 0-based, as in the surface):
/// 1. it must have a triangle, every vertex index must lie in [0, #V) and every coordinate
///    must be finite (even on a vertex no triangle uses: a NaN means the file is broken);
/// 2. vertices at exactly the same position are merged into one (the one that comes first),
///    and vertices no triangle uses are dropped; the others keep their order. Welding lives
///    here rather than in the STL reader because every format needs it: an STL file stores
///    each triangle's three corners on their own, with no shared vertices at all, and OBJ and
///    VTK files exported from modellers often repeat the vertices along seams. Only exactly
///    equal positions are merged, with no tolerance: a tolerance would be a length scale the
///    user never chose, and it could merge the two banks of a thin slit;
/// 3. no triangle may be degenerate: two of its corners the same vertex (after welding), or the
///    three corners collinear, decided exactly by CGAL::collinear() on the double coordinates
///    (Exact_predicates_inexact_constructions_kernel), never with an epsilon. A degenerate
///    triangle has no normal, so no side of the cut;
/// 4. no two triangles may have the same three corners (in any order): a surface lying on itself;
/// 5. no edge may belong to more than two triangles (a non-manifold edge, where three sheets
///    meet and "the other side" means nothing);
/// 6. the triangles are oriented consistently, component by component, by a breadth-first walk
///    over the triangles that share an edge: the first triangle of each component (the lowest
///    index) keeps its orientation, and a neighbour that traverses the shared edge in the same
///    direction as the triangle it is reached from is reversed (corners 1 and 2 swapped). If a
///    triangle is reached twice with contradicting orientations, the surface has no consistent
///    orientation (a Möbius strip) and is refused: it has one side only, so no sign of a point.
///    We orient combinatorially rather than by comparing normals (P §3.2's "dot product > 0"),
///    which fails for folds sharper than 90 degrees.
///
/// A surface built in code can be put through this check too; a checked surface passes it
/// again unchanged (nothing merged, dropped or flipped).
///
/// @param surface the surface, welded and oriented in place
/// @param file    the file name used in messages
/// @return what was merged, dropped and flipped, the number of components and of boundary edges
/// @throws InputError `FILE: FIELD: PROBLEM` for the first problem found, FIELD naming the
///         triangle, vertex or edge
SurfaceCheck check_triangle_surface(TriangleSurface& surface, const std::string& file);

} // namespace kerf
