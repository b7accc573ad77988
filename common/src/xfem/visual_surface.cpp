#include "kerf/xfem/visual_surface.hpp"

#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/mesh/point_locator.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <limits>
#include <utility>

namespace kerf {

namespace {

/// lambda of x in the tet with corners X (rows): xi = J^-1 (x - X_0) with J = [X_1 - X_0, X_2 - X_0,
/// X_3 - X_0], lambda = (1 - xi_1 - xi_2 - xi_3, xi). Outside the tet some lambda are negative.
Eigen::Vector4d barycentric_in(const Eigen::Matrix<double, 4, 3>& X, const Eigen::Vector3d& x) {
  Eigen::Matrix3d J;
  for (int a = 0; a < 3; ++a) J.col(a) = (X.row(a + 1) - X.row(0)).transpose();
  const Eigen::Vector3d xi = J.partialPivLu().solve(x - X.row(0).transpose());
  return {1.0 - xi.sum(), xi(0), xi(1), xi(2)};
}

/// The point of the triangle (a, b, c) closest to p (Ericson, Real-Time Collision Detection, 5.1.5):
/// which of the seven regions (three corners, three edges, the face) p projects into.
Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + d1 / (d1 - d3) * ab;
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denominator = 1.0 / (va + vb + vc);
  return a + ab * (vb * denominator) + ac * (vc * denominator);
}

/// Row i of a #rows by 3 matrix as a point. A template, so that the mesh's nodes (row-major) and
/// the surface's vertices (column-major) are both read in place, never copied.
template <typename Matrix>
Eigen::Vector3d row(const Matrix& m, Eigen::Index i) {
  return m.row(i).transpose();
}

/// (b - a) x (c - a) . (d - a): six times the signed volume of the tet (a, b, c, d).
double orientation(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
  return (b - a).cross(c - a).dot(d - a);
}

/// Whether the segment p q crosses the triangle (a, b, c): p and q strictly on opposite sides of
/// its plane, and the line p q passing through the triangle (the three volumes with p q and one
/// edge of the triangle all of one sign, zero on an edge).
bool segment_crosses_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                              const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double side_p = orientation(a, b, c, p), side_q = orientation(a, b, c, q);
  if (!((side_p < 0.0 && side_q > 0.0) || (side_p > 0.0 && side_q < 0.0))) return false;
  const double s_ab = orientation(p, q, a, b), s_bc = orientation(p, q, b, c), s_ca = orientation(p, q, c, a);
  return (s_ab >= 0.0 && s_bc >= 0.0 && s_ca >= 0.0) || (s_ab <= 0.0 && s_bc <= 0.0 && s_ca <= 0.0);
}

} // namespace

VisualSurface::VisualSurface(const TetMesh& mesh, TriangleSurface reference) : mesh_(mesh), reference_(std::move(reference)) {
  const PointLocator locator(mesh_);
  const BoundaryFaces boundary = boundary_faces(mesh_);
  embedding_.resize(static_cast<std::size_t>(reference_.num_vertices()));
  for (Eigen::Index v = 0; v < reference_.num_vertices(); ++v) {
    const Eigen::Vector3d x = row(reference_.vertices, v);
    VisualVertexEmbedding& e = embedding_[static_cast<std::size_t>(v)];
    const PointLocation location = locator.locate(x);
    if (location.tet >= 0) {
      e.tet = static_cast<int>(location.tet);
      e.barycentric = {1.0 - location.xi.sum(), location.xi(0), location.xi(1), location.xi(2)};
      continue;
    }
    // Outside every tet: the tet of the closest boundary face, searched among them all.
    double best = std::numeric_limits<double>::infinity();
    for (Eigen::Index f = 0; f < boundary.faces.rows(); ++f) {
      const Eigen::Vector3d closest =
          closest_point_on_triangle(x, row(mesh_.nodes, boundary.faces(f, 0)), row(mesh_.nodes, boundary.faces(f, 1)),
                                    row(mesh_.nodes, boundary.faces(f, 2)));
      const double d = (closest - x).norm();
      if (d < best) {
        best = d;
        e.tet = boundary.tet[static_cast<std::size_t>(f)];
      }
    }
    e.distance = best;
    e.barycentric = barycentric_in(tet_corners(mesh_, e.tet), x);
  }
}

Eigen::Vector3d VisualSurface::embedded_position(Eigen::Index v) const {
  const VisualVertexEmbedding& e = embedding_[static_cast<std::size_t>(v)];
  return (e.barycentric.transpose() * tet_corners(mesh_, e.tet)).transpose();
}

Eigen::Index VisualSurface::num_outside() const {
  return std::count_if(embedding_.begin(), embedding_.end(), [](const VisualVertexEmbedding& e) { return e.distance > 0.0; });
}

double VisualSurface::largest_distance() const {
  double largest = 0.0;
  for (const VisualVertexEmbedding& e : embedding_) largest = std::max(largest, e.distance);
  return largest;
}

TriangleSurface VisualSurface::deform(const VisualDisplacement& u) const {
  TriangleSurface moved = reference_;
  for (Eigen::Index v = 0; v < reference_.num_vertices(); ++v) {
    const Eigen::Vector3d x = row(reference_.vertices, v);
    moved.vertices.row(v) = (x + u(embedding_[static_cast<std::size_t>(v)].tet, x)).transpose();
  }
  return moved;
}

std::vector<int> untorn_triangles(const TriangleSurface& visual, const CutSurfaces& cuts) {
  // Each edge asks the cuts' tree for the triangles near it (their boxes meet its box): the few
  // the exact test then decides, instead of every triangle of a cut that may be long.
  const auto crosses_cut = [&](const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
    for (const CutTriangle& t : cuts.triangles_near_segment(p, q))
      if (segment_crosses_triangle(p, q, t.corners[0], t.corners[1], t.corners[2])) return true;
    return false;
  };
  std::vector<int> keep;
  for (Eigen::Index f = 0; f < visual.num_triangles(); ++f) {
    bool torn = false;
    for (int a = 0; a < 3 && !torn; ++a)
      torn = crosses_cut(row(visual.vertices, visual.triangles(f, a)), row(visual.vertices, visual.triangles(f, (a + 1) % 3)));
    if (!torn) keep.push_back(static_cast<int>(f));
  }
  return keep;
}

TriangleSurface keep_triangles(const TriangleSurface& surface, const std::vector<int>& keep) {
  TriangleSurface kept;
  kept.vertices = surface.vertices;
  kept.triangles.resize(static_cast<Eigen::Index>(keep.size()), 3);
  for (std::size_t i = 0; i < keep.size(); ++i) kept.triangles.row(static_cast<Eigen::Index>(i)) = surface.triangles.row(keep[i]);
  return kept;
}

VisualDisplacement xfem_visual_displacement(const CutXfemModel& model, const Eigen::VectorXd& u) {
  return [&model, &u](int t, const Eigen::Vector3d& x) {
    const Eigen::Vector3d value = model.displacement_at(u, t, x);
    if (!value.hasNaN()) return value;
    // Outside the pieces of a cut tet: the field at the tet's point with the clamped coordinates.
    const Eigen::Matrix<double, 4, 3> X = tet_corners(model.mesh(), t);
    Eigen::Vector4d lambda = barycentric_in(X, x).cwiseMax(0.0);
    lambda /= lambda.sum();
    return Eigen::Vector3d(model.displacement_at(u, t, (lambda.transpose() * X).transpose()));
  };
}

} // namespace kerf
