#include "kerf/cut/clip_tet.hpp"

#include <Eigen/Dense>
#include <algorithm>

namespace kerf {

namespace {

using Corners = Eigen::Matrix<double, 4, 3>;

// Appends the tet (a, b, c, d) to `part`, positively oriented. The orientation of a piece
// depends on the permutation that brought the sign pattern into its canonical order below;
// rather than tracking that parity through every case we swap two corners when the volume
// comes out negative. The sign is reliable for any piece whose volume is above round-off, and
// a piece below round-off contributes nothing either way.
void add_tet(std::vector<Corners>& part, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
             const Eigen::Vector3d& d) {
  Corners T;
  T.row(0) = a.transpose();
  T.row(1) = b.transpose();
  T.row(2) = c.transpose();
  T.row(3) = d.transpose();
  if (signed_tet_volume(T) < 0.0) T.row(1).swap(T.row(2));
  part.push_back(T);
}

// A triangular prism with bottom (A0, A1, A2) and top (B0, B1, B2), Ai joined to Bi by an edge,
// as three tets. The diagonals A0-B1, A1-B2, A0-B2 of the three quadrilateral sides do not run
// round in a cycle, which is what makes the three tets fill the prism without overlap (for the
// convex prisms a plane cuts off a tet, every such choice works).
void add_prism(std::vector<Corners>& part, const Eigen::Vector3d& A0, const Eigen::Vector3d& A1,
               const Eigen::Vector3d& A2, const Eigen::Vector3d& B0, const Eigen::Vector3d& B1,
               const Eigen::Vector3d& B2) {
  add_tet(part, A0, A1, A2, B2);
  add_tet(part, A0, A1, B1, B2);
  add_tet(part, A0, B0, B1, B2);
}

// Area vector of a planar polygon (Newell's formula): half the sum of the cross products of
// consecutive corners, taken relative to the first one to keep round-off small. Its length is
// the area and it points along the normal for which the corners run counter-clockwise.
Eigen::Vector3d area_vector(const std::vector<Eigen::Vector3d>& polygon) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
    sum += (polygon[k] - polygon[0]).cross(polygon[k + 1] - polygon[0]);
  return 0.5 * sum;
}

} // namespace

double signed_tet_volume(const Corners& X) {
  Eigen::Matrix3d J;
  for (int c = 0; c < 3; ++c) J.col(c) = (X.row(c + 1) - X.row(0)).transpose();
  return J.determinant() / 6.0;
}

double polygon_area(const std::vector<Eigen::Vector3d>& polygon) {
  return polygon.size() < 3 ? 0.0 : area_vector(polygon).norm();
}

ClippedTet clip_tet(const Corners& X, const Eigen::Vector4d& lambda) {
  ClippedTet result;
  result.tet_case = classify_tet_cut(lambda);
  const auto x = [&](int i) -> Eigen::Vector3d { return X.row(i).transpose(); };
  // The crossing of the edge from a + corner p to a - corner m, interpolated from the + end.
  const auto crossing = [&](int p, int m) -> Eigen::Vector3d {
    const double t = lambda[p] / (lambda[p] - lambda[m]); // in (0, 1): lambda[p] > 0 > lambda[m]
    return x(p) + t * (x(m) - x(p));
  };

  // Sort the corners by sign, keeping their local order within each group.
  std::vector<int> plus, minus, zero;
  for (int i = 0; i < 4; ++i) (lambda[i] > 0.0 ? plus : lambda[i] < 0.0 ? minus : zero).push_back(i);
  // The + side is "above": its pieces go to result.above, those of the - side to result.below.
  std::vector<Corners>& plus_part = result.above;
  std::vector<Corners>& minus_part = result.below;

  switch (result.tet_case) {
  case TetCutCase::cut_one_vertex_apart: {
    // The lone corner keeps a small tet whose other corners are the three crossings; the other
    // side is the prism between the opposite face and the triangular section.
    const bool lone_is_plus = plus.size() == 1;
    const int lone = lone_is_plus ? plus[0] : minus[0];
    const std::vector<int>& others = lone_is_plus ? minus : plus;
    Eigen::Vector3d c[3];
    for (int k = 0; k < 3; ++k) c[k] = lone_is_plus ? crossing(lone, others[k]) : crossing(others[k], lone);
    add_tet(lone_is_plus ? plus_part : minus_part, x(lone), c[0], c[1], c[2]);
    add_prism(lone_is_plus ? minus_part : plus_part, x(others[0]), x(others[1]), x(others[2]), c[0], c[1], c[2]);
    result.section = {c[0], c[1], c[2]};
    break;
  }
  case TetCutCase::cut_two_two: {
    // Four crossings, one on each edge from {a, b} (+) to {c, d} (-); each side is a prism whose
    // two triangles lie in two faces of the tet, and the section is the quadrilateral between.
    const int a = plus[0], b = plus[1], c = minus[0], d = minus[1];
    const Eigen::Vector3d p_ac = crossing(a, c), p_ad = crossing(a, d), p_bc = crossing(b, c), p_bd = crossing(b, d);
    add_prism(plus_part, x(a), p_ac, p_ad, x(b), p_bc, p_bd);
    add_prism(minus_part, x(c), p_ac, p_bc, x(d), p_ad, p_bd);
    result.section = {p_ac, p_bc, p_bd, p_ad}; // consecutive points share a corner of the tet
    break;
  }
  case TetCutCase::cut_through_vertex: {
    // The plane passes through corner z and separates a lone corner from the other two (o0, o1).
    // The lone side is the tet (lone, z, c0, c1); the other side is a pyramid with apex z over the
    // quadrilateral (o0, o1, c1, c0), split along its diagonal o0-c1.
    const int z = zero[0];
    const bool lone_is_plus = plus.size() == 1;
    const int lone = lone_is_plus ? plus[0] : minus[0];
    const std::vector<int>& o = lone_is_plus ? minus : plus;
    const Eigen::Vector3d c0 = lone_is_plus ? crossing(lone, o[0]) : crossing(o[0], lone);
    const Eigen::Vector3d c1 = lone_is_plus ? crossing(lone, o[1]) : crossing(o[1], lone);
    add_tet(lone_is_plus ? plus_part : minus_part, x(lone), x(z), c0, c1);
    std::vector<Corners>& pyramid_part = lone_is_plus ? minus_part : plus_part;
    add_tet(pyramid_part, x(z), x(o[0]), x(o[1]), c1);
    add_tet(pyramid_part, x(z), x(o[0]), c1, c0);
    result.section = {x(z), c0, c1};
    break;
  }
  case TetCutCase::cut_through_edge: {
    // The plane contains the edge (z0, z1) and crosses the opposite edge at c: one tet per side.
    const int p = plus[0], m = minus[0];
    const Eigen::Vector3d c = crossing(p, m);
    add_tet(plus_part, x(p), x(zero[0]), x(zero[1]), c);
    add_tet(minus_part, x(m), x(zero[0]), x(zero[1]), c);
    result.section = {x(zero[0]), x(zero[1]), c};
    break;
  }
  default:
    // Not separated: the whole tet lies on the side of its nonzero corners; all_zero goes above.
    add_tet(minus.empty() ? result.above : result.below, x(0), x(1), x(2), x(3));
    break;
  }

  // Orient the section counter-clockwise seen from above: its area vector must point to a +
  // corner (every separated tet has one).
  if (!result.section.empty() && area_vector(result.section).dot(x(plus[0]) - result.section[0]) < 0.0)
    std::reverse(result.section.begin(), result.section.end());

  for (const Corners& T : result.above) result.V_a += signed_tet_volume(T);
  for (const Corners& T : result.below) result.V_b += signed_tet_volume(T);
  return result;
}

bool minimum_volume_fraction_met(double fraction_a, double fraction_b, double minimum_fraction) {
  return std::min(fraction_a, fraction_b) >= minimum_fraction;
}

} // namespace kerf
