#include "kerf/cut/crack_front.hpp"

#include "kerf/cut/point_side.hpp"
#include "kerf/mesh/boundary_faces.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace kerf {

namespace {

constexpr double barycentric_tolerance = 1e-10;

// A boundary edge of a cut surface, oriented as its triangle walks it.
struct BoundaryEdge {
  int surface = 0, triangle = 0;
  int from = 0, to = 0, opposite = 0; // surface vertex indices
};

std::vector<BoundaryEdge> boundary_edges(const TriangleSurface& surface, int s) {
  std::map<std::pair<int, int>, std::vector<std::array<int, 4>>> edges; // key sorted pair: (triangle, from, to, opposite)
  for (Eigen::Index f = 0; f < surface.num_triangles(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int i = surface.triangles(f, k), j = surface.triangles(f, (k + 1) % 3), o = surface.triangles(f, (k + 2) % 3);
      edges[{std::min(i, j), std::max(i, j)}].push_back({static_cast<int>(f), i, j, o});
    }
  std::vector<BoundaryEdge> result;
  for (const auto& [key, list] : edges)
    if (list.size() == 1) result.push_back({s, list[0][0], list[0][1], list[0][2], list[0][3]});
  return result;
}

// The parameter interval [s0, s1] of p + s (q - p), s in [0, 1], inside the closed tet X, or an
// empty interval (s0 > s1). A face the segment runs (nearly) parallel to, its barycentric
// coordinate changing by less than the tolerance along it, only has to be reached within the
// tolerance (a front lying in a face belongs to the tets on both sides); a face it crosses
// bounds it exactly, so that the ends of a front on the mesh's skin lie on the skin.
std::pair<double, double> clip_segment_to_tet(const Eigen::Matrix<double, 4, 3>& X, const Eigen::Vector3d& p,
                                              const Eigen::Vector3d& q) {
  Eigen::Matrix3d J;
  for (int k = 0; k < 3; ++k) J.col(k) = (X.row(k + 1) - X.row(0)).transpose();
  const Eigen::Matrix3d Jinv = J.inverse();
  const Eigen::Vector3d xi_p = Jinv * (p - X.row(0).transpose()), xi_q = Jinv * (q - X.row(0).transpose());
  // Barycentric coordinates lambda_k(s) = l0_k + s (l1_k - l0_k).
  const Eigen::Vector4d l0(1.0 - xi_p.sum(), xi_p(0), xi_p(1), xi_p(2));
  const Eigen::Vector4d l1(1.0 - xi_q.sum(), xi_q(0), xi_q(1), xi_q(2));
  double s0 = 0.0, s1 = 1.0;
  for (int k = 0; k < 4; ++k) {
    const double d = l1(k) - l0(k);
    if (std::abs(d) <= barycentric_tolerance) {
      if (std::min(l0(k), l1(k)) < -barycentric_tolerance) return {1.0, 0.0};
      continue;
    }
    const double s = -l0(k) / d;
    if (d > 0.0) s0 = std::max(s0, s);
    else s1 = std::min(s1, s);
  }
  return {s0, s1};
}

// The frame of a segment of edge (from -> to) of a triangle with the third vertex `opposite`.
FrontSegment make_segment(const Eigen::Vector3d& start, const Eigen::Vector3d& end, const Eigen::Vector3d& normal,
                          const Eigen::Vector3d& opposite, int surface, int triangle) {
  FrontSegment s;
  s.surface = surface;
  s.triangle = triangle;
  s.b = normal.normalized();
  s.c = (end - start).normalized();
  s.a = s.b.cross(s.c);
  s.start = start;
  s.end = end;
  // a must point ahead, away from the triangle (Moes et al. 1999): else flip a and c together.
  if (s.a.dot(start - opposite) < 0.0) {
    s.a = -s.a;
    s.c = -s.c;
    std::swap(s.start, s.end);
  }
  return s;
}

struct Piece {
  FrontSegment segment;
  int start_key = -1, end_key = -1; // chain keys: a surface vertex, or a unique key for a clipped end
};

Eigen::Vector3d unit_or(const Eigen::Vector3d& v, const Eigen::Vector3d& fallback) {
  const double n = v.norm();
  return n > 0.0 ? Eigen::Vector3d(v / n) : fallback;
}

void add_vertex_frames(FrontPolyline& line) {
  const std::size_t m = line.segments.size();
  line.tangents.assign(m + 1, Eigen::Vector3d::Zero());
  line.normals.assign(m + 1, Eigen::Vector3d::Zero());
  for (std::size_t v = 0; v <= m; ++v) {
    const bool has_before = v > 0 || line.closed, has_after = v < m || line.closed;
    const FrontSegment& before = line.segments[v > 0 ? v - 1 : m - 1];
    const FrontSegment& after = line.segments[v < m ? v : 0];
    Eigen::Vector3d c = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero();
    if (has_before) c += before.c, b += before.b;
    if (has_after) c += after.c, b += after.b;
    c = unit_or(c, has_after ? after.c : before.c);
    b = unit_or(b - b.dot(c) * c, has_after ? after.b : before.b);
    line.tangents[v] = c;
    line.normals[v] = b;
  }
}

} // namespace

int CrackFronts::num_segments() const {
  int n = 0;
  for (const FrontPolyline& line : polylines) n += static_cast<int>(line.segments.size());
  return n;
}

double CrackFronts::length() const {
  double L = 0.0;
  for (const FrontPolyline& line : polylines)
    for (const FrontSegment& s : line.segments) L += (s.end - s.start).norm();
  return L;
}

double CrackFronts::distance(const Eigen::Vector3d& x) const {
  double best = std::numeric_limits<double>::infinity();
  for (const FrontPolyline& line : polylines)
    for (const FrontSegment& s : line.segments) {
      const Eigen::Vector3d e = s.end - s.start;
      const double t = std::clamp((x - s.start).dot(e) / e.squaredNorm(), 0.0, 1.0);
      best = std::min(best, (x - s.start - t * e).norm());
    }
  return best;
}

FrontPolar CrackFronts::polar(const Eigen::Vector3d& x, int cut_side) const {
  if (polylines.empty()) throw std::logic_error("CrackFronts::polar: there is no front");
  FrontPolar best;
  double best_distance = std::numeric_limits<double>::infinity(), best_t = 0.0;
  bool by_tangent = true; // the foot solves (x - gamma(t)) . c(t) = 0 (false: the fallback below)
  const auto consider = [&](int l, int k, double t) {
    const FrontPolyline& line = polylines[static_cast<std::size_t>(l)];
    const FrontSegment& s = line.segments[static_cast<std::size_t>(k)];
    const Eigen::Vector3d foot = s.start + t * (s.end - s.start);
    const double d = (x - foot).norm();
    if (d >= best_distance) return;
    const double w = std::clamp(t, 0.0, 1.0); // beyond an open end the end's frame holds
    const Eigen::Vector3d c = unit_or((1.0 - w) * line.tangents[static_cast<std::size_t>(k)] +
                                          w * line.tangents[static_cast<std::size_t>(k) + 1], s.c);
    Eigen::Vector3d b = (1.0 - w) * line.normals[static_cast<std::size_t>(k)] + w * line.normals[static_cast<std::size_t>(k) + 1];
    b = unit_or(b - b.dot(c) * c, s.b);
    best_distance = d;
    best.foot = foot;
    best.c = c;
    best.b = b;
    best.a = b.cross(c);
    best.polyline = l;
    best.segment = k;
    best_t = t;
  };
  for (std::size_t l = 0; l < polylines.size(); ++l) {
    const FrontPolyline& line = polylines[l];
    const std::size_t m = line.segments.size();
    for (std::size_t k = 0; k < m; ++k) {
      const FrontSegment& s = line.segments[k];
      // q(t) = (d - t e) . (c0 + t (c1 - c0)) = q0 + q1 t + q2 t^2: x - gamma(t) perpendicular to
      // the (unnormalised) interpolated tangent.
      const Eigen::Vector3d d = x - s.start, e = s.end - s.start;
      const Eigen::Vector3d c0 = line.tangents[k], dc = line.tangents[k + 1] - line.tangents[k];
      const double q0 = d.dot(c0), q1 = d.dot(dc) - e.dot(c0), q2 = -e.dot(dc);
      const bool open_start = !line.closed && k == 0, open_end = !line.closed && k + 1 == m;
      const auto accept = [&](double t) {
        const double slack = 1e-12;
        if ((t >= -slack || open_start) && (t <= 1.0 + slack || open_end)) consider(static_cast<int>(l), static_cast<int>(k), t);
      };
      if (std::abs(q2) <= 1e-14 * std::abs(q1)) {
        if (q1 != 0.0) accept(-q0 / q1);
      } else {
        const double disc = q1 * q1 - 4.0 * q2 * q0;
        if (disc >= 0.0) {
          // The stable pair of roots (no cancellation).
          const double h = -0.5 * (q1 + std::copysign(std::sqrt(disc), q1));
          accept(h / q2);
          if (h != 0.0) accept(q0 / h);
        }
      }
    }
  }
  if (best.polyline < 0) {
    // No foot (possible on a closed front far from it): the closest point of the nearest segment.
    by_tangent = false;
    for (std::size_t l = 0; l < polylines.size(); ++l)
      for (std::size_t k = 0; k < polylines[l].segments.size(); ++k) {
        const FrontSegment& s = polylines[l].segments[k];
        const Eigen::Vector3d e = s.end - s.start;
        consider(static_cast<int>(l), static_cast<int>(k), std::clamp((x - s.start).dot(e) / e.squaredNorm(), 0.0, 1.0));
      }
  }
  const Eigen::Vector3d y = x - best.foot;
  best.x_a = y.dot(best.a);
  best.x_b = y.dot(best.b);
  best.r = std::hypot(best.x_a, best.x_b);
  // atan2 in (-pi, pi]: a point on the cut's plane behind the front (x_b = -0.0) gets +pi, not
  // -pi, so that the result does not depend on the sign of a zero.
  best.theta = best.x_b == 0.0 && best.x_a < 0.0 ? std::numbers::pi : std::atan2(best.x_b, best.x_a);
  if (cut_side != 0) best.theta = cut_side > 0 ? std::numbers::pi : -std::numbers::pi;

  // The gradients of x_a and x_b. The foot parameter t(x) solves q = (x - gamma(t)) . c^(t) = 0
  // with c^(t) = c0 + t (c1 - c0), so grad t = -c^ / (dq/dt), dq/dt = -e . c^ + y . (c1 - c0), and
  //   grad x_a = a + (-e . a + y . da/dt) grad t,   grad x_b = b + (-e . b + y . db/dt) grad t.
  // On a straight front (c1 = c0, b1 = b0) both corrections vanish: grad x_a = a, grad x_b = b.
  best.grad_x_a = best.a;
  best.grad_x_b = best.b;
  if (by_tangent) {
    const FrontPolyline& line = polylines[static_cast<std::size_t>(best.polyline)];
    const std::size_t k = static_cast<std::size_t>(best.segment);
    const Eigen::Vector3d e = line.segments[k].end - line.segments[k].start;
    const Eigen::Vector3d dc_hat = line.tangents[k + 1] - line.tangents[k];
    const Eigen::Vector3d c_hat = line.tangents[k] + best_t * dc_hat;
    const double dq_dt = -e.dot(c_hat) + y.dot(dc_hat);
    if (dq_dt != 0.0) {
      const Eigen::Vector3d grad_t = -c_hat / dq_dt;
      Eigen::Vector3d da = Eigen::Vector3d::Zero(), db = Eigen::Vector3d::Zero();
      if (best_t >= 0.0 && best_t <= 1.0) {
        // The interpolated frame's derivative (beyond an open end the frame is constant):
        // c = c^ / |c^|, b = b~ / |b~| with b~ = b^ - (b^ . c) c, b^ = b0 + t (b1 - b0), a = b x c.
        const double c_norm = c_hat.norm();
        const Eigen::Vector3d& c = best.c;
        const Eigen::Vector3d dc = (dc_hat - c.dot(dc_hat) * c) / c_norm;
        const Eigen::Vector3d db_hat = line.normals[k + 1] - line.normals[k];
        const Eigen::Vector3d b_hat = line.normals[k] + best_t * db_hat;
        const Eigen::Vector3d b_tilde = b_hat - b_hat.dot(c) * c;
        const Eigen::Vector3d db_tilde = db_hat - (db_hat.dot(c) + b_hat.dot(dc)) * c - b_hat.dot(c) * dc;
        db = (db_tilde - best.b.dot(db_tilde) * best.b) / b_tilde.norm();
        da = db.cross(c) + best.b.cross(dc);
      }
      best.grad_x_a += (-e.dot(best.a) + y.dot(da)) * grad_t;
      best.grad_x_b += (-e.dot(best.b) + y.dot(db)) * grad_t;
    }
  }
  return best;
}

std::vector<FrontPiece> front_in_tet(const CrackFronts& fronts, const Eigen::Matrix<double, 4, 3>& X) {
  std::vector<FrontPiece> result;
  const double size = (X.colwise().maxCoeff() - X.colwise().minCoeff()).norm();
  for (std::size_t l = 0; l < fronts.polylines.size(); ++l)
    for (std::size_t k = 0; k < fronts.polylines[l].segments.size(); ++k) {
      const FrontSegment& s = fronts.polylines[l].segments[k];
      const auto [s0, s1] = clip_segment_to_tet(X, s.start, s.end);
      if (!((s1 - s0) * (s.end - s.start).norm() > barycentric_tolerance * size)) continue;
      result.push_back({s.start + s0 * (s.end - s.start), s.start + s1 * (s.end - s.start), static_cast<int>(l), static_cast<int>(k)});
    }
  return result;
}

CrackFronts find_crack_fronts(const TetMesh& mesh, const CutSurfaces& cuts) {
  // The mesh's skin as a triangle surface, for closest_surface_point.
  const BoundaryFaces boundary = boundary_faces(mesh);
  TriangleSurface skin;
  skin.vertices = mesh.nodes;
  skin.triangles = boundary.faces.leftCols(3);
  // The tets' boxes, for a cheap rejection before the exact clipping.
  const Eigen::Index T = mesh.num_tets();
  std::vector<Eigen::Vector3d> low(static_cast<std::size_t>(T)), high(static_cast<std::size_t>(T));
  std::vector<double> size(static_cast<std::size_t>(T));
  for (Eigen::Index t = 0; t < T; ++t) {
    const Eigen::Matrix<double, 4, 3> X = tet_corners(mesh, t);
    low[static_cast<std::size_t>(t)] = X.colwise().minCoeff().transpose();
    high[static_cast<std::size_t>(t)] = X.colwise().maxCoeff().transpose();
    size[static_cast<std::size_t>(t)] = (high[static_cast<std::size_t>(t)] - low[static_cast<std::size_t>(t)]).norm();
  }

  // Chain keys: surface s's vertex v is key_offset[s] + v; an end made by clipping (where the
  // front leaves the mesh) gets a key of its own, from next_key on.
  std::vector<Piece> pieces;
  std::vector<int> key_offset(static_cast<std::size_t>(cuts.num_surfaces()) + 1, 0);
  for (int s = 0; s < cuts.num_surfaces(); ++s)
    key_offset[static_cast<std::size_t>(s) + 1] = key_offset[static_cast<std::size_t>(s)] + static_cast<int>(cuts.surface(s).num_vertices());
  int next_key = key_offset.back();

  for (int s = 0; s < cuts.num_surfaces(); ++s) {
    const TriangleSurface& surface = cuts.surface(s);
    for (const BoundaryEdge& edge : boundary_edges(surface, s)) {
      const Eigen::Vector3d p = surface.vertices.row(edge.from).transpose(), q = surface.vertices.row(edge.to).transpose();
      const Eigen::Vector3d lo = p.cwiseMin(q), hi = p.cwiseMax(q);
      std::vector<std::pair<double, double>> inside;
      for (Eigen::Index t = 0; t < T; ++t) {
        const double slack = 1e-10 * size[static_cast<std::size_t>(t)];
        if ((lo.array() > high[static_cast<std::size_t>(t)].array() + slack).any() ||
            (hi.array() < low[static_cast<std::size_t>(t)].array() - slack).any())
          continue;
        const auto [s0, s1] = clip_segment_to_tet(tet_corners(mesh, t), p, q);
        if (!((s1 - s0) * (q - p).norm() > barycentric_tolerance * size[static_cast<std::size_t>(t)])) continue;
        // A piece in the mesh's skin is where the cut is open, not a front.
        const Eigen::Vector3d middle = p + 0.5 * (s0 + s1) * (q - p);
        if (closest_surface_point(skin, middle).distance <= barycentric_tolerance * size[static_cast<std::size_t>(t)]) continue;
        inside.emplace_back(std::max(s0, 0.0), std::min(s1, 1.0));
      }
      if (inside.empty()) continue;
      std::sort(inside.begin(), inside.end());
      std::vector<std::pair<double, double>> merged{inside[0]};
      for (std::size_t k = 1; k < inside.size(); ++k) {
        if (inside[k].first <= merged.back().second + 1e-9) merged.back().second = std::max(merged.back().second, inside[k].second);
        else merged.push_back(inside[k]);
      }
      const Eigen::Vector3d tri_normal =
          (surface.vertices.row(surface.triangles(edge.triangle, 1)) - surface.vertices.row(surface.triangles(edge.triangle, 0)))
              .cross(surface.vertices.row(surface.triangles(edge.triangle, 2)) - surface.vertices.row(surface.triangles(edge.triangle, 0)))
              .transpose();
      const Eigen::Vector3d opposite = surface.vertices.row(edge.opposite).transpose();
      for (auto [s0, s1] : merged) {
        // Ends within round-off of the edge's ends are its vertices, so that chains join.
        if (s0 < 1e-9) s0 = 0.0;
        if (s1 > 1.0 - 1e-9) s1 = 1.0;
        Piece piece;
        const Eigen::Vector3d from = p + s0 * (q - p), to = p + s1 * (q - p);
        piece.segment = make_segment(s0 == 0.0 ? p : from, s1 == 1.0 ? q : to, tri_normal, opposite, s, edge.triangle);
        int key_from = s0 == 0.0 ? key_offset[static_cast<std::size_t>(s)] + edge.from : next_key++;
        int key_to = s1 == 1.0 ? key_offset[static_cast<std::size_t>(s)] + edge.to : next_key++;
        // make_segment may have swapped the ends to orient c.
        if ((piece.segment.start - (s0 == 0.0 ? p : from)).squaredNorm() != 0.0) std::swap(key_from, key_to);
        piece.start_key = key_from;
        piece.end_key = key_to;
        pieces.push_back(piece);
      }
    }
  }

  // Chain the pieces through shared keys: a key with exactly one piece starting and one ending
  // there joins them.
  std::map<int, std::vector<int>> starting, ending;
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    starting[pieces[k].start_key].push_back(static_cast<int>(k));
    ending[pieces[k].end_key].push_back(static_cast<int>(k));
  }
  // The piece that continues piece k through its end (forward) or start (backward), -1 if the
  // chain ends there (no piece, or a vertex where more than two front edges meet).
  const auto next = [&](int k, bool forward) {
    const Piece& piece = pieces[static_cast<std::size_t>(k)];
    const int key = forward ? piece.end_key : piece.start_key;
    const auto s = starting.find(key);
    const auto e = ending.find(key);
    if (s == starting.end() || e == ending.end() || s->second.size() != 1 || e->second.size() != 1) return -1;
    return forward ? s->second[0] : e->second[0];
  };
  CrackFronts fronts;
  std::vector<char> used(pieces.size(), 0);
  for (std::size_t first = 0; first < pieces.size(); ++first) {
    if (used[first]) continue;
    // Walk back to the start of the chain (or once round a loop).
    int start = static_cast<int>(first);
    for (int back = next(start, false); back >= 0 && back != static_cast<int>(first); back = next(back, false)) start = back;
    FrontPolyline line;
    int k = start;
    do {
      used[static_cast<std::size_t>(k)] = 1;
      line.segments.push_back(pieces[static_cast<std::size_t>(k)].segment);
      k = next(k, true);
    } while (k >= 0 && !used[static_cast<std::size_t>(k)]);
    line.closed = k == start;
    line.points.push_back(line.segments.front().start);
    for (const FrontSegment& s : line.segments) line.points.push_back(s.end);
    add_vertex_frames(line);
    fronts.polylines.push_back(std::move(line));
  }
  return fronts;
}

} // namespace kerf
