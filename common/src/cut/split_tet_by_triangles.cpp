// split_tet_by_triangles (tet_pieces.hpp): a tet cut into its pieces by cut triangles, in a file
// of its own, so that chapter 4's assignment can replace it (assignments/04_cut_quadrature/).
#include "kerf/cut/tet_pieces.hpp"

#include "cut/cell_face_planes.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numeric>

namespace kerf {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Corners = Eigen::Matrix<double, 4, 3>;

Kernel::Point_3 to_cgal(const Eigen::Vector3d& x) { return {x[0], x[1], x[2]}; }

// The side function of a triangle's plane. A corner of the tet gets the exact sign of
// orientation(T0, T1, T2, corner) (positive above, where (T1 - T0) x (T2 - T0) points), and a
// value of that sign; any other point gets its distance to the plane, snapped to 0 within the
// tolerance. The value of a corner that the predicate puts strictly on one side is never 0,
// however small its distance: the exact decision wins over round-off.
//
// The corners' values are decided once per triangle, when the side function is made: the
// function is asked about the same four corners again and again as cells are split.
struct TrianglePlaneSide {
  const Corners* X;
  Eigen::Vector3d normal; // unit
  double offset;
  double tolerance;
  std::array<double, 4> corner_value{}; // the value of corner k, its sign exact

  TrianglePlaneSide(const CutTriangle& triangle, const Corners& corners, const Eigen::Vector3d& unit_normal, double tol)
      : X(&corners), normal(unit_normal), offset(unit_normal.dot(triangle.corners[0])), tolerance(tol) {
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d x = corners.row(k).transpose();
      const CGAL::Orientation o = CGAL::orientation(to_cgal(triangle.corners[0]), to_cgal(triangle.corners[1]),
                                                    to_cgal(triangle.corners[2]), to_cgal(x));
      const double distance = normal.dot(x) - offset;
      corner_value[static_cast<std::size_t>(k)] =
          o == CGAL::COPLANAR ? 0.0 : (o == CGAL::POSITIVE ? 1.0 : -1.0) * std::max(std::abs(distance), std::numeric_limits<double>::min());
    }
  }

  double operator()(const Eigen::Vector3d& x) const {
    for (int k = 0; k < 4; ++k)
      if (x == X->row(k).transpose()) return corner_value[static_cast<std::size_t>(k)];
    const double distance = normal.dot(x) - offset;
    return std::abs(distance) <= tolerance ? 0.0 : distance;
  }
};

// Clips a convex polygon to the closed half-space value <= 0 (with the snap: points within
// the tolerance are kept). Keeps only the part inside; may leave fewer than 3 points, which
// still tell that the polygon touches the half-space.
std::vector<Eigen::Vector3d> keep_below(const std::vector<Eigen::Vector3d>& polygon, const SnappedPlaneSide& side) {
  std::vector<Eigen::Vector3d> kept;
  const std::size_t n = polygon.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector3d& p = polygon[k];
    const Eigen::Vector3d& q = polygon[(k + 1) % n];
    const double sp = side(p), sq = side(q);
    if (sp <= 0.0) kept.push_back(p);
    if ((sp < 0.0 && sq > 0.0) || (sp > 0.0 && sq < 0.0)) kept.push_back(p + sp / (sp - sq) * (q - p));
  }
  return kept;
}

// Whether point x lies in the closed triangle t, given that it lies in t's plane: its three
// barycentric coordinates (by areas in the plane) are >= -tolerance relative.
bool in_triangle(const Eigen::Vector3d& x, const CutTriangle& t, const Eigen::Vector3d& unit_normal) {
  const double twice_area = (t.corners[1] - t.corners[0]).cross(t.corners[2] - t.corners[0]).dot(unit_normal);
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d& p = t.corners[(k + 1) % 3];
    const Eigen::Vector3d& q = t.corners[(k + 2) % 3];
    if ((q - p).cross(x - p).dot(unit_normal) < -1e-12 * twice_area) return false;
  }
  return true;
}

// The bounding box of a cell's corners.
Eigen::AlignedBox3d cell_box(const ConvexCell& cell) {
  Eigen::AlignedBox3d box;
  for (const CellFace& face : cell.faces)
    for (const Eigen::Vector3d& x : face.polygon) box.extend(x);
  return box;
}

int find_root(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

} // namespace

TetPieces split_tet_by_triangles(const Corners& X, const std::vector<CutTriangle>& triangles) {
  TetPieces result;
  Eigen::Matrix3d J;
  for (int c = 0; c < 3; ++c) J.col(c) = (X.row(c + 1) - X.row(0)).transpose();
  result.volume = std::abs(J.determinant()) / 6.0;
  double diameter = 0.0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) diameter = std::max(diameter, (X.row(i) - X.row(j)).norm());
  const double tolerance = 1e-12 * diameter;
  result.diameter = diameter;

  std::vector<ConvexCell>& cells = result.cells;
  cells.push_back(tet_cell(X));
  std::vector<Eigen::AlignedBox3d> boxes{cell_box(cells.front())}; // one per cell, kept up to date
  // The tet's four faces as inward-pointing half-spaces, to clip each triangle to the tet.
  const ConvexCell tet = cells.front();

  std::vector<Eigen::Vector3d> unit_normals(triangles.size());
  for (std::size_t k = 0; k < triangles.size(); ++k) {
    const CutTriangle& T = triangles[k];
    const Eigen::Vector3d n = (T.corners[1] - T.corners[0]).cross(T.corners[2] - T.corners[0]).normalized();
    unit_normals[k] = n;

    // 1. P_T, the part of T in the closed tet.
    std::vector<Eigen::Vector3d> P(T.corners.begin(), T.corners.end());
    for (const CellFace& face : tet.faces) {
      P = keep_below(P, face_plane(face, tolerance));
      if (P.empty()) break;
    }
    if (P.size() < 3) continue; // T misses the tet, or touches it in a point or a segment only

    // 2. Split only where T's plane meets a cell inside T's footprint. For every cell: its
    // section by T's plane (or its face in that plane, for a cell that only touches it). A
    // section that lies across one of T's edges is split by the plane through that edge
    // (perpendicular to T, inner side towards the opposite corner), and both halves are looked
    // at again; a section outside an edge is not T's business; a section inside all three is
    // inside T, and the cell is split by T's plane: its new faces lie in T, covered by the cut.
    std::array<SnappedPlaneSide, 3> edge_sides;
    std::array<Plane, 3> edge_planes;
    for (int e = 0; e < 3; ++e) {
      const Eigen::Vector3d& p = T.corners[e];
      const Eigen::Vector3d& q = T.corners[(e + 1) % 3];
      const Eigen::Vector3d m = n.cross(q - p).normalized(); // in T's plane, perpendicular to the edge, pointing inwards
      edge_sides[e] = {m, m.dot(p), tolerance};
      edge_planes[e] = {m, m.dot(p)};
    }
    const TrianglePlaneSide side(T, X, n, tolerance);
    const Plane plane{n, n.dot(T.corners[0])};
    // Only cells whose box meets T's box can meet T: most cells of a tet that many small
    // triangles cross are far from any one of them.
    Eigen::AlignedBox3d triangle_box;
    for (const Eigen::Vector3d& x : T.corners) triangle_box.extend(x);
    const Eigen::Vector3d margin = Eigen::Vector3d::Constant(tolerance);
    triangle_box.extend(triangle_box.min() - margin).extend(triangle_box.max() + margin);
    std::vector<int> work;
    for (int c = 0; c < static_cast<int>(cells.size()); ++c)
      if (boxes[static_cast<std::size_t>(c)].intersects(triangle_box)) work.push_back(c);
    std::vector<Eigen::Vector3d> section;
    while (!work.empty()) {
      const int c = work.back();
      work.pop_back();
      // The section: the cell's points on T's plane (corners of value 0 and crossings).
      section.clear();
      PlaneSides cell_sides;
      for (const CellFace& face : cells[c].faces) {
        const PlaneSides face_sides = polygon_section(face.polygon, side, section);
        cell_sides.above = cell_sides.above || face_sides.above;
        cell_sides.below = cell_sides.below || face_sides.below;
      }
      const bool straddles = cell_sides.above && cell_sides.below; // cell_side() == 0, from the same values
      if (section.size() < 3) continue; // the plane misses the cell, or touches an edge or a corner
      // Look at all three edges before splitting: a section beyond any one edge's line does not
      // meet T, whatever the other two say, and splitting it would only fragment the cell.
      int split_edge = -1;
      bool outside = false;
      for (int e = 0; e < 3 && !outside; ++e) {
        bool in = false, out = false;
        for (const Eigen::Vector3d& x : section) {
          const double v = edge_sides[e](x);
          in = in || v > 0.0;
          out = out || v < 0.0;
        }
        if (!in) outside = true; // the section lies on or beyond this edge's line
        else if (out && split_edge < 0) split_edge = e;
      }
      if (outside) continue;
      if (split_edge >= 0) {
        const int b = split_cell(cells, c, edge_sides[split_edge], edge_planes[split_edge],
                                 {FaceOrigin::Kind::edge_plane, static_cast<int>(k)});
        if (b >= 0) {
          boxes[static_cast<std::size_t>(c)] = cell_box(cells[static_cast<std::size_t>(c)]);
          boxes.push_back(cell_box(cells[static_cast<std::size_t>(b)]));
          work.push_back(c);
          work.push_back(b);
          continue;
        }
        // The section crossed the edge's line by round-off only (the cell's corners, which the
        // split looks at, do not): the cell is inside that edge, go on as for a cell inside T.
      }
      if (straddles) {
        const int b = split_cell(cells, c, side, plane, {FaceOrigin::Kind::cut_plane, static_cast<int>(k)});
        if (b >= 0) {
          boxes[static_cast<std::size_t>(c)] = cell_box(cells[static_cast<std::size_t>(c)]);
          boxes.push_back(cell_box(cells[static_cast<std::size_t>(b)]));
        }
      }
    }
  }

  // 3. Which faces the cut covers. A face made by a triangle's plane inside its prism is covered
  // by construction; any other face is covered when it lies in the plane of a triangle (parallel,
  // its centre on the plane) and its centre lies in that triangle.
  for (ConvexCell& cell : cells)
    for (CellFace& face : cell.faces) {
      const Eigen::Vector3d a = polygon_area_vector(face.polygon);
      if (face.origin.kind == FaceOrigin::Kind::cut_plane) {
        face.covered = true;
        face.cut_side = a.dot(unit_normals[static_cast<std::size_t>(face.origin.index)]) < 0.0 ? 1 : -1;
        continue;
      }
      if (a.norm() == 0.0) continue;
      const Eigen::Vector3d normal = a.normalized();
      Eigen::Vector3d centre = Eigen::Vector3d::Zero();
      for (const Eigen::Vector3d& x : face.polygon) centre += x;
      centre /= static_cast<double>(face.polygon.size());
      for (std::size_t k = 0; k < triangles.size() && !face.covered; ++k) {
        const Eigen::Vector3d& n = unit_normals[k];
        if (std::abs(std::abs(n.dot(normal)) - 1.0) > 1e-9) continue;
        if (std::abs(n.dot(centre - triangles[k].corners[0])) > tolerance) continue;
        face.covered = in_triangle(centre, triangles[k], n);
        if (face.covered) face.cut_side = normal.dot(n) < 0.0 ? 1 : -1;
      }
    }

  // 4. Pieces: cells glued through uncovered faces (a face and its neighbour's copy agree, as
  // both are decided from the same plane; a face is glued if either copy is uncovered, so that
  // a round-off disagreement can only merge, never tear the material).
  const int n_cells = static_cast<int>(cells.size());
  std::vector<int> parent(n_cells);
  std::iota(parent.begin(), parent.end(), 0);
  bool cut_inside = false, cut_on_face = false;
  for (int c = 0; c < n_cells; ++c)
    for (const CellFace& face : cells[c].faces) {
      if (face.neighbour < 0) {
        cut_on_face = cut_on_face || face.covered;
        continue;
      }
      if (face.covered) {
        cut_inside = true;
        continue;
      }
      if (!has_area(face, tolerance)) continue; // two cells touching along a line only

      parent[find_root(parent, c)] = find_root(parent, face.neighbour);
    }
  result.cell_piece.assign(n_cells, -1);
  std::vector<int> root_piece(n_cells, -1);
  for (int c = 0; c < n_cells; ++c) {
    const int r = find_root(parent, c);
    if (root_piece[r] < 0) {
      root_piece[r] = static_cast<int>(result.pieces.size());
      result.pieces.emplace_back();
    }
    const int p = root_piece[r];
    result.cell_piece[c] = p;
    TetPiece& piece = result.pieces[p];
    piece.cells.push_back(c);
    piece.volume += convex_cell_volume(cells[c]);
    for (const CellFace& face : cells[c].faces) {
      const bool inner = face.neighbour >= 0;
      if (inner && !face.covered) continue;
      PieceBoundaryPolygon boundary{face.polygon, face.origin, face.covered, face.cut_side};
      piece.boundary.push_back(std::move(boundary));
    }
  }
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector3d corner = X.row(k).transpose();
    for (int c = 0; c < n_cells; ++c) {
      bool holds = false;
      for (const CellFace& face : cells[c].faces)
        holds = holds || std::find(face.polygon.begin(), face.polygon.end(), corner) != face.polygon.end();
      std::vector<int>& list = result.corner_pieces[k];
      if (holds && std::find(list.begin(), list.end(), result.cell_piece[c]) == list.end()) list.push_back(result.cell_piece[c]);
    }
    std::sort(result.corner_pieces[k].begin(), result.corner_pieces[k].end());
  }

  result.cell_planes.reserve(cells.size());
  for (const ConvexCell& cell : cells) result.cell_planes.push_back(cell_face_planes(cell, 1e-12 * result.diameter));
  result.triangles = triangles;
  if (result.pieces.size() > 1) result.state = SurfaceCutState::completely_cut;
  else if (cut_inside) result.state = SurfaceCutState::partially_cut;
  else if (cut_on_face) result.state = SurfaceCutState::touched;
  return result;
}

} // namespace kerf
