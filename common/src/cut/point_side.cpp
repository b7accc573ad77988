#include "kerf/cut/point_side.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace kerf {

namespace {

Eigen::Vector3d corner(const TriangleSurface& s, Eigen::Index f, int k) { return s.vertices.row(s.triangles(f, k)).transpose(); }

// The closest point of triangle (p0, p1, p2) to x and the feature it lies on, local corners 0-2
// (Ericson's ClosestPtPointTriangle: the Voronoi regions of the corners, the edges, the face).
struct LocalClosest {
  Eigen::Vector3d point;
  TriangleFeature feature;
  int a, b; // local corners
};

LocalClosest closest_on_triangle(const Eigen::Vector3d& x, const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2) {
  const Eigen::Vector3d ab = p1 - p0, ac = p2 - p0, ap = x - p0;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return {p0, TriangleFeature::vertex, 0, -1};
  const Eigen::Vector3d bp = x - p1;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return {p1, TriangleFeature::vertex, 1, -1};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return {p0 + d1 / (d1 - d3) * ab, TriangleFeature::edge, 0, 1};
  const Eigen::Vector3d cp = x - p2;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return {p2, TriangleFeature::vertex, 2, -1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return {p0 + d2 / (d2 - d6) * ac, TriangleFeature::edge, 0, 2};
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
    return {p1 + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (p2 - p1), TriangleFeature::edge, 1, 2};
  const double denominator = 1.0 / (va + vb + vc);
  return {p0 + vb * denominator * ab + vc * denominator * ac, TriangleFeature::face, -1, -1};
}

int sign_of(double value) { return value > 0.0 ? 1 : (value < 0.0 ? -1 : 0); }

std::pair<int, int> edge_key(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

} // namespace

ClosestSurfacePoint closest_surface_point(const TriangleSurface& surface, const Eigen::Vector3d& x) {
  ClosestSurfacePoint best;
  best.distance = std::numeric_limits<double>::infinity();
  for (Eigen::Index f = 0; f < surface.num_triangles(); ++f) {
    const LocalClosest c = closest_on_triangle(x, corner(surface, f, 0), corner(surface, f, 1), corner(surface, f, 2));
    const double distance = (x - c.point).norm();
    // A tie keeps the lower-numbered triangle. Two triangles sharing the closest edge compute
    // its point from different corners, so their distances may differ in the last bits: a
    // later triangle must be closer by more than 1e-12 relative to count as closer.
    if (distance >= best.distance * (1.0 - 1e-12)) continue;
    best.point = c.point;
    best.distance = distance;
    best.triangle = static_cast<int>(f);
    best.feature = c.feature;
    best.a = c.a >= 0 ? surface.triangles(f, c.a) : -1;
    best.b = c.b >= 0 ? surface.triangles(f, c.b) : -1;
  }
  return best;
}

int closest_triangle_side(const TriangleSurface& surface, const Eigen::Vector3d& x) {
  const ClosestSurfacePoint c = closest_surface_point(surface, x);
  const Eigen::Vector3d p0 = corner(surface, c.triangle, 0);
  const Eigen::Vector3d n = (corner(surface, c.triangle, 1) - p0).cross(corner(surface, c.triangle, 2) - p0);
  return sign_of((x - p0).dot(n));
}

PseudoNormals angle_weighted_pseudo_normals(const TriangleSurface& surface) {
  PseudoNormals normals;
  normals.face.resize(surface.num_triangles(), 3);
  normals.vertex = Eigen::MatrixX3d::Zero(surface.num_vertices(), 3);
  for (Eigen::Index f = 0; f < surface.num_triangles(); ++f) {
    const std::array<Eigen::Vector3d, 3> p{corner(surface, f, 0), corner(surface, f, 1), corner(surface, f, 2)};
    const Eigen::Vector3d n = (p[1] - p[0]).cross(p[2] - p[0]).normalized();
    normals.face.row(f) = n.transpose();
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d u = p[static_cast<std::size_t>((k + 1) % 3)] - p[static_cast<std::size_t>(k)];
      const Eigen::Vector3d w = p[static_cast<std::size_t>((k + 2) % 3)] - p[static_cast<std::size_t>(k)];
      // The angle at corner k, by atan2 (accurate for angles near 0 and pi, unlike acos).
      const double angle = std::atan2(u.cross(w).norm(), u.dot(w));
      normals.vertex.row(surface.triangles(f, k)) += angle * n.transpose();
      const auto key = edge_key(surface.triangles(f, k), surface.triangles(f, (k + 1) % 3));
      normals.edge.try_emplace(key, Eigen::Vector3d::Zero()).first->second += n;
    }
  }
  return normals;
}

int pseudo_normal_side(const TriangleSurface& surface, const PseudoNormals& normals, const Eigen::Vector3d& x) {
  const ClosestSurfacePoint c = closest_surface_point(surface, x);
  Eigen::Vector3d n = normals.face.row(c.triangle).transpose();
  if (c.feature == TriangleFeature::edge) n = normals.edge.at(edge_key(c.a, c.b));
  if (c.feature == TriangleFeature::vertex) n = normals.vertex.row(c.a).transpose();
  return sign_of((x - c.point).dot(n));
}

} // namespace kerf
