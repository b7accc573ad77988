// Cut geometry: the rectangle and its plane, nodal level sets with snapping, the 15 sign patterns
// of a tet, clipping a tet into sub-tets above and below (V_a + V_b = V for every pattern and for
// random planes, against the closed form of the volume above an affine level set), sections that
// match across a shared face, and the counts of cut elements on the paper's beam.
#include "kerf/cut/clip_tet.hpp"
#include "kerf/cut/level_set.hpp"
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/cut/tet_cut_classification.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <stdexcept>
#include <tuple>

namespace {

using Corners = Eigen::Matrix<double, 4, 3>;

Corners unit_tet() {
  Corners X;
  X << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  return X;
}

Corners distorted_tet() {
  Corners X;
  X << 0.1, -0.2, 0.05, 2.0, 0.3, -0.1, 0.4, 1.5, 0.2, -0.3, 0.6, 0.9;
  return X;
}

// Barycentric coordinates of x in the tet X: the values of the four linear shape functions.
Eigen::Vector4d barycentric(const Corners& X, const Eigen::Vector3d& x) {
  Eigen::Matrix3d J;
  for (int c = 0; c < 3; ++c) J.col(c) = (X.row(c + 1) - X.row(0)).transpose();
  const Eigen::Vector3d xi = J.lu().solve(x - X.row(0).transpose());
  return {1.0 - xi.sum(), xi[0], xi[1], xi[2]};
}

// A plane cut through point p with normal n, as a square of side 2 h centred on p: large enough
// that its boundary stays away from the tets these tests use. e1 x e2 = |e1|^2 n, so the
// rectangle's orientation is n.
kerf::RectangleCut plane_cut(const Eigen::Vector3d& p, const Eigen::Vector3d& n, double h) {
  const Eigen::Vector3d unit_n = n.normalized();
  const Eigen::Vector3d e1 = 2.0 * h * unit_n.unitOrthogonal();
  const Eigen::Vector3d e2 = unit_n.cross(e1);
  return kerf::RectangleCut(p - 0.5 * (e1 + e2), e1, e2);
}

kerf::TetMesh one_tet_mesh(const Corners& X) {
  kerf::TetMesh mesh;
  mesh.nodes = X;
  mesh.tets.resize(1, 4);
  mesh.tets << 0, 1, 2, 3;
  return mesh;
}

// What every clipping must satisfy: V_a + V_b = V to 1e-14 relative, positive finite sub-tets
// inside the parent, each on its own side of the plane (lambda interpolated at its corners),
// and the number of pieces that the case promises.
void check_clip(const Corners& X, const Eigen::Vector4d& lambda, const kerf::ClippedTet& clip) {
  const double V = std::abs(kerf::signed_tet_volume(X));
  CHECK(std::isfinite(clip.V_a));
  CHECK(std::isfinite(clip.V_b));
  CHECK(std::abs(clip.V_a + clip.V_b - V) <= 1e-14 * V);
  const double tol = 1e-12 * lambda.cwiseAbs().maxCoeff();
  for (int side = 0; side < 2; ++side) {
    const auto& part = side == 0 ? clip.above : clip.below;
    for (const Corners& T : part) {
      CHECK(T.allFinite());
      CHECK(kerf::signed_tet_volume(T) > 0.0);
      for (int a = 0; a < 4; ++a) {
        const Eigen::Vector4d N = barycentric(X, T.row(a).transpose());
        CHECK(N.minCoeff() >= -1e-12);
        const double value = N.dot(lambda);
        if (side == 0) {
          CHECK(value >= -tol);
        } else {
          CHECK(value <= tol);
        }
      }
    }
  }
  const std::map<kerf::TetCutCase, std::pair<std::size_t, std::size_t>> pieces = {
      {kerf::TetCutCase::cut_one_vertex_apart, {1, 3}}, // lone side, other side
      {kerf::TetCutCase::cut_two_two, {3, 3}},
      {kerf::TetCutCase::cut_through_vertex, {1, 2}},
      {kerf::TetCutCase::cut_through_edge, {1, 1}}};
  if (kerf::is_cut(clip.tet_case)) {
    int plus = 0;
    for (int i = 0; i < 4; ++i) plus += lambda[i] > 0.0;
    const auto [lone, other] = pieces.at(clip.tet_case);
    // For two-two both sides are prisms; for the others the lone corner is + when only one is.
    const bool lone_is_plus = plus == 1 || clip.tet_case == kerf::TetCutCase::cut_two_two;
    CHECK(clip.above.size() == (lone_is_plus ? lone : other));
    CHECK(clip.below.size() == (lone_is_plus ? other : lone));
    CHECK(clip.section.size() == (clip.tet_case == kerf::TetCutCase::cut_two_two ? 4u : 3u));
    for (const auto& p : clip.section) CHECK(std::abs(barycentric(X, p).dot(lambda)) <= tol);
  } else {
    CHECK(clip.above.size() + clip.below.size() == 1u);
    CHECK(clip.section.empty());
  }
}

// The volume fraction of {lambda > 0} in a tet for an affine lambda with distinct corner values:
// sum over the + corners of lambda_i^3 / prod_{j != i} (lambda_i - lambda_j) (a divided difference
// of max(t, 0)^3, the B-spline identity), independent of any subdivision.
double fraction_above_closed_form(const Eigen::Vector4d& lambda) {
  double sum = 0.0;
  for (int i = 0; i < 4; ++i) {
    if (lambda[i] <= 0.0) continue;
    double denominator = 1.0;
    for (int j = 0; j < 4; ++j)
      if (j != i) denominator *= lambda[i] - lambda[j];
    sum += std::pow(lambda[i], 3) / denominator;
  }
  return sum;
}

} // namespace

TEST_CASE("cut: a rectangle's normal, signed distance to its plane, projection test and distance") {
  const kerf::RectangleCut cut({0, 0, 0}, {2, 0, 0}, {0, 1, 0});
  CHECK((cut.normal() - Eigen::Vector3d(0, 0, 1)).norm() == doctest::Approx(0.0));
  CHECK(cut.signed_distance_to_plane({0.5, 0.5, 0.3}) == kerf_test::relative(0.3));
  CHECK(cut.signed_distance_to_plane({5.0, -3.0, -0.2}) == kerf_test::relative(-0.2)); // the plane is unbounded
  CHECK(cut.contains_projection({0.5, 0.5, -7.0}, 0.0));
  CHECK(cut.contains_projection({2.0, 1.0, 0.0}, 0.0)); // a corner: the closure counts
  CHECK_FALSE(cut.contains_projection({2.0 + 1e-10, 0.5, 0.0}, 0.0));
  CHECK(cut.contains_projection({2.0 + 1e-10, 0.5, 0.0}, 1e-9));
  CHECK_FALSE(cut.contains_projection({1.0, -1e-8, 0.0}, 1e-9));
  CHECK(cut.distance_to_rectangle({1.0, 0.5, -0.25}) == kerf_test::relative(0.25)); // above the inside
  CHECK(cut.distance_to_rectangle({1.0, 2.0, 0.0}) == kerf_test::relative(1.0));    // beside an edge
  CHECK(cut.distance_to_rectangle({3.0, 2.0, 1.0}) == kerf_test::relative(std::sqrt(3.0))); // past a corner
  CHECK(cut.distance_to_rectangle({1.5, 0.25, 0.0}) == 0.0);
  // Swapping the edges flips the orientation, and with it every signed distance.
  const kerf::RectangleCut flipped({0, 0, 0}, {0, 1, 0}, {2, 0, 0});
  CHECK(flipped.signed_distance_to_plane({0.5, 0.5, 0.3}) == kerf_test::relative(-0.3));
  CHECK_THROWS_AS(kerf::RectangleCut({0, 0, 0}, {1, 0, 0}, {1, 1, 0}), std::invalid_argument);
  CHECK_THROWS_AS(kerf::RectangleCut({0, 0, 0}, {0, 0, 0}, {0, 1, 0}), std::invalid_argument);
}

TEST_CASE("cut: the 81 sign patterns of a tet fall into 15 multisets and 9 cases, and every one clips") {
  // Values of different sizes, so that no pattern is accidentally symmetric.
  const Eigen::Vector4d magnitude(0.3, 1.1, 0.7, 2.0);
  std::map<kerf::TetCutCase, int> patterns_per_case;
  std::map<std::tuple<int, int, int>, std::set<kerf::TetCutCase>> cases_per_multiset;
  for (const Corners& X : {unit_tet(), distorted_tet()}) {
    for (int code = 0; code < 81; ++code) {
      Eigen::Vector4d lambda;
      int plus = 0, minus = 0, zero = 0;
      for (int i = 0, c = code; i < 4; ++i, c /= 3) {
        const int s = c % 3 - 1; // -1, 0, +1
        lambda[i] = s * magnitude[i];
        plus += s > 0;
        minus += s < 0;
        zero += s == 0;
      }
      CAPTURE(lambda.transpose());
      const kerf::TetCutCase c = kerf::classify_tet_cut(lambda);
      CHECK(kerf::is_cut(c) == (plus > 0 && minus > 0)); // eq. 73: min * max < 0
      CHECK(kerf::is_cut(c) == (lambda.minCoeff() * lambda.maxCoeff() < 0.0));
      if (X == unit_tet()) {
        ++patterns_per_case[c];
        cases_per_multiset[{plus, minus, zero}].insert(c);
      }
      const kerf::ClippedTet clip = kerf::clip_tet(X, lambda);
      CHECK(clip.tet_case == c);
      check_clip(X, lambda, clip);
    }
  }
  // 3^4 = 81 patterns; up to permutation C(6, 3) = 15 multisets, each mapped to exactly one case.
  CHECK(cases_per_multiset.size() == 15u);
  for (const auto& [multiset, cases] : cases_per_multiset) CHECK(cases.size() == 1u);
  // Counted by hand: which corners are zero, which are lone, and the signs.
  using C = kerf::TetCutCase;
  CHECK(patterns_per_case[C::uncut] == 2);                 // ++++, ----
  CHECK(patterns_per_case[C::touched_vertex] == 8);        // 4 zero corners x 2 signs
  CHECK(patterns_per_case[C::touched_edge] == 12);         // 6 edges x 2 signs
  CHECK(patterns_per_case[C::touched_face] == 8);          // 4 faces x 2 signs
  CHECK(patterns_per_case[C::all_zero] == 1);
  CHECK(patterns_per_case[C::cut_one_vertex_apart] == 8);  // 4 lone corners x 2 signs
  CHECK(patterns_per_case[C::cut_two_two] == 6);           // 6 ways to pick the + pair
  CHECK(patterns_per_case[C::cut_through_vertex] == 24);   // 4 zero x 3 lone x 2 signs
  CHECK(patterns_per_case[C::cut_through_edge] == 12);     // 6 edges on the plane x 2 signs
}

TEST_CASE("cut: random planes through random tets keep V_a + V_b = V and match the closed-form volume") {
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  int checked_against_closed_form = 0;
  for (int trial = 0; trial < 500; ++trial) {
    Corners X;
    for (int a = 0; a < 4; ++a)
      for (int c = 0; c < 3; ++c) X(a, c) = uniform(rng);
    if (std::abs(kerf::signed_tet_volume(X)) < 1e-3) continue; // skip slivers; clip_tet takes them, the check is noisy
    const Eigen::Vector3d n = Eigen::Vector3d(uniform(rng), uniform(rng), uniform(rng)).normalized();
    const double d = 0.5 * uniform(rng);
    Eigen::Vector4d lambda;
    for (int a = 0; a < 4; ++a) lambda[a] = n.dot(X.row(a).transpose()) - d;
    CAPTURE(trial);
    const kerf::ClippedTet clip = kerf::clip_tet(X, lambda);
    check_clip(X, lambda, clip);
    double min_gap = 1e300;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) min_gap = std::min(min_gap, std::abs(lambda[i] - lambda[j]));
    if (min_gap > 1e-2) {
      const double V = std::abs(kerf::signed_tet_volume(X));
      CHECK(clip.V_a / V == kerf_test::relative(fraction_above_closed_form(lambda), 1e-9));
      ++checked_against_closed_form;
    }
  }
  CHECK(checked_against_closed_form > 200);
}

TEST_CASE("cut: sections and volumes in closed form on the unit tet") {
  const Corners X = unit_tet(); // V = 1/6
  SUBCASE("x = 0.5 cuts off the corner (1,0,0): triangle of area 1/8, V_a = V / 8") {
    const Eigen::Vector4d lambda(-0.5, 0.5, -0.5, -0.5);
    const kerf::ClippedTet clip = kerf::clip_tet(X, lambda);
    CHECK(clip.tet_case == kerf::TetCutCase::cut_one_vertex_apart);
    CHECK(kerf::polygon_area(clip.section) == kerf_test::relative(1.0 / 8.0, 1e-15));
    CHECK(clip.V_a == kerf_test::relative(1.0 / 48.0, 1e-15));
    CHECK(clip.V_b == kerf_test::relative(7.0 / 48.0, 1e-15));
    // counter-clockwise seen from above: the area vector points along +x
    const Eigen::Vector3d area_vector =
        0.5 * (clip.section[1] - clip.section[0]).cross(clip.section[2] - clip.section[0]);
    CHECK(area_vector.x() == kerf_test::relative(1.0 / 8.0));
  }
  SUBCASE("x + y = 0.5 splits two against two: rectangle 0.5 by sqrt(0.5), V_a = V_b = 1/12") {
    const Eigen::Vector4d lambda(-0.5, 0.5, 0.5, -0.5);
    const kerf::ClippedTet clip = kerf::clip_tet(X, lambda);
    CHECK(clip.tet_case == kerf::TetCutCase::cut_two_two);
    CHECK(kerf::polygon_area(clip.section) == kerf_test::relative(std::sqrt(2.0) / 4.0, 1e-15));
    CHECK(clip.V_a == kerf_test::relative(1.0 / 12.0, 1e-15));
    CHECK(clip.V_b == kerf_test::relative(1.0 / 12.0, 1e-15));
  }
  SUBCASE("a plane through corner 1 with normal (1,2,-2)/3: triangle of area 3/16, V_a = 1/48") {
    // lambda = n . (x - x1): corners 0, 2, 3 get -1/3, 1/3, -1. Crossings at (0, 1/2, 0) and
    // (0, 3/4, 1/4); the + side is the tet (x2, x1, crossings) = V * 1 * 1/2 * 1/4.
    const Eigen::Vector4d lambda(-1.0 / 3.0, 0.0, 1.0 / 3.0, -1.0);
    const kerf::ClippedTet clip = kerf::clip_tet(X, lambda);
    CHECK(clip.tet_case == kerf::TetCutCase::cut_through_vertex);
    CHECK(kerf::polygon_area(clip.section) == kerf_test::relative(3.0 / 16.0, 1e-15));
    CHECK(clip.V_a == kerf_test::relative(1.0 / 48.0, 1e-15));
  }
  SUBCASE("the plane y = z contains the edge (0,1): two halves of V / 2") {
    const Eigen::Vector4d lambda(0.0, 0.0, 1.0, -1.0);
    const kerf::ClippedTet clip = kerf::clip_tet(X, lambda);
    CHECK(clip.tet_case == kerf::TetCutCase::cut_through_edge);
    CHECK(clip.V_a == kerf_test::relative(1.0 / 12.0, 1e-15));
    CHECK(clip.V_b == kerf_test::relative(1.0 / 12.0, 1e-15));
    // section: (0,0,0), (1,0,0), (0, 1/2, 1/2): area |(1,0,0) x (0,1/2,1/2)| / 2 = sqrt(2)/4
    CHECK(kerf::polygon_area(clip.section) == kerf_test::relative(std::sqrt(2.0) / 4.0, 1e-15));
  }
}

TEST_CASE("cut: two tets sharing a face have sections that meet exactly on it") {
  // Tet A is the unit tet; tet B = (x1, x3, x2, (1,1,1)) shares the face x + y + z = 1 with it.
  Corners A = unit_tet(), B;
  B << 1, 0, 0, 0, 0, 1, 0, 1, 0, 1, 1, 1;
  const Eigen::Vector3d n(0.3, -0.5, 0.8);
  const double d = 0.1;
  const auto level_set = [&](const Corners& X) {
    Eigen::Vector4d lambda;
    for (int a = 0; a < 4; ++a) lambda[a] = n.dot(X.row(a).transpose()) - d;
    return lambda;
  };
  const kerf::ClippedTet clip_A = kerf::clip_tet(A, level_set(A));
  const kerf::ClippedTet clip_B = kerf::clip_tet(B, level_set(B));
  REQUIRE(kerf::is_cut(clip_A.tet_case));
  REQUIRE(kerf::is_cut(clip_B.tet_case));
  const auto on_shared_face = [](const std::vector<Eigen::Vector3d>& section) {
    std::set<std::tuple<double, double, double>> points;
    for (const auto& p : section)
      if (std::abs(p.sum() - 1.0) <= 1e-14) points.insert({p.x(), p.y(), p.z()});
    return points;
  };
  const auto shared_A = on_shared_face(clip_A.section), shared_B = on_shared_face(clip_B.section);
  CHECK(shared_A.size() == 2u);
  CHECK(shared_A == shared_B); // bitwise: both interpolate each crossing from its + end
}

TEST_CASE("cut: a plane through a node is snapped, and classified and clipped as such") {
  const Corners X = unit_tet();
  const kerf::TetMesh mesh = one_tet_mesh(X);
  // The plane through corner 1 with normal (1,2,-2), moved off it by 1e-12: round-off size.
  const Eigen::Vector3d n = Eigen::Vector3d(1, 2, -2) / 3.0;
  const kerf::RectangleCut cut = plane_cut(Eigen::Vector3d(1, 0, 0) + 1e-12 * n, n, 10.0);
  CHECK(kerf::default_snap_tolerance(mesh) == kerf_test::relative(1e-9 * std::sqrt(3.0)));

  const kerf::LevelSet snapped = kerf::make_level_set(mesh, cut);
  CHECK(snapped.lambda[1] == 0.0);
  CHECK((snapped.sign.transpose() == Eigen::RowVector4i(-1, 0, 1, -1)));
  const kerf::ClippedTet clip = kerf::clip_tet(X, snapped.lambda);
  CHECK(clip.tet_case == kerf::TetCutCase::cut_through_vertex);
  check_clip(X, snapped.lambda, clip);

  // Without snapping the same plane separates corner 2 from a sliver-producing -1e-12 at corner 1.
  const kerf::LevelSet raw = kerf::make_level_set(mesh, cut, 0.0);
  CHECK(raw.lambda[1] == kerf_test::relative(-1e-12, 1e-3));
  CHECK(kerf::classify_tet_cut(raw.lambda) == kerf::TetCutCase::cut_one_vertex_apart);
  check_clip(X, raw.lambda, kerf::clip_tet(X, raw.lambda));
}

TEST_CASE("cut: a plane along a face, all corners on the plane, and a 1e-12 volume fraction") {
  const Corners X = unit_tet();
  const double V = 1.0 / 6.0;
  SUBCASE("x + y + z = 1 (up to 1e-13) is touched_face: one side is empty, no NaN") {
    const kerf::TetMesh mesh = one_tet_mesh(X);
    const Eigen::Vector3d n = Eigen::Vector3d(1, 1, 1).normalized();
    const kerf::RectangleCut cut = plane_cut(Eigen::Vector3d(1, 0, 0) + 1e-13 * n, n, 10.0);
    const kerf::LevelSet level_set = kerf::make_level_set(mesh, cut);
    CHECK((level_set.sign.transpose() == Eigen::RowVector4i(-1, 0, 0, 0)));
    const kerf::ClippedTet clip = kerf::clip_tet(X, level_set.lambda);
    CHECK(clip.tet_case == kerf::TetCutCase::touched_face);
    CHECK(clip.above.empty());
    CHECK(clip.V_a == 0.0);
    CHECK(clip.V_b == kerf_test::relative(V, 1e-15));
    check_clip(X, level_set.lambda, clip);
    const kerf::MeshCutClassification classes = kerf::classify_mesh_cut(mesh, level_set, cut);
    CHECK(classes.count(kerf::ElementCutState::touched) == 1);
  }
  SUBCASE("all four values zero: the whole tet counts as above") {
    const kerf::ClippedTet clip = kerf::clip_tet(X, Eigen::Vector4d::Zero());
    CHECK(clip.tet_case == kerf::TetCutCase::all_zero);
    CHECK(clip.V_a == kerf_test::relative(V, 1e-15));
    CHECK(clip.below.empty());
    CHECK_FALSE(kerf::is_cut(clip.tet_case));
  }
  SUBCASE("x = 1 - 1e-4 leaves V_a / V = 1e-12: exact, and below the enrichment threshold") {
    const double s = 1e-4;
    const Eigen::Vector4d lambda(-(1.0 - s), s, -(1.0 - s), -(1.0 - s));
    const kerf::ClippedTet clip = kerf::clip_tet(X, lambda);
    check_clip(X, lambda, clip);
    CHECK(clip.V_a / V == kerf_test::relative(1e-12, 1e-9));
    CHECK_FALSE(kerf::minimum_volume_fraction_met(clip.V_a / V, clip.V_b / V));
    CHECK(kerf::minimum_volume_fraction_met(clip.V_a / V, clip.V_b / V, 1e-13));
    CHECK(kerf::minimum_volume_fraction_met(0.3, 0.7));
    CHECK_FALSE(kerf::minimum_volume_fraction_met(0.0, 1.0)); // uncut: nothing to enrich
    CHECK(kerf::default_minimum_volume_fraction == 1e-4);
  }
}

TEST_CASE("cut: the paper's beam with the half-depth cut at z = 0.1") {
  // Beam 0.03 x 0.06 x 0.2 m; the cut rectangle covers x in [0, 0.015] and all of y at z = 0.1.
  // Node (i, j, k) of make_box_mesh has index i + 4 (j + 7 k); we decide the expected classes
  // from these grid indices alone, without any level set.
  const Eigen::Vector3d box_min(0, 0, 0), box_max(0.03, 0.06, 0.2);
  const auto grid = [](int node) { return Eigen::Vector3i(node % 4, (node / 4) % 7, node / 28); };

  SUBCASE("20 cells along z: z = 0.1 is a plane of nodes, so nothing is cut, only touched") {
    const kerf::TetMesh mesh = kerf::make_box_mesh(box_min, box_max, {3, 6, 20});
    const kerf::RectangleCut cut({0, 0, 0.1}, {0.015, 0, 0}, {0, 0.06, 0});
    const kerf::LevelSet level_set = kerf::make_level_set(mesh, cut);
    CHECK((level_set.sign.array() == 0).count() == 4 * 7); // the node layer k = 10
    const kerf::MeshCutClassification classes = kerf::classify_mesh_cut(mesh, level_set, cut);
    std::array<int, 4> expected_case{};                   // by the number of corners at k = 10
    int expected_touched = 0;
    for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
      int on_plane = 0;
      bool in_rectangle = false;
      for (int a = 0; a < 4; ++a) {
        const Eigen::Vector3i g = grid(mesh.tets(t, a));
        if (g.z() == 10) {
          ++on_plane;
          in_rectangle = in_rectangle || g.x() <= 1; // x = 0 or 0.01 <= 0.015
        }
      }
      ++expected_case[static_cast<std::size_t>(on_plane)];
      expected_touched += in_rectangle;
    }
    using C = kerf::TetCutCase;
    CHECK(classes.count(C::uncut) == expected_case[0]);
    CHECK(classes.count(C::touched_vertex) == expected_case[1]);
    CHECK(classes.count(C::touched_edge) == expected_case[2]);
    CHECK(classes.count(C::touched_face) == expected_case[3]);
    // Each cell next to the plane has 2 tets on it by a face, 2 by an edge, 2 by a corner
    // (Kuhn's split), and there are 2 x 18 such cells.
    CHECK(classes.count(C::touched_face) == 72);
    CHECK(classes.count(C::touched_edge) == 72);
    CHECK(classes.count(C::touched_vertex) == 72);
    CHECK(classes.count(C::uncut) == 2160 - 216);
    for (C c : {C::cut_one_vertex_apart, C::cut_two_two, C::cut_through_vertex, C::cut_through_edge})
      CHECK(classes.count(c) == 0);
    CHECK(classes.count(kerf::ElementCutState::touched) == expected_touched);
    // By hand: the column x in [0, 0.01] gives all 6 tets of its 2 x 6 cells (72); in the column
    // x in [0.01, 0.02] a tet is touched if a corner on the plane has x = 0.01: 3 tets per cell
    // below the plane and 6 above (54); the column x >= 0.02 gives none.
    CHECK(classes.count(kerf::ElementCutState::touched) == 126);
    CHECK(classes.count(kerf::ElementCutState::partially_cut) == 0);
    CHECK(classes.count(kerf::ElementCutState::completely_cut) == 0);
  }

  SUBCASE("21 cells along z: z = 0.1 halves the layer k = 10") {
    const kerf::TetMesh mesh = kerf::make_box_mesh(box_min, box_max, {3, 6, 21});
    // At mid-height every crossing is an edge midpoint, with x index (i_bottom + i_top) / 2, so
    // a crossing lies in a rectangle x <= width (x index <= width / 0.01) when
    // i_bottom + i_top <= 2 width / 0.01. Border x = 0.015: sum <= 3, so some crossings lie
    // exactly on the border and count as inside (Paulus et al. use the closure); x = 0.0125: sum <= 2.
    // A tet is partially cut only if its section overlaps the rectangle in an area, which here
    // means a crossing strictly inside in x (sum < 2 width / 0.01): a section that reaches the
    // border x = 0.015 only at its edge lies beyond the cut.
    for (const auto& [width, max_index_sum, completely, partially] :
         {std::tuple{0.015, 3, 54, 0}, std::tuple{0.0125, 2, 36, 18}}) {
      CAPTURE(width);
      const kerf::RectangleCut cut({0, 0, 0.1}, {width, 0, 0}, {0, 0.06, 0});
      const kerf::LevelSet level_set = kerf::make_level_set(mesh, cut);
      CHECK((level_set.sign.array() == 0).count() == 0);
      const kerf::MeshCutClassification classes = kerf::classify_mesh_cut(mesh, level_set, cut);
      std::array<int, 4> expected_state{};
      int expected_one_apart = 0, expected_two_two = 0;
      for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
        int above = 0, below = 0, inside = 0, strictly_inside = 0, crossings = 0;
        for (int a = 0; a < 4; ++a) {
          const Eigen::Vector3i g = grid(mesh.tets(t, a));
          above += g.z() == 11;
          below += g.z() == 10;
        }
        if (above + below == 4 && above > 0 && below > 0) {
          (above == 2 ? expected_two_two : expected_one_apart) += 1;
          for (int a = 0; a < 4; ++a)
            for (int b = 0; b < 4; ++b) {
              const Eigen::Vector3i ga = grid(mesh.tets(t, a)), gb = grid(mesh.tets(t, b));
              if (ga.z() == 10 && gb.z() == 11) {
                ++crossings;
                inside += ga.x() + gb.x() <= max_index_sum;
                strictly_inside += 0.005 * (ga.x() + gb.x()) < width - 1e-12;
              }
            }
        }
        const auto state = crossings == 0                ? kerf::ElementCutState::uncut
                           : inside == crossings         ? kerf::ElementCutState::completely_cut
                           : strictly_inside > 0         ? kerf::ElementCutState::partially_cut
                                                         : kerf::ElementCutState::uncut;
        ++expected_state[static_cast<std::size_t>(state)];
      }
      using C = kerf::TetCutCase;
      CHECK(classes.count(C::cut_one_vertex_apart) == expected_one_apart);
      CHECK(classes.count(C::cut_two_two) == expected_two_two);
      CHECK(classes.count(C::cut_one_vertex_apart) == 72); // 4 of Kuhn's 6 tets, 18 cells
      CHECK(classes.count(C::cut_two_two) == 36);
      CHECK(classes.count(C::uncut) == 2268 - 108);
      for (int s = 0; s < 4; ++s)
        CHECK(classes.state_counts[static_cast<std::size_t>(s)] == expected_state[static_cast<std::size_t>(s)]);
      // By hand: cells with x in [0, 0.01] are completely cut (6 tets x 6 cells); in the column
      // x in [0.01, 0.02], border 0.015: 3 tets of 6 reach x <= 0.015 only, completely cut, and
      // the other 3 touch the border only with the edge of their section, uncut; border 0.0125
      // runs through the cells: 3 tets of 6 partially cut, the other 3 uncut.
      CHECK(classes.count(kerf::ElementCutState::completely_cut) == completely);
      CHECK(classes.count(kerf::ElementCutState::partially_cut) == partially);
      CHECK(classes.count(kerf::ElementCutState::touched) == 0);

      // Every cut tet of the layer clips with V_a + V_b = V, and the halves sum to half the layer.
      double V_a = 0.0, V_b = 0.0;
      for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
        if (!kerf::is_cut(classes.tet_case[static_cast<std::size_t>(t)])) continue;
        Corners X;
        Eigen::Vector4d lambda;
        for (int a = 0; a < 4; ++a) {
          X.row(a) = mesh.nodes.row(mesh.tets(t, a));
          lambda[a] = level_set.lambda[mesh.tets(t, a)];
        }
        const kerf::ClippedTet clip = kerf::clip_tet(X, lambda);
        check_clip(X, lambda, clip);
        V_a += clip.V_a;
        V_b += clip.V_b;
      }
      const double layer_volume = 0.03 * 0.06 * 0.2 / 21.0;
      CHECK(V_a == kerf_test::relative(layer_volume / 2, 1e-12));
      CHECK(V_b == kerf_test::relative(layer_volume / 2, 1e-12));
    }
  }
}

TEST_CASE("cut: partially cut is relative to the section: a round-off strip is not, 1e-3 of it is") {
  // A tet of 1 cm the plane z = 0 cuts in a right triangle with legs 0.005 m along x and y and
  // the leg x = 0 on the y axis: corner A below, B, C, D above, crossings at the midpoints of
  // AB, AC, AD. The rectangle covers x <= x1 (and much more than the section in y), so with
  // x1 = 0 it meets the section only along its leg x = 0, and with x1 = delta > 0 it covers a
  // strip of width delta along that leg: area about 0.005 delta of the section's 1.25e-5 m^2,
  // a fraction of about 4 delta / 0.01.
  Corners X;
  X << 0, 0, -0.01, 0.01, 0, 0.01, 0, 0.01, 0.01, 0, 0, 0.01;
  const Eigen::Vector4d lambda(-0.01, 0.01, 0.01, 0.01);
  REQUIRE(kerf::classify_tet_cut(lambda) == kerf::TetCutCase::cut_one_vertex_apart);
  const double section = 0.5 * 0.005 * 0.005;
  const double tolerance = 1e-12 * 0.01; // the order of default_snap_tolerance for a 1 cm mesh
  const auto state = [&](double x1) {
    const kerf::RectangleCut cut({-0.01, -0.01, 0}, {0.01 + x1, 0, 0}, {0, 0.03, 0});
    return kerf::classify_element_cut(X, lambda, cut, tolerance);
  };
  // 1e-9 m inside: an overlap of 5e-12 m^2, 4e-7 of the section, far below 1e-4 and far above
  // the old absolute rule's limit tolerance x diameter = 7e-17 m^2, which counted it as cut.
  CHECK(state(1e-9) == kerf::ElementCutState::uncut);
  CHECK(state(0.0) == kerf::ElementCutState::uncut);
  // 1e-3 of the section's width (5e-6 m) inside: 4e-3 of its area, partially cut.
  const double delta = 1e-3 * 0.005;
  CHECK(state(delta) == kerf::ElementCutState::partially_cut);
  // The threshold itself: just above a strip of area 1e-4 of the section it is cut, just below not.
  const double at_threshold = kerf::partial_cut_minimum_area_fraction * section / 0.005; // strip width, first order
  CHECK(state(0.5 * at_threshold) == kerf::ElementCutState::uncut);
  CHECK(state(2.0 * at_threshold) == kerf::ElementCutState::partially_cut);
  // The whole section inside: completely cut.
  CHECK(state(0.006) == kerf::ElementCutState::completely_cut);
}
