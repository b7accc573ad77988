#include "kerf/quadrature/front_quadrature.hpp"

#include "kerf/cut/convex_cell.hpp"
#include "kerf/fem/tet_quadrature.hpp"
#include "kerf/quadrature/gauss_piece_rules.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <limits>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace kerf {

namespace {

// n Gauss-Legendre points and weights on [0, 1].
struct Line {
  std::vector<double> x, w;
  explicit Line(int n, int alpha = 0) { gauss_jacobi_01(n, alpha, x, w); }
};

double tet_volume(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2, const Eigen::Vector3d& p3) {
  return std::abs((p1 - p0).cross(p2 - p0).dot(p3 - p0)) / 6.0;
}

// The tet (q0, q1, P2, P3) with its edge q0 q1 on the front: x = (1 - rho) A(s) + rho B(t),
// rho = sigma^2, dV = 6 V rho (1 - rho) 2 sigma dsigma ds dt.
void append_edge_collapsed(const Eigen::Vector3d& q0, const Eigen::Vector3d& q1, const Eigen::Vector3d& P2,
                           const Eigen::Vector3d& P3, const Line& g, double min_volume, PieceQuadratureRule& rule) {
  const double V = tet_volume(q0, q1, P2, P3);
  if (V <= min_volume) return; // an edge of the face through q1: no volume
  for (std::size_t i = 0; i < g.x.size(); ++i)       // sigma
    for (std::size_t j = 0; j < g.x.size(); ++j)     // s, along the front
      for (std::size_t k = 0; k < g.x.size(); ++k) { // t, along the opposite edge
        const double sigma = g.x[i], rho = sigma * sigma;
        const Eigen::Vector3d A = q0 + g.x[j] * (q1 - q0), B = P2 + g.x[k] * (P3 - P2);
        rule.points.push_back((1.0 - rho) * A + rho * B);
        rule.weights.push_back(g.w[i] * g.w[j] * g.w[k] * 6.0 * V * rho * (1.0 - rho) * 2.0 * sigma);
      }
}

// The tet (q0, P1, P2, P3) with its corner q0 on the front: x = q0 + rho (y(u, v) - q0), y on
// the opposite face by the collapsed map u = a, v = (1 - a) b, rho = sigma^2,
// dV = 6 V rho^2 2 sigma dsigma (1 - a) da db.
void append_corner_collapsed(const Eigen::Vector3d& q0, const Eigen::Vector3d& P1, const Eigen::Vector3d& P2,
                             const Eigen::Vector3d& P3, const Line& g, const Line& g1, double min_volume,
                             PieceQuadratureRule& rule) {
  const double V = tet_volume(q0, P1, P2, P3);
  if (V <= min_volume) return; // a fan triangle of collinear corners
  for (std::size_t i = 0; i < g.x.size(); ++i)
    for (std::size_t j = 0; j < g1.x.size(); ++j)  // a, weight (1 - a) in g1
      for (std::size_t k = 0; k < g.x.size(); ++k) { // b
        const double sigma = g.x[i], rho = sigma * sigma, a = g1.x[j], b = (1.0 - a) * g.x[k];
        const Eigen::Vector3d y = P1 + a * (P2 - P1) + b * (P3 - P1);
        rule.points.push_back(q0 + rho * (y - q0));
        rule.weights.push_back(g.w[i] * g1.w[j] * g.w[k] * 6.0 * V * rho * rho * 2.0 * sigma);
      }
}

// The part of segment [p, q] in the closed convex cell: bounded exactly by the faces it crosses;
// a face it runs along (its distance changing by less than the tolerance) need only be reached
// within the tolerance (a front on a face of the cell, as it is on the cut's and the front's
// planes that split the tet).
std::pair<double, double> clip_segment_to_cell(const ConvexCell& cell, const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                                               double tolerance) {
  double s0 = 0.0, s1 = 1.0;
  for (const CellFace& face : cell.faces) {
    if (face.polygon.size() < 3) continue;
    const Eigen::Vector3d n = polygon_area_vector(face.polygon);
    const double length = n.norm();
    if (length == 0.0) continue;
    const Eigen::Vector3d u = n / length; // outward: inside where f(s) = fp + s (fq - fp) <= 0
    const double fp = u.dot(p - face.polygon[0]), fq = u.dot(q - face.polygon[0]);
    if (std::abs(fq - fp) <= tolerance) {
      if (std::max(fp, fq) > tolerance) return {1.0, 0.0};
      continue;
    }
    const double s = fp / (fp - fq);
    if (fq > fp) s1 = std::min(s1, s);
    else s0 = std::max(s0, s);
  }
  return {s0, s1};
}

// The front's line through a cell: a point and the unit direction.
struct Line3 {
  Eigen::Vector3d point, direction;
  double distance(const Eigen::Vector3d& x) const {
    const Eigen::Vector3d y = x - point;
    return (y - y.dot(direction) * direction).norm();
  }
};

// The direction of the front segment nearest to x (for a cell the front only touches at a point).
Eigen::Vector3d front_direction(const CrackFronts& fronts, const std::vector<FrontPiece>& front, const Eigen::Vector3d& x) {
  double best = std::numeric_limits<double>::infinity();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
  for (const FrontPiece& f : front) {
    const Eigen::Vector3d e = f.end - f.start;
    const double t = std::clamp((x - f.start).dot(e) / e.squaredNorm(), 0.0, 1.0);
    const double d = (x - f.start - t * e).norm();
    if (d < best) {
      best = d;
      direction = fronts.polylines[static_cast<std::size_t>(f.polyline)].segments[static_cast<std::size_t>(f.segment)].c;
    }
  }
  return direction;
}

// The grading. The collapse takes the singularity on the front out of the radial direction, but
// the front can pass close to the rest of a sub-tet (a corner of the tet a little beside the
// front, or the front leaving the tet near an edge of a face): then r^-1/2 is steep, though
// smooth, along the opposite edge or face, and Gauss converges slowly. So the opposite edge
// (face) is split until each part lies at least its own length from the front's line (at most
// 12 times): the parts shrink geometrically towards the near point, and Gauss converges at a
// fixed rate on each. The number of halvings is capped (default_front_grading, 12); where the
// front runs along a face of a cell, the parts near it multiply with every halving, and a cut
// made of many small triangles (chapter 7's sheets) can reach 15 million points in one tet
// with 12: a smaller cap trades that for a coarser rule near the face.

double segment_line_distance(const Line3& line, const Eigen::Vector3d& v, const Eigen::Vector3d& w) {
  // The distance to the line is convex along the segment: a few golden-section steps are
  // plenty for a splitting criterion.
  double a = 0.0, b = 1.0;
  for (int k = 0; k < 40; ++k) {
    const double m1 = a + 0.382 * (b - a), m2 = a + 0.618 * (b - a);
    if (line.distance(v + m1 * (w - v)) < line.distance(v + m2 * (w - v))) b = m2;
    else a = m1;
  }
  return line.distance(v + 0.5 * (a + b) * (w - v));
}

void append_graded_edge(const Line3& line, const Eigen::Vector3d& q0, const Eigen::Vector3d& q1, const Eigen::Vector3d& v,
                        const Eigen::Vector3d& w, const Line& g, double min_volume, int depth, int max_grading, PieceQuadratureRule& rule) {
  if (tet_volume(q0, q1, v, w) <= min_volume) return; // an edge through q1: no volume to grade
  if (depth < max_grading && segment_line_distance(line, v, w) < (w - v).norm()) {
    const Eigen::Vector3d m = 0.5 * (v + w);
    append_graded_edge(line, q0, q1, v, m, g, 0.5 * min_volume, depth + 1, max_grading, rule);
    append_graded_edge(line, q0, q1, m, w, g, 0.5 * min_volume, depth + 1, max_grading, rule);
    return;
  }
  append_edge_collapsed(q0, q1, v, w, g, min_volume, rule);
}

void append_graded_corner(const Line3& line, const Eigen::Vector3d& q0, const Eigen::Vector3d& P1, const Eigen::Vector3d& P2,
                          const Eigen::Vector3d& P3, const Line& g, const Line& g1, double min_volume, int depth, int max_grading,
                          PieceQuadratureRule& rule) {
  if (tet_volume(q0, P1, P2, P3) <= min_volume) return; // a fan triangle of collinear corners
  const double size = std::max({(P2 - P1).norm(), (P3 - P2).norm(), (P1 - P3).norm()});
  // The triangle's distance to the line is at least the smallest of its edges' distances or,
  // when the line's projection crosses it, 0: its edges bound it from below unless the line
  // passes through it, which a face of the cell without q0 and q1 cannot (the cell meets the
  // line in S only).
  const double distance = std::min({segment_line_distance(line, P1, P2), segment_line_distance(line, P2, P3), segment_line_distance(line, P3, P1)});
  if (depth < max_grading && distance < size) {
    const Eigen::Vector3d m12 = 0.5 * (P1 + P2), m23 = 0.5 * (P2 + P3), m31 = 0.5 * (P3 + P1);
    for (const auto& [a, b, c] : {std::array<Eigen::Vector3d, 3>{P1, m12, m31}, std::array<Eigen::Vector3d, 3>{m12, P2, m23},
                                 std::array<Eigen::Vector3d, 3>{m31, m23, P3}, std::array<Eigen::Vector3d, 3>{m12, m23, m31}})
      append_graded_corner(line, q0, a, b, c, g, g1, 0.25 * min_volume, depth + 1, max_grading, rule);
    return;
  }
  append_corner_collapsed(q0, P1, P2, P3, g, g1, min_volume, rule);
}

double distance_to_plane_of(const std::vector<Eigen::Vector3d>& polygon, const Eigen::Vector3d& x) {
  const Eigen::Vector3d n = polygon_area_vector(polygon);
  return std::abs(n.normalized().dot(x - polygon[0]));
}

} // namespace

PieceQuadratureRule front_collapsed_rule(const Eigen::Matrix<double, 4, 3>& X, const TetPieces& pieces, int piece,
                                         const CrackFronts& fronts, int n, int grading) {
  if (n < 1 || n > 8) throw std::invalid_argument("front_collapsed_rule: n must be in 1..8");
  if (grading < 0 || grading > default_front_grading) throw std::invalid_argument("front_collapsed_rule: grading must be in 0..12");
  const Line g(n), g1(n, 1);
  const double tolerance = 1e-10 * pieces.diameter;
  const double min_volume = 1e-14 * pieces.volume;
  const std::vector<FrontPiece> front = front_in_tet(fronts, X);
  PieceQuadratureRule rule;
  for (const int c : pieces.pieces[static_cast<std::size_t>(piece)].cells) {
    const ConvexCell& cell = pieces.cells[static_cast<std::size_t>(c)];
    // The longest piece of the front in this cell (a point if it only touches it).
    bool touches = false;
    Eigen::Vector3d q0 = Eigen::Vector3d::Zero(), q1 = Eigen::Vector3d::Zero();
    double longest = -1.0;
    for (const FrontPiece& f : front) {
      const auto [s0, s1] = clip_segment_to_cell(cell, f.start, f.end, tolerance);
      if (s1 < s0) continue;
      const double length = (s1 - s0) * (f.end - f.start).norm();
      if (length <= longest) continue;
      longest = length;
      touches = true;
      q0 = f.start + s0 * (f.end - f.start);
      q1 = f.start + s1 * (f.end - f.start);
    }
    if (!touches) {
      append_cell_gauss_rule(cell, 2 * n - 1, rule); // away from the front: Gauss on the cell's fan
      continue;
    }
    const bool segment = longest > tolerance;
    const Line3 line{q0, segment ? Eigen::Vector3d((q1 - q0).normalized()) : front_direction(fronts, front, q0)};
    // Cones from q0 over the faces that do not hold it; in a face that holds q1, cones from q1.
    for (const CellFace& face : cell.faces) {
      const std::vector<Eigen::Vector3d>& P = face.polygon;
      if (P.size() < 3 || distance_to_plane_of(P, q0) <= tolerance) continue;
      if (segment && distance_to_plane_of(P, q1) <= tolerance) {
        for (std::size_t k = 0; k < P.size(); ++k) append_graded_edge(line, q0, q1, P[k], P[(k + 1) % P.size()], g, min_volume, 0, grading, rule);
      } else {
        for (std::size_t k = 1; k + 1 < P.size(); ++k) append_graded_corner(line, q0, P[0], P[k], P[k + 1], g, g1, min_volume, 0, grading, rule);
      }
    }
  }
  return rule;
}

namespace {

void append_graded_subtet(const Eigen::Matrix<double, 4, 3>& T, const CrackFronts& fronts, const TetQuadratureRule& gauss, int depth,
                          PieceQuadratureRule& rule) {
  const Eigen::Vector3d centre = T.colwise().mean().transpose();
  double radius = 0.0, diameter = 0.0;
  for (int i = 0; i < 4; ++i) {
    radius = std::max(radius, (T.row(i).transpose() - centre).norm());
    for (int j = i + 1; j < 4; ++j) diameter = std::max(diameter, (T.row(i) - T.row(j)).norm());
  }
  if (depth > 0 && diameter > fronts.distance(centre) - radius) {
    for (const Eigen::Matrix<double, 4, 3>& child : refine_tet(T)) append_graded_subtet(child, fronts, gauss, depth - 1, rule);
    return;
  }
  Eigen::Matrix3d J;
  for (int c = 0; c < 3; ++c) J.col(c) = (T.row(c + 1) - T.row(0)).transpose();
  const double volume_scale = std::abs(J.determinant());
  for (std::size_t q = 0; q < gauss.points.size(); ++q) {
    rule.points.push_back(T.row(0).transpose() + J * gauss.points[q]);
    rule.weights.push_back(gauss.weights[q] * volume_scale);
  }
}

} // namespace

PieceQuadratureRule near_front_graded_rule(const TetPieces& pieces, int piece, const CrackFronts& fronts, int degree, int max_depth) {
  if (max_depth < 0) throw std::invalid_argument("near_front_graded_rule: max_depth must be >= 0");
  const TetQuadratureRule gauss = tet_quadrature_rule(degree);
  PieceQuadratureRule rule;
  for (const int c : pieces.pieces[static_cast<std::size_t>(piece)].cells)
    for (const Eigen::Matrix<double, 4, 3>& T : convex_cell_tetrahedra(pieces.cells[static_cast<std::size_t>(c)]))
      append_graded_subtet(T, fronts, gauss, max_depth, rule);
  return rule;
}

} // namespace kerf
