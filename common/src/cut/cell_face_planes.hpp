// Private to the kerf library (not under include/): the planes of a convex cell's faces, which
// both the splitting of a tet (split_tet_by_triangles.cpp) and the lookup of the pieces that
// hold a point (tet_pieces.cpp) test points against.
#pragma once

#include "kerf/cut/convex_cell.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

namespace kerf {

// The side function of any other plane (through an edge of a triangle, or a face of a cell):
// the distance, snapped.
struct SnappedPlaneSide {
  Eigen::Vector3d normal; // unit
  double offset;
  double tolerance;
  double operator()(const Eigen::Vector3d& x) const {
    const double distance = normal.dot(x) - offset;
    return std::abs(distance) <= tolerance ? 0.0 : distance;
  }
};

// The plane of a face of a cell, with its outward normal: value > 0 outside the cell. The second
// form takes the face's area vector (polygon_area_vector) when the caller has it already.
inline SnappedPlaneSide face_plane(const CellFace& face, const Eigen::Vector3d& area_vector, double tolerance) {
  const Eigen::Vector3d n = area_vector.normalized();
  return {n, n.dot(face.polygon.front()), tolerance};
}
inline SnappedPlaneSide face_plane(const CellFace& face, double tolerance) {
  return face_plane(face, polygon_area_vector(face.polygon), tolerance);
}

// Whether a face is more than a sliver: wider than the snap (1e-12 d), its width taken as its
// area over its longest edge. A narrower face is one the snap cannot tell apart from a line: a split left it where two cut planes meet at an angle, where a
// plane grazes an edge, or round a vertex of the cut where several triangles' edge planes meet
// (an icosphere's vertices leave faces of 1e-22 d^2 there). Its normal is noise, it bounds
// nothing the cell's other faces do not, and no material joins two cells through it: gluing
// through it let the inside of a fine icosphere leak to the outside.
inline bool has_area(const CellFace& face, const Eigen::Vector3d& area_vector, double snap) {
  if (face.polygon.size() < 3) return false;
  double longest = 0.0;
  for (std::size_t k = 0; k < face.polygon.size(); ++k)
    longest = std::max(longest, (face.polygon[(k + 1) % face.polygon.size()] - face.polygon[k]).norm());
  return area_vector.norm() > snap * longest;
}
inline bool has_area(const CellFace& face, double snap) { return has_area(face, polygon_area_vector(face.polygon), snap); }

// The outward planes of a cell's faces that have area (unit normals): a point x is outside the
// cell, beyond a tolerance, when n . x - offset > tolerance for one of them (face_plane's test).
inline std::vector<Plane> cell_face_planes(const ConvexCell& cell, double snap) {
  std::vector<Plane> planes;
  for (const CellFace& face : cell.faces) {
    const Eigen::Vector3d area_vector = polygon_area_vector(face.polygon);
    if (!has_area(face, area_vector, snap)) continue;
    const Eigen::Vector3d n = area_vector.normalized();
    planes.push_back({n, n.dot(face.polygon.front())});
  }
  return planes;
}

} // namespace kerf
