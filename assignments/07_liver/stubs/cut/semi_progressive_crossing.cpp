// Assignment 07 (assignments/07_liver/README.md): the semi-progressive crossing test, the edge
// test and the tet test that decide when the blade's swept sheet has crossed a tet. This file
// replaces common/src/cut/semi_progressive_crossing.cpp in the graded build; the declarations,
// with their full comments, are in kerf/cut/semi_progressive_cut.hpp. SemiProgressiveCut
// (semi_progressive_cut.cpp, not handed out) finds the candidate edges of each swept triangle in
// its AABB tree, calls edge_triangle_contact on each, records the crossings once per edge, and
// calls tet_corners_separated on the tets around what changed.
#include "kerf/cut/semi_progressive_cut.hpp"

#include <stdexcept>

namespace kerf {

/// How the segment x_a x_b meets a (non-degenerate) swept triangle, decided exactly (use exact
/// predicates, e.g. CGAL::orientation of CGAL's Exact_predicates_inexact_constructions_kernel,
/// never a tolerance):
/// - end_on_sheet[k]: end k lies in the closed triangle (in its plane, inside or on its boundary);
/// - crossed: the ends lie strictly on opposite sides of the triangle's plane, and the segment
///   meets the plane inside the closed triangle (a blade stopped exactly on the edge has crossed
///   it); an edge with an end in the plane, or lying in it, is not crossed;
/// - parameter: where crossed, s = h_a / (h_a - h_b) clamped to [0, 1], h the ends' heights over
///   the plane (doubles), so that the crossing point is (1 - s) x_a + s x_b; 0 otherwise.
EdgeTriangleContact edge_triangle_contact([[maybe_unused]] const SweptTriangle& triangle, [[maybe_unused]] const Eigen::Vector3d& x_a,
                                          [[maybe_unused]] const Eigen::Vector3d& x_b) {
  throw std::logic_error("assignment 07: implement edge_triangle_contact (assignments/07_liver/README.md)");
}

/// Whether the sheet has crossed a tet (the chapter's rule, replacing Gutierrez and Ramos's third crossed
/// edge, section 3.3): the corners not on the sheet, joined by the tet's edges that are not
/// crossed and have neither end on the sheet, fall into two or more groups.
/// @param edge_crossed    per edge of the tet, in the order of tet_edge_corners (kerf/mesh/tet_mesh.hpp)
/// @param corner_on_sheet per corner 0..3
bool tet_corners_separated([[maybe_unused]] const std::array<bool, 6>& edge_crossed,
                           [[maybe_unused]] const std::array<bool, 4>& corner_on_sheet) {
  throw std::logic_error("assignment 07: implement tet_corners_separated (assignments/07_liver/README.md)");
}

} // namespace kerf
