#include "kerf/cut/tet_cut_classification.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

namespace kerf {

TetCutCase classify_tet_cut(const Eigen::Vector4d& lambda) {
  int plus = 0, minus = 0, zero = 0;
  for (int i = 0; i < 4; ++i) {
    const int s = level_set_sign(lambda[i]);
    plus += s > 0;
    minus += s < 0;
    zero += s == 0;
  }
  // Both signs present: the plane separates the tet (eq. 73). The number of corners on the plane
  // tells the four cut cases apart, and for no zeros the split 1-3 versus 2-2.
  if (plus > 0 && minus > 0) {
    if (zero == 2) return TetCutCase::cut_through_edge;
    if (zero == 1) return TetCutCase::cut_through_vertex;
    return plus == 2 ? TetCutCase::cut_two_two : TetCutCase::cut_one_vertex_apart;
  }
  // One sign at most: the number of zeros says what the plane touches.
  switch (zero) {
  case 0: return TetCutCase::uncut;
  case 1: return TetCutCase::touched_vertex;
  case 2: return TetCutCase::touched_edge;
  case 3: return TetCutCase::touched_face;
  default: return TetCutCase::all_zero;
  }
}

const char* to_string(TetCutCase c) {
  switch (c) {
  case TetCutCase::uncut: return "uncut";
  case TetCutCase::touched_vertex: return "touched_vertex";
  case TetCutCase::touched_edge: return "touched_edge";
  case TetCutCase::touched_face: return "touched_face";
  case TetCutCase::all_zero: return "all_zero";
  case TetCutCase::cut_one_vertex_apart: return "cut_one_vertex_apart";
  case TetCutCase::cut_two_two: return "cut_two_two";
  case TetCutCase::cut_through_vertex: return "cut_through_vertex";
  case TetCutCase::cut_through_edge: return "cut_through_edge";
  }
  return "?";
}

const char* to_string(ElementCutState s) {
  switch (s) {
  case ElementCutState::uncut: return "uncut";
  case ElementCutState::touched: return "touched";
  case ElementCutState::partially_cut: return "partially_cut";
  case ElementCutState::completely_cut: return "completely_cut";
  }
  return "?";
}

namespace {

/// The area (m^2) of the convex polygon of the cut points, which all lie in the cut's plane:
/// in the rectangle's in-plane coordinates, ordered by angle about their mean, by the shoelace formula.
double section_area(const std::vector<Eigen::Vector3d>& points, const RectangleCut& cut) {
  if (points.size() < 3) return 0.0;
  const Eigen::Vector3d e1 = cut.edge1().normalized(), e2 = cut.edge2().normalized();
  std::vector<Eigen::Vector2d> polygon;
  for (const Eigen::Vector3d& x : points) polygon.emplace_back((x - cut.origin()).dot(e1), (x - cut.origin()).dot(e2));
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& q : polygon) mean += q / static_cast<double>(polygon.size());
  std::sort(polygon.begin(), polygon.end(), [&](const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
    return std::atan2(p.y() - mean.y(), p.x() - mean.x()) < std::atan2(q.y() - mean.y(), q.x() - mean.x());
  });
  double twice_area = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d p = polygon[i] - mean, q = polygon[(i + 1) % polygon.size()] - mean;
    twice_area += p.x() * q.y() - p.y() * q.x();
  }
  return 0.5 * std::abs(twice_area);
}

} // namespace

ElementCutState classify_element_cut(const Eigen::Matrix<double, 4, 3>& X, const Eigen::Vector4d& lambda,
                                     const RectangleCut& cut, double tolerance) {
  const TetCutCase tet_case = classify_tet_cut(lambda);
  const auto corner = [&](int i) -> Eigen::Vector3d { return X.row(i).transpose(); };

  if (!is_cut(tet_case)) {
    // Not separated: touched if a corner on the plane lies in the rectangle, else uncut.
    for (int i = 0; i < 4; ++i)
      if (lambda[i] == 0.0 && cut.contains_projection(corner(i), tolerance)) return ElementCutState::touched;
    return ElementCutState::uncut;
  }

  // The cut points: corners on the plane, and the crossings of the edges with a + and a - end.
  // The crossing is interpolated from the + end (lambda linear along the edge, the intercept
  // theorem of section 5.2), as clip_tet does, so both agree on the point.
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 4; ++i)
    if (lambda[i] == 0.0) points.push_back(corner(i));
  for (const auto& edge : tet_edge_corners) {
    int a = edge[0], b = edge[1];
    if (lambda[a] * lambda[b] >= 0.0) continue;
    if (lambda[a] < 0.0) std::swap(a, b);
    const double t = lambda[a] / (lambda[a] - lambda[b]);
    points.push_back(corner(a) + t * (corner(b) - corner(a)));
  }
  const bool all_inside = std::all_of(points.begin(), points.end(),
                                      [&](const Eigen::Vector3d& p) { return cut.contains_projection(p, tolerance); });
  if (all_inside) return ElementCutState::completely_cut;

  // Partially cut only if the section and the rectangle overlap in more than
  // partial_cut_minimum_area_fraction of the section's own area: a section that only touches
  // the rectangle's edge (the cut's front), or overlaps it in a strip of round-off width, lies
  // beyond the cut, not on it. Relative to the section, so that the decision does not depend on
  // the element's size and a move of the front by round-off cannot flip it.
  const double overlap = cut.overlap_area(points, 0.0);
  const double area = section_area(points, cut);
  return overlap > partial_cut_minimum_area_fraction * area ? ElementCutState::partially_cut : ElementCutState::uncut;
}

MeshCutClassification classify_mesh_cut(const TetMesh& mesh, const LevelSet& level_set, const RectangleCut& cut) {
  if (level_set.lambda.size() != mesh.num_nodes())
    throw std::invalid_argument("classify_mesh_cut: the level set must have one value per mesh node");
  MeshCutClassification result;
  const auto num_tets = static_cast<std::size_t>(mesh.num_tets());
  result.tet_case.resize(num_tets);
  result.state.resize(num_tets);
  Eigen::Matrix<double, 4, 3> X;
  Eigen::Vector4d lambda;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    for (int a = 0; a < 4; ++a) {
      const int node = mesh.tets(t, a);
      X.row(a) = mesh.nodes.row(node);
      lambda[a] = level_set.lambda[node];
    }
    const auto k = static_cast<std::size_t>(t);
    result.tet_case[k] = classify_tet_cut(lambda);
    result.state[k] = classify_element_cut(X, lambda, cut, level_set.snap_tolerance);
    ++result.case_counts[static_cast<std::size_t>(result.tet_case[k])];
    ++result.state_counts[static_cast<std::size_t>(result.state[k])];
  }
  return result;
}

} // namespace kerf
