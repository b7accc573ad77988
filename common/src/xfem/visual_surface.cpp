#include "kerf/xfem/visual_surface.hpp"

#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/mesh/point_locator.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <optional>
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

/// Where a cut first crosses the segment p q: the parameter s of p + s (q - p), and the plane of
/// the cut triangle it crosses there (unit normal, a point).
struct SegmentCrossing {
  double s;
  Eigen::Vector3d normal, point;
};

/// The first cut triangle the segment p q crosses, if any. The segment asks the cuts' tree for
/// the triangles near it (their boxes meet its box): the few the exact test then decides,
/// instead of every triangle of a cut that may be long.
std::optional<SegmentCrossing> first_crossing(const CutSurfaces& cuts, const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
  for (const CutTriangle& t : cuts.triangles_near_segment(p, q))
    if (segment_crosses_triangle(p, q, t.corners[0], t.corners[1], t.corners[2])) {
      const double h_p = orientation(t.corners[0], t.corners[1], t.corners[2], p);
      const double h_q = orientation(t.corners[0], t.corners[1], t.corners[2], q);
      return SegmentCrossing{h_p / (h_p - h_q), (t.corners[1] - t.corners[0]).cross(t.corners[2] - t.corners[0]).normalized(),
                             t.corners[0]};
    }
  return std::nullopt;
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
  const auto crosses_cut = [&](const Eigen::Vector3d& p, const Eigen::Vector3d& q) { return first_crossing(cuts, p, q).has_value(); };
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

CutSkin::CutSkin(const VisualSurface& visual, const CutSurfaces& cuts, const PointLocator& locator) : visual_(visual) {
  const TriangleSurface& skin = visual.reference();
  // Where a point p of the side of vertex w moves: as the field at p pushed into the body (the
  // fine skin pokes out between the tets' corners, and a tet's field extrapolated to a point
  // outside it is taken at its nearest point, which near a cut may lie across it), along the
  // skin's inward normal n_in made parallel to the cut. The push is twice the farthest any skin
  // vertex lies out, or half, a quarter, an eighth of that, or none: the first whose point lies
  // in a tet and is joined to w by a segment that crosses no cut triangle (the sheet is not
  // flat, and the push must keep the side). None if no such point is found.
  const double inward = 2.0 * visual.largest_distance();
  const auto follower = [&](const Eigen::Vector3d& p, Eigen::Index w, const SegmentCrossing& c, const Eigen::Vector3d& n_in) -> std::optional<Follower> {
    const Eigen::Vector3d along = n_in - n_in.dot(c.normal) * c.normal;
    const Eigen::Vector3d direction = along.norm() > 1e-3 ? Eigen::Vector3d(along.normalized()) : Eigen::Vector3d::Zero();
    const Eigen::Vector3d x_w = row(skin.vertices, w);
    for (const double push : {inward, 0.5 * inward, 0.25 * inward, 0.125 * inward, 0.0}) {
      const Eigen::Vector3d at = p + push * direction;
      if (first_crossing(cuts, x_w, at)) continue;
      const PointLocation where = locator.locate(at);
      if (where.tet >= 0) return Follower{static_cast<int>(where.tet), at};
    }
    return std::nullopt;
  };
  // A vertex of a split triangle follows its side (a follower, if one is found; else as
  // VisualSurface moves it). The point X of edge (a, b) where the cut crosses it, for the side of
  // its vertex w: a follower from a quarter of the way from X to w (off the cut by more than
  // round-off), else as w moves.
  std::vector<char> seen(static_cast<std::size_t>(skin.num_vertices()), 0);
  const auto follow_vertex = [&](Eigen::Index w, const SegmentCrossing& c, const Eigen::Vector3d& n_in) {
    if (seen[static_cast<std::size_t>(w)]) return;
    seen[static_cast<std::size_t>(w)] = 1;
    if (const auto f = follower(row(skin.vertices, w), w, c, n_in)) vertex_followers_.emplace_back(static_cast<int>(w), *f);
  };
  // The two triangles that share a crossed edge share its point for each side, so that each
  // side's skin stays closed along the rim.
  std::map<std::array<Eigen::Index, 3>, int> rim_index; // (lower end, higher end, side's vertex) -> vertex
  const auto rim_point = [&](const SegmentCrossing& c, Eigen::Index a, Eigen::Index b, Eigen::Index w, const Eigen::Vector3d& n_in) {
    const auto [known, added] = rim_index.try_emplace({std::min(a, b), std::max(a, b), w}, 0);
    if (!added) return known->second;
    const Eigen::Vector3d x_a = row(skin.vertices, a), X = x_a + c.s * (row(skin.vertices, b) - x_a);
    rim_.push_back({X, follower(X + 0.25 * (row(skin.vertices, w) - X), w, c, n_in), static_cast<int>(w)});
    return known->second = static_cast<int>(skin.num_vertices()) + static_cast<int>(rim_.size()) - 1;
  };
  for (Eigen::Index f = 0; f < skin.num_triangles(); ++f) {
    std::array<Eigen::Index, 3> c{skin.triangles(f, 0), skin.triangles(f, 1), skin.triangles(f, 2)};
    std::array<std::optional<SegmentCrossing>, 3> s; // edge k from corner k to corner k + 1
    int crossed = 0;
    for (int k = 0; k < 3; ++k) crossed += (s[k] = first_crossing(cuts, row(skin.vertices, c[k]), row(skin.vertices, c[(k + 1) % 3]))).has_value();
    if (crossed == 0) {
      untorn_.push_back(static_cast<int>(f));
      continue;
    }
    if (crossed != 2) {
      ++dropped_;
      continue;
    }
    // The corner both crossed edges meet, w0, alone on its side; w1 and w2 on the other. The
    // cut meets w0 w1 at P and w2 w0 at Q.
    const int k = !s[0] ? 2 : !s[1] ? 0 : 1; // the uncrossed edge, w1 w2, is edge (k + 1) % 3
    const Eigen::Index w0 = c[k], w1 = c[(k + 1) % 3], w2 = c[(k + 2) % 3];
    const Eigen::Vector3d x0 = row(skin.vertices, w0), x1 = row(skin.vertices, w1), x2 = row(skin.vertices, w2);
    const Eigen::Vector3d n_in = -(x1 - x0).cross(x2 - x0).normalized(); // the skin is oriented outwards
    const SegmentCrossing& P = *s[k];           // on w0 w1
    const SegmentCrossing& Q = *s[(k + 2) % 3]; // on w2 w0
    follow_vertex(w0, P, n_in), follow_vertex(w1, P, n_in), follow_vertex(w2, Q, n_in);
    const int P0 = rim_point(P, w0, w1, w0, n_in), P1 = rim_point(P, w0, w1, w1, n_in);
    const int Q0 = rim_point(Q, w2, w0, w0, n_in), Q1 = rim_point(Q, w2, w0, w2, n_in);
    const int v0 = static_cast<int>(w0), v1 = static_cast<int>(w1), v2 = static_cast<int>(w2);
    // The original's orientation kept: w0 P Q on one side, P w1 w2 and P w2 Q on the other.
    split_.insert(split_.end(), {Eigen::Vector3i(v0, P0, Q0), Eigen::Vector3i(P1, v1, v2), Eigen::Vector3i(P1, v2, Q1)});
  }
}

TriangleSurface CutSkin::deform(const VisualDisplacement& u) const {
  const TriangleSurface& reference = visual_.reference();
  TriangleSurface skin = visual_.deform(u);
  for (const auto& [w, f] : vertex_followers_) skin.vertices.row(w) = (row(reference.vertices, w) + u(f.tet, f.at)).transpose();
  const Eigen::Index n = skin.num_vertices();
  skin.vertices.conservativeResize(n + static_cast<Eigen::Index>(rim_.size()), 3);
  for (std::size_t k = 0; k < rim_.size(); ++k) {
    const RimPoint& r = rim_[k];
    const Eigen::Vector3d u_r = r.follower ? u(r.follower->tet, r.follower->at) : Eigen::Vector3d(row(skin.vertices, r.w) - row(reference.vertices, r.w));
    skin.vertices.row(n + static_cast<Eigen::Index>(k)) = (r.X + u_r).transpose();
  }
  skin.triangles.resize(static_cast<Eigen::Index>(untorn_.size() + split_.size()), 3);
  Eigen::Index row_index = 0;
  for (const int f : untorn_) skin.triangles.row(row_index++) = reference.triangles.row(f);
  for (const Eigen::Vector3i& t : split_) skin.triangles.row(row_index++) = t.transpose();
  return skin;
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
