/// @file convex_cell.hpp
/// @brief A convex polyhedron kept as its face polygons, split by planes: the building block of a tet cut by a triangle mesh.
///
/// Chapter 3 clipped a tet by one plane with a table of sign cases (clip_tet.hpp). A triangle
/// mesh is many planes, each valid only inside its triangle, and the pieces it leaves in a tet
/// need not be convex (a kinked cut makes an L-shaped piece). So chapter 4 cuts the tet into
/// convex cells, splitting by one plane at a time (a binary space partition), and then glues
/// the cells whose shared face the cut does not cover into pieces (tet_pieces.hpp). Each cell
/// stays convex, so it can always be integrated exactly, by a fan of tetrahedra.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <concepts>
#include <vector>

namespace kerf {

/// The oriented plane n . x = offset; "above" is where n . x > offset.
struct Plane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ(); ///< n, not necessarily of unit length
  double offset = 0.0;                               ///< n . x on the plane
  /// n . x - offset: a multiple |n| of the signed distance.
  double evaluate(const Eigen::Vector3d& x) const { return normal.dot(x) - offset; }
};

/// Where a face of a cell came from, so that a piece's boundary can say which part of it lies
/// on the tet's surface and which on the cut.
struct FaceOrigin {
  enum class Kind : signed char {
    tet_face,     ///< part of face `index` of the tet (the face opposite corner `index`)
    cut_plane,    ///< part of the plane of cut triangle `index` (the candidate's position in the list)
    edge_plane,   ///< part of a plane through an edge of cut triangle `index`: never covered by the cut
  };
  Kind kind = Kind::tet_face;
  int index = 0;
};

/// One face of a convex cell: a convex polygon, its corners counter-clockwise seen from outside
/// the cell, the cell on its other side, and where it came from.
struct CellFace {
  std::vector<Eigen::Vector3d> polygon; ///< corners in order; consecutive collinear corners may occur
  int neighbour = -1;                   ///< index of the cell across this face, -1 on the tet's boundary
  FaceOrigin origin;                    ///< which plane the face lies in
  bool covered = false;                 ///< the cut covers this face (set once all triangles are in, tet_pieces.cpp)
  int cut_side = 0;                     ///< when covered: +1 if the cell lies above the covering triangle, -1 below
};

/// A convex polyhedron as the closed surface of its face polygons (a "polygon soup" that
/// closes exactly: where two faces meet, their corners are bitwise the same points).
///
/// Why faces and not a vertex list with indices: a split that passes near an existing corner
/// makes points that two faces would otherwise compute in two ways; here a point on an edge
/// is always interpolated from the same end (the one above the plane), so both faces of the
/// edge, and the neighbouring cell, get bitwise the same point, and the surface stays closed.
struct ConvexCell {
  std::vector<CellFace> faces;
};

/// The tet with corners X (rows) as a cell with four faces, face f opposite corner f,
/// all on the tet's boundary (neighbour -1), oriented outward whatever the corners' order.
ConvexCell tet_cell(const Eigen::Matrix<double, 4, 3>& X);

/// The signed value of each corner of each face against a plane, with the decision of which
/// corners lie on it.
///
/// `value(x)` must be a deterministic function of the point (the same point always gets the
/// same value), with 0 meaning "on the plane". tet_pieces.cpp passes exact orientation
/// predicates for points that are corners of the tet and a snapped plane evaluation for
/// points made by earlier splits.
template <typename Value>
concept PlaneSideFunction = requires(const Value& v, const Eigen::Vector3d& x) {
  { v(x) } -> std::convertible_to<double>;
};

/// Whether the cell lies on both sides of a plane: some corner has value > 0 and some < 0.
/// @return +1 all values >= 0 (above or on), -1 all <= 0 (below or on), 0 if it straddles
///         (a cell lying in the plane, all values 0, cannot occur: it would have no volume)
template <PlaneSideFunction Value>
int cell_side(const ConvexCell& cell, const Value& value) {
  bool above = false, below = false;
  for (const CellFace& face : cell.faces)
    for (const Eigen::Vector3d& x : face.polygon) {
      const double s = value(x);
      above = above || s > 0.0;
      below = below || s < 0.0;
    }
  return above && below ? 0 : (below ? -1 : 1);
}

/// Splits the polygon by a plane into the part where value >= 0 and the part where value <= 0
/// (Sutherland-Hodgman for one plane). A crossing point on the edge (p, q) with value(p) > 0 >
/// value(q) is p + s_p / (s_p - s_q) (q - p), always computed from the end above, so the same
/// edge walked in either direction gives bitwise the same point.
/// @param polygon the convex polygon, corners in order
/// @param value   the plane's side function
/// @param above   receives the part with value >= 0 (fewer than 3 corners: nothing above)
/// @param below   receives the part with value <= 0
/// @param on_plane when given, gets the corners of value 0 and the crossings appended (each once)
template <PlaneSideFunction Value>
void split_polygon(const std::vector<Eigen::Vector3d>& polygon, const Value& value, std::vector<Eigen::Vector3d>& above,
                   std::vector<Eigen::Vector3d>& below, std::vector<Eigen::Vector3d>* on_plane = nullptr) {
  const auto record = [on_plane](const Eigen::Vector3d& x) {
    if (on_plane && std::find(on_plane->begin(), on_plane->end(), x) == on_plane->end()) on_plane->push_back(x);
  };
  above.clear();
  below.clear();
  const std::size_t n = polygon.size();
  if (n == 0) return;
  // Each corner's value once, carried along the walk (no buffer: this runs for every face of
  // every cell a cut triangle looks at, and an allocation per call was a third of its cost).
  const double first = value(polygon[0]);
  bool any_above = false, any_below = false;
  double sp = first;
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector3d& p = polygon[k];
    const Eigen::Vector3d& q = polygon[(k + 1) % n];
    const double sq = k + 1 < n ? value(q) : first;
    any_above = any_above || sp > 0.0;
    any_below = any_below || sp < 0.0;
    if (sp >= 0.0) above.push_back(p);
    if (sp <= 0.0) below.push_back(p);
    if (sp == 0.0) record(p);
    if ((sp > 0.0 && sq < 0.0) || (sp < 0.0 && sq > 0.0)) {
      // From the end above: the same point whichever face walks this edge.
      const Eigen::Vector3d crossing = sp > 0.0 ? Eigen::Vector3d(p + sp / (sp - sq) * (q - p))
                                                : Eigen::Vector3d(q + sq / (sq - sp) * (p - q));
      above.push_back(crossing);
      below.push_back(crossing);
      record(crossing);
    }
    sp = sq;
  }
  // A part needs a corner strictly on its side: otherwise all its points lie on the plane,
  // in a line (the polygon only touches the plane), and it has no area.
  if (above.size() < 3 || !any_above) above.clear();
  if (below.size() < 3 || !any_below) below.clear();
}

/// The points where a plane meets a polygon, as split_polygon() finds them: the corners of
/// value 0 and the crossings of its edges (the same doubles split_polygon() makes), appended to
/// `on_plane` if not there yet. For looking at a section before deciding whether to split.
/// @return whether some corner has a value > 0 (above) and some a value < 0 (below)
struct PlaneSides {
  bool above = false;
  bool below = false;
};
template <PlaneSideFunction Value>
PlaneSides polygon_section(const std::vector<Eigen::Vector3d>& polygon, const Value& value, std::vector<Eigen::Vector3d>& on_plane) {
  const auto record = [&on_plane](const Eigen::Vector3d& x) {
    if (std::find(on_plane.begin(), on_plane.end(), x) == on_plane.end()) on_plane.push_back(x);
  };
  PlaneSides sides;
  const std::size_t n = polygon.size();
  if (n == 0) return sides;
  const double first = value(polygon[0]);
  double sp = first;
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector3d& p = polygon[k];
    const Eigen::Vector3d& q = polygon[(k + 1) % n];
    const double sq = k + 1 < n ? value(q) : first;
    sides.above = sides.above || sp > 0.0;
    sides.below = sides.below || sp < 0.0;
    if (sp == 0.0) record(p);
    if (sp > 0.0 && sq < 0.0) record(Eigen::Vector3d(p + sp / (sp - sq) * (q - p)));
    if (sp < 0.0 && sq > 0.0) record(Eigen::Vector3d(q + sq / (sq - sp) * (p - q)));
    sp = sq;
  }
  return sides;
}

/// The area vector of a planar polygon (Newell): its length is the area, it points along the
/// normal for which the corners run counter-clockwise.
Eigen::Vector3d polygon_area_vector(const std::vector<Eigen::Vector3d>& polygon);

/// Orders the corners of a convex polygon that lies in a plane with normal n counter-clockwise
/// seen from the side n points to (by angle about their mean). Exactly equal points must have
/// been removed.
void order_convex_polygon(std::vector<Eigen::Vector3d>& corners, const Eigen::Vector3d& normal);

/// Splits cell `c` of a cell complex by a plane, if the plane passes through it.
///
/// The part with value >= 0 keeps index c, the part with value <= 0 becomes a new cell at the
/// end of `cells`; both get the section as a new face (`origin`, each the other's neighbour),
/// with outward normal -plane.normal above and +plane.normal below. Every neighbour across a
/// face that the plane splits has its matching face split the same way, so that each face
/// still meets exactly one cell: the complex stays a partition of the tet with known adjacency.
/// @return the index of the new cell below, or -1 when the cell lies on one side
template <PlaneSideFunction Value>
int split_cell(std::vector<ConvexCell>& cells, int c, const Value& value, const Plane& plane, FaceOrigin origin) {
  if (cell_side(cells[c], value) != 0) return -1;
  const int b = static_cast<int>(cells.size());
  ConvexCell above, below;
  std::vector<Eigen::Vector3d> section, part_above, part_below;
  for (const CellFace& face : cells[c].faces) {
    // The section's corners are the points of the faces on the plane: old corners of value 0
    // and new crossings.
    split_polygon(face.polygon, value, part_above, part_below, &section);
    // A face with every corner on the plane (a cell convex only up to the snap, whose face lies
    // within the snap of a plane that still crosses the cell) would go into neither half. It
    // bounds the half on the side away from which it faces: below if its outward normal points
    // up. Its neighbour's copy faces the other way and follows the same decision below.
    const bool on_plane = part_above.empty() && part_below.empty() && face.polygon.size() >= 3;
    const bool to_below = on_plane && polygon_area_vector(face.polygon).dot(plane.normal) > 0.0;
    if (on_plane) (to_below ? part_below : part_above) = face.polygon;
    if (!part_above.empty()) above.faces.push_back({part_above, face.neighbour, face.origin, face.covered, face.cut_side});
    if (!part_below.empty()) below.faces.push_back({part_below, face.neighbour, face.origin, face.covered, face.cut_side});
    // The neighbour's face towards c is this face walked backwards: split it the same way.
    if (face.neighbour < 0) continue;
    std::vector<CellFace>& theirs = cells[face.neighbour].faces;
    for (std::size_t k = 0; k < theirs.size(); ++k) {
      if (theirs[k].neighbour != c) continue;
      split_polygon(theirs[k].polygon, value, part_above, part_below);
      if (on_plane) {
        if (to_below) theirs[k].neighbour = b;
      } else if (part_above.empty()) {
        theirs[k].neighbour = b;
      } else if (!part_below.empty()) {
        CellFace lower{part_below, b, theirs[k].origin, theirs[k].covered, theirs[k].cut_side};
        theirs[k].polygon = part_above;
        theirs.push_back(std::move(lower));
      }
      break;
    }
  }
  order_convex_polygon(section, plane.normal);
  below.faces.push_back({section, c, origin, false, 0});
  std::reverse(section.begin(), section.end());
  above.faces.push_back({section, b, origin, false, 0});
  cells[c] = std::move(above);
  cells.push_back(std::move(below));
  return b;
}

/// The volume of a closed convex cell, (1/3) sum over faces of (x_f . A_f), with x_f a corner
/// of the face and A_f its outward area vector (the divergence theorem for div x = 3).
double convex_cell_volume(const ConvexCell& cell);

/// The mean of the corners of the cell's faces (each corner counted once per face): a point
/// inside a convex cell, cheaper than its centroid.
Eigen::Vector3d convex_cell_inner_point(const ConvexCell& cell);

/// The cell as positively oriented tetrahedra: a fan from the cell's first corner to the
/// triangles of a fan over each face that does not contain that corner. Every tet lies in the
/// cell and they fill it without overlap, so a Gauss rule on each integrates over the cell with
/// the rule's degree of exactness.
std::vector<Eigen::Matrix<double, 4, 3>> convex_cell_tetrahedra(const ConvexCell& cell);

} // namespace kerf
