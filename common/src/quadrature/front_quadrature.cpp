#include "kerf/quadrature/front_quadrature.hpp"

#include "kerf/cut/convex_cell.hpp"
#include "kerf/fem/tet_quadrature.hpp"
#include "kerf/quadrature/gauss_piece_rules.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <stdexcept>
#include <vector>

namespace kerf {

namespace {

// n Gauss-Legendre points and weights on [0, 1] (alpha = 1: for the weight 1 - x).
struct Line {
  std::vector<double> x, w;
  explicit Line(int n, int alpha = 0) { gauss_jacobi_01(n, alpha, x, w); }
};

double tet_volume(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2, const Eigen::Vector3d& p3) {
  return std::abs((p1 - p0).cross(p2 - p0).dot(p3 - p0)) / 6.0;
}

// The points of the tet (q0, q1, P2, P3) with its edge q0 q1 on the front:
// x = (1 - rho) A(s) + rho B(t), A(s) = q0 + s (q1 - q0), B(t) = P2 + t (P3 - P2), rho = sigma^2,
// dV = 6 V rho (1 - rho) 2 sigma dsigma ds dt; `along` the Gauss points in s.
template <class Visit>
void for_each_edge_collapsed_point(const Eigen::Vector3d& q0, const Eigen::Vector3d& q1, const Eigen::Vector3d& P2,
                                   const Eigen::Vector3d& P3, const Line& g, const Line& along, Visit&& visit) {
  const double V = tet_volume(q0, q1, P2, P3);
  for (std::size_t i = 0; i < g.x.size(); ++i)         // sigma
    for (std::size_t j = 0; j < along.x.size(); ++j)   // s, along the front
      for (std::size_t k = 0; k < g.x.size(); ++k) {   // t, along the opposite edge
        const double sigma = g.x[i], rho = sigma * sigma;
        const Eigen::Vector3d A = q0 + along.x[j] * (q1 - q0), B = P2 + g.x[k] * (P3 - P2);
        visit(Eigen::Vector3d((1.0 - rho) * A + rho * B), g.w[i] * along.w[j] * g.w[k] * 6.0 * V * rho * (1.0 - rho) * 2.0 * sigma);
      }
}

// The points of the tet (q0, P1, P2, P3) with its corner q0 on the front:
// x = q0 + rho (y(u, v) - q0), y on the opposite face by the collapsed map u = a, v = (1 - a) b,
// rho = sigma^2, dV = 6 V rho^2 2 sigma dsigma (1 - a) da db.
template <class Visit>
void for_each_corner_collapsed_point(const Eigen::Vector3d& q0, const Eigen::Vector3d& P1, const Eigen::Vector3d& P2,
                                     const Eigen::Vector3d& P3, const Line& g, const Line& g1, Visit&& visit) {
  const double V = tet_volume(q0, P1, P2, P3);
  for (std::size_t i = 0; i < g.x.size(); ++i)
    for (std::size_t j = 0; j < g1.x.size(); ++j)  // a, weight (1 - a) in g1
      for (std::size_t k = 0; k < g.x.size(); ++k) { // b
        const double sigma = g.x[i], rho = sigma * sigma, a = g1.x[j], b = (1.0 - a) * g.x[k];
        const Eigen::Vector3d y = P1 + a * (P2 - P1) + b * (P3 - P1);
        visit(Eigen::Vector3d(q0 + rho * (y - q0)), g.w[i] * g1.w[j] * g.w[k] * 6.0 * V * rho * rho * 2.0 * sigma);
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

double distance_to_plane_of(const std::vector<Eigen::Vector3d>& polygon, const Eigen::Vector3d& x) {
  const Eigen::Vector3d n = polygon_area_vector(polygon);
  return std::abs(n.normalized().dot(x - polygon[0]));
}

// The front segments that can be nearest to a point of a region: those whose distance to its
// centre is at most the nearest one's plus twice the region's radius (the triangle inequality).
// The distance of the region's points to the front is then the distance to these alone: the
// blending rules ask it for every sub-tet, and a front of many short segments has hundreds.
class NearbyFront {
public:
  NearbyFront(const CrackFronts& fronts, const Eigen::Vector3d& centre, double radius) {
    double nearest = std::numeric_limits<double>::infinity();
    std::vector<std::pair<double, const FrontSegment*>> all;
    for (const FrontPolyline& line : fronts.polylines)
      for (const FrontSegment& s : line.segments) {
        all.push_back({segment_distance(s, centre), &s});
        nearest = std::min(nearest, all.back().first);
      }
    for (const auto& [d, s] : all)
      if (d <= nearest + 2.0 * radius) segments_.push_back(s);
  }
  double distance(const Eigen::Vector3d& x) const {
    double best = std::numeric_limits<double>::infinity();
    for (const FrontSegment* s : segments_) best = std::min(best, segment_distance(*s, x));
    return best;
  }

private:
  static double segment_distance(const FrontSegment& s, const Eigen::Vector3d& x) {
    const Eigen::Vector3d e = s.end - s.start;
    const double t = std::clamp((x - s.start).dot(e) / e.squaredNorm(), 0.0, 1.0);
    return (x - s.start - t * e).norm();
  }
  std::vector<const FrontSegment*> segments_;
};

// The Gauss rule with n points per direction of a tet of any size: the degree 2 n - 1 rule
// (tet_quadrature_rule's collapsed product), mapped.
void append_gauss_tet(const Eigen::Matrix<double, 4, 3>& T, const TetQuadratureRule& gauss, PieceQuadratureRule& rule) {
  Eigen::Matrix3d J;
  for (int c = 0; c < 3; ++c) J.col(c) = (T.row(c + 1) - T.row(0)).transpose();
  const double volume_scale = std::abs(J.determinant());
  if (volume_scale == 0.0) return; // a fan tet of collinear corners: no volume
  for (std::size_t q = 0; q < gauss.points.size(); ++q) {
    rule.points.push_back(T.row(0).transpose() + J * gauss.points[q]);
    rule.weights.push_back(gauss.weights[q] * volume_scale);
  }
}

struct SubtetSize {
  Eigen::Vector3d centre;
  double radius = 0.0, diameter = 0.0;
  explicit SubtetSize(const Eigen::Matrix<double, 4, 3>& T) : centre(T.colwise().mean().transpose()) {
    for (int i = 0; i < 4; ++i) {
      radius = std::max(radius, (T.row(i).transpose() - centre).norm());
      for (int j = i + 1; j < 4; ++j) diameter = std::max(diameter, (T.row(i) - T.row(j)).norm());
    }
  }
};

// One collapsed sub-tet of the rule: the cone from the corner q0 on the front over the triangle
// (c0, c1, c2), or (edge) the tet (q0, q1, c0, c1) with its edge q0 q1 on the front.
struct Cone {
  bool edge = false;
  Eigen::Vector3d q0, q1, c0, c1, c2;
  const Line3* line = nullptr;
  int depth = 0;      // how often its opposite face (edge) was split
  double volume = 0.0;
  double error = 0.0; // its estimated quadrature error (ConeRule::estimated_error, m^2)
  bool operator<(const Cone& other) const { return error < other.error; }
};

// The opposite face split into 4 by its edges' midpoints (the opposite edge into 2).
std::vector<Cone> split_cone(const Cone& cone) {
  std::vector<Cone> children;
  const auto child = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    Cone k = cone;
    k.c0 = a;
    k.c1 = b;
    k.c2 = c;
    k.depth = cone.depth + 1;
    k.volume = cone.edge ? tet_volume(k.q0, k.q1, a, b) : tet_volume(k.q0, a, b, c);
    children.push_back(k);
  };
  if (cone.edge) {
    const Eigen::Vector3d m = 0.5 * (cone.c0 + cone.c1);
    child(cone.c0, m, m);
    child(m, cone.c1, m);
  } else {
    const Eigen::Vector3d m01 = 0.5 * (cone.c0 + cone.c1), m12 = 0.5 * (cone.c1 + cone.c2), m20 = 0.5 * (cone.c2 + cone.c0);
    child(cone.c0, m01, m20);
    child(m01, cone.c1, m12);
    child(m20, m12, cone.c2);
    child(m01, m12, m20);
  }
  return children;
}

// The points per direction of a collapsed sub-tet: n in sigma and across, `along` in s.
struct ConeRule {
  Line g, g1, along;
  template <class Visit>
  void for_each_point(const Cone& c, Visit&& visit) const {
    if (c.edge) for_each_edge_collapsed_point(c.q0, c.q1, c.c0, c.c1, g, along, visit);
    else for_each_corner_collapsed_point(c.q0, c.c0, c.c1, c.c2, g, g1, visit);
  }
  // int g(theta) / r dV over the cone by its rule, r and theta about its front line, with
  // g = 1.5 - 0.5 cos(3 theta): 1/r is the stiffness's worst radial term, exact in r on the cone
  // and near-singular across it only where the line passes close to the opposite face; the
  // products of the branch functions' gradients hold angles up to 3 theta, which vary fast
  // across a face the line grazes. cos(3 theta) = 4 c^3 - 3 c, c = cos(theta), from any
  // direction perpendicular to the line (the phase does not matter to an error estimate).
  double estimator_integral(const Cone& c) const {
    const Eigen::Vector3d across = c.line->direction.unitOrthogonal();
    double sum = 0.0;
    for_each_point(c, [&](const Eigen::Vector3d& x, double w) {
      const Eigen::Vector3d y = x - c.line->point;
      const Eigen::Vector3d radial = y - y.dot(c.line->direction) * c.line->direction;
      const double r = std::max(radial.norm(), std::numeric_limits<double>::min());
      const double cosine = radial.dot(across) / r;
      sum += w * (1.5 - 0.5 * (4.0 * cosine * cosine * cosine - 3.0 * cosine)) / r;
    });
    return sum;
  }
  // The error estimate: the rule on the cone against the rule on its four (two) children.
  double estimated_error(const Cone& c) const {
    double refined = 0.0;
    for (const Cone& k : split_cone(c)) refined += estimator_integral(k);
    return std::abs(estimator_integral(c) - refined);
  }
};

// int 1/r dV over the sub-tet T by the Gauss rule `gauss`, r the distance to the front.
double gauss_inverse_distance(const Eigen::Matrix<double, 4, 3>& T, const TetQuadratureRule& gauss, const NearbyFront& front) {
  Eigen::Matrix3d J;
  for (int c = 0; c < 3; ++c) J.col(c) = (T.row(c + 1) - T.row(0)).transpose();
  double sum = 0.0;
  for (std::size_t q = 0; q < gauss.points.size(); ++q)
    sum += gauss.weights[q] /
           std::max(front.distance(T.row(0).transpose() + J * gauss.points[q]), std::numeric_limits<double>::min());
  return sum * std::abs(J.determinant());
}

// A sub-tet with a Gauss rule (of a blending rule, or of a cell of a front tet that the front does
// not touch): n points per direction, refined `depth` times.
struct GaussSubtet {
  Eigen::Matrix<double, 4, 3> T;
  int n = 0, depth = 0;
  bool near = false;  // larger than its distance to the front: it may be refined
  double error = 0.0; // its estimated error for 1/r (m^2)
  bool operator<(const GaussSubtet& other) const { return error < other.error; }
};

// The sub-tet's estimated error: its rule against the same rule on its 8 children.
void estimate_error(GaussSubtet& s, const std::vector<TetQuadratureRule>& gauss, const NearbyFront& front) {
  const TetQuadratureRule& rule = gauss[static_cast<std::size_t>(s.n)];
  double refined = 0.0;
  for (const Eigen::Matrix<double, 4, 3>& child : refine_tet(s.T)) refined += gauss_inverse_distance(child, rule, front);
  s.error = std::abs(gauss_inverse_distance(s.T, rule, front) - refined);
}

std::size_t cube(int k) { return static_cast<std::size_t>(k) * static_cast<std::size_t>(k) * static_cast<std::size_t>(k); }

} // namespace

PieceQuadratureRule front_collapsed_rule(const Eigen::Matrix<double, 4, 3>& X, const TetPieces& pieces, int piece,
                                         const CrackFronts& fronts, int n, int grading) {
  if (n < 1 || n > 8) throw std::invalid_argument("front_collapsed_rule: n must be in 1..8");
  if (grading < 0 || grading > default_front_grading) throw std::invalid_argument("front_collapsed_rule: grading must be in 0..12");
  // Along the front the integrands are the elements' polynomials (r and theta do not change
  // along a straight front): n / 2 points (at least 1) are exact for degree n - 2, N_i N_j of a
  // Tet4 with n = 4 and of a Tet10 with n = 6, and for every polynomial of degree n - 3, the
  // rule's exactness in r. The Gauss cells start as exact for polynomials.
  const ConeRule cone_rule{Line(n), Line(n, 1), Line(std::max(1, n / 2))};
  const int gauss_n_least = std::max(1, n / 2);
  const auto cone_points = [&](const Cone& c) {
    return static_cast<std::size_t>(n * n) * (c.edge ? cone_rule.along.x.size() : static_cast<std::size_t>(n));
  };
  const double tolerance = 1e-10 * pieces.diameter;
  const double min_volume = 1e-14 * pieces.volume;
  const std::vector<FrontPiece> front = front_in_tet(fronts, X);
  const NearbyFront nearby(fronts, X.colwise().mean().transpose(), pieces.diameter);
  std::vector<TetQuadratureRule> gauss(static_cast<std::size_t>(n) + 1);
  for (int k = gauss_n_least; k <= n; ++k) gauss[static_cast<std::size_t>(k)] = tet_quadrature_rule(2 * k - 1);

  std::vector<Line3> lines; // one per collapsed cell, never reallocated: the cones point into it
  lines.reserve(pieces.cells.size());
  std::priority_queue<Cone> cones;
  std::priority_queue<GaussSubtet> subtets;
  double total_error = 0.0;
  std::size_t points = 0;
  const auto push_cone = [&](Cone cone) {
    // No volume: a fan triangle of collinear corners.
    if (cone.volume <= min_volume * std::pow(cone.edge ? 0.5 : 0.25, cone.depth)) return;
    cone.error = cone_rule.estimated_error(cone);
    total_error += cone.error;
    points += cone_points(cone);
    cones.push(cone);
  };
  const auto push_subtet = [&](GaussSubtet subtet) {
    const SubtetSize size(subtet.T);
    subtet.near = size.diameter > nearby.distance(size.centre) - size.radius;
    estimate_error(subtet, gauss, nearby);
    total_error += subtet.error;
    points += cube(subtet.n);
    subtets.push(subtet);
  };
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
      // Away from the front: Gauss on the cell's fan.
      for (const Eigen::Matrix<double, 4, 3>& T : convex_cell_tetrahedra(cell))
        if (SubtetSize(T).diameter > 0.0) push_subtet({T, gauss_n_least});
      continue;
    }
    const bool segment = longest > tolerance;
    lines.push_back({q0, segment ? Eigen::Vector3d((q1 - q0).normalized()) : front_direction(fronts, front, q0)});
    const Line3& line = lines.back();
    // Cones from q0 over the faces that do not hold it; in a face that holds q1, cones from q1.
    for (const CellFace& face : cell.faces) {
      const std::vector<Eigen::Vector3d>& P = face.polygon;
      if (P.size() < 3 || distance_to_plane_of(P, q0) <= tolerance) continue;
      if (segment && distance_to_plane_of(P, q1) <= tolerance) {
        for (std::size_t k = 0; k < P.size(); ++k) {
          const Eigen::Vector3d &a = P[k], &b = P[(k + 1) % P.size()];
          push_cone({true, q0, q1, a, b, a, &line, 0, tet_volume(q0, q1, a, b)});
        }
      } else {
        for (std::size_t k = 1; k + 1 < P.size(); ++k)
          push_cone({false, q0, q1, P[0], P[k], P[k + 1], &line, 0, tet_volume(q0, P[0], P[k], P[k + 1])});
      }
    }
  }

  // The grading: the part with the largest estimated error is improved (a cone split; a Gauss
  // sub-tet given a point more per direction, or at n points refined if it is larger than its
  // distance to the front: a cell the front touches within the clipping's tolerance only) until
  // the piece's total is below front_rule_tolerance(n) of V / h, or the piece would pass
  // front_rule_max_points(n). A part split `grading` times, or one the budget has no room for,
  // is final.
  const double allowed = front_rule_tolerance(n) * pieces.volume / pieces.diameter;
  const std::size_t budget = front_rule_max_points(n);
  std::vector<Cone> final_cones;
  std::vector<GaussSubtet> final_subtets;
  while (total_error > allowed && !(cones.empty() && subtets.empty())) {
    if (subtets.empty() || (!cones.empty() && cones.top().error >= subtets.top().error)) {
      const Cone cone = cones.top();
      cones.pop();
      const std::vector<Cone> children = split_cone(cone);
      std::size_t more = 0;
      for (const Cone& child : children) more += cone_points(child);
      if (cone.depth >= grading || points - cone_points(cone) + more > budget) {
        total_error -= cone.error;
        final_cones.push_back(cone);
        continue;
      }
      total_error -= cone.error;
      points -= cone_points(cone);
      for (const Cone& child : children) push_cone(child);
    } else {
      GaussSubtet subtet = subtets.top();
      subtets.pop();
      const bool refine = subtet.n >= n; // at n points: refined towards the front, if it is near
      const std::size_t after = refine ? 8 * cube(gauss_n_least) : cube(subtet.n + 1);
      if ((refine && !(subtet.near && subtet.depth < grading)) || points - cube(subtet.n) + after > budget) {
        total_error -= subtet.error;
        final_subtets.push_back(subtet);
        continue;
      }
      total_error -= subtet.error;
      points -= cube(subtet.n);
      if (refine) {
        for (const Eigen::Matrix<double, 4, 3>& child : refine_tet(subtet.T))
          push_subtet({child, gauss_n_least, subtet.depth + 1});
      } else {
        ++subtet.n;
        push_subtet(subtet);
      }
    }
  }
  PieceQuadratureRule rule;
  const auto append = [&](const Eigen::Vector3d& x, double w) {
    rule.points.push_back(x);
    rule.weights.push_back(w);
  };
  for (const Cone& cone : final_cones) cone_rule.for_each_point(cone, append);
  for (; !cones.empty(); cones.pop()) cone_rule.for_each_point(cones.top(), append);
  const auto append_subtet = [&](const GaussSubtet& s) { append_gauss_tet(s.T, gauss[static_cast<std::size_t>(s.n)], rule); };
  for (const GaussSubtet& subtet : final_subtets) append_subtet(subtet);
  for (; !subtets.empty(); subtets.pop()) append_subtet(subtets.top());
  return rule;
}

PieceQuadratureRule near_front_graded_rule(const TetPieces& pieces, int piece, const CrackFronts& fronts, int degree, int max_depth,
                                           double tolerance, int polynomial_degree) {
  if (max_depth < 0) throw std::invalid_argument("near_front_graded_rule: max_depth must be >= 0");
  if (!(tolerance >= 0.0)) throw std::invalid_argument("near_front_graded_rule: tolerance must be >= 0");
  if (polynomial_degree < 0) throw std::invalid_argument("near_front_graded_rule: polynomial_degree must be >= 0");
  // tet_quadrature_rule's product rules have (degree + 2) / 2 points per direction from degree
  // 3 on (exact to 2 n - 1); its own 1- and 4-point rules below that are kept on every sub-tet.
  const int n_most = degree >= 3 ? (degree + 2) / 2 : 1;
  const int n_least = degree >= 3 ? std::clamp((polynomial_degree + 2) / 2, 1, n_most) : 1;
  std::vector<TetQuadratureRule> gauss(static_cast<std::size_t>(n_most) + 1);
  for (int k = n_least; k < n_most; ++k) gauss[static_cast<std::size_t>(k)] = tet_quadrature_rule(2 * k - 1);
  gauss[static_cast<std::size_t>(n_most)] = tet_quadrature_rule(degree);
  const double allowed = (tolerance > 0.0 ? tolerance : front_rule_tolerance(n_most)) * pieces.volume / pieces.diameter;

  Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), high = -low;
  for (const ConvexCell& cell : pieces.cells)
    for (const CellFace& face : cell.faces)
      for (const Eigen::Vector3d& x : face.polygon) {
        low = low.cwiseMin(x);
        high = high.cwiseMax(x);
      }
  const NearbyFront front(fronts, 0.5 * (low + high), 0.5 * (high - low).norm());

  // Every sub-tet starts with the fewest points; the one with the largest estimated error (its
  // rule against the same rule on its 8 children) gets one point more per direction, or, at
  // `degree` and nearer the front than its size, is refined, until the piece's total is below
  // the tolerance of V / h.
  std::priority_queue<GaussSubtet> subtets;
  double total_error = 0.0;
  const auto push = [&](GaussSubtet s) {
    const SubtetSize size(s.T);
    s.near = size.diameter > front.distance(size.centre) - size.radius;
    estimate_error(s, gauss, front);
    total_error += s.error;
    subtets.push(s);
  };
  for (const int c : pieces.pieces[static_cast<std::size_t>(piece)].cells)
    for (const Eigen::Matrix<double, 4, 3>& T : convex_cell_tetrahedra(pieces.cells[static_cast<std::size_t>(c)]))
      if (SubtetSize(T).diameter > 0.0) push({T, n_least, 0});
  std::vector<GaussSubtet> final_subtets;
  while (!subtets.empty() && total_error > allowed) {
    GaussSubtet s = subtets.top();
    subtets.pop();
    total_error -= s.error;
    if (s.n < n_most) {
      ++s.n;
      push(s);
    } else if (s.near && s.depth < max_depth) {
      for (const Eigen::Matrix<double, 4, 3>& child : refine_tet(s.T)) push({child, n_least, s.depth + 1});
    } else {
      final_subtets.push_back(s);
    }
  }
  PieceQuadratureRule rule;
  const auto append_subtet = [&](const GaussSubtet& s) { append_gauss_tet(s.T, gauss[static_cast<std::size_t>(s.n)], rule); };
  for (const GaussSubtet& s : final_subtets) append_subtet(s);
  for (; !subtets.empty(); subtets.pop()) append_subtet(subtets.top());
  return rule;
}

} // namespace kerf
