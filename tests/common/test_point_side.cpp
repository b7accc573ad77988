// The side of a point against a triangle-mesh cut (cut/point_side.hpp): Paulus's closest-
// triangle test is wrong in a wedge at a kink sharper than a right angle, the angle-weighted
// pseudo-normal test is right everywhere off the surface.
#include "kerf/cut/height_field_surface.hpp"
#include "kerf/cut/point_side.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <random>

namespace {

// The ridge z = -s |x| (s > 0) or the valley z = s |x| (s < 0 gives -s |x| with the sign
// flipped: we pass the signed slope), over [-1, 1]^2 on 2 x 2 cells, so that the kink x = 0 is
// a grid line. Normals point up (+z).
kerf::TriangleSurface roof(double signed_slope) {
  return kerf::height_field_surface([signed_slope](double x, double) { return -signed_slope * std::abs(x); }, 0.0, {-1.0, -1.0}, {1.0, 1.0},
                                    {2, 2});
}

int analytic_side(double signed_slope, const Eigen::Vector3d& x) { return x.z() > -signed_slope * std::abs(x.x()) ? 1 : -1; }

struct WrongCounts {
  int points = 0, closest = 0, pseudo = 0;
};

// Random points of [-0.5, 0.5]^2 x [-1.5, 1] (the surface reaches x, y = +-1, so the closest point
// of every such point is an inner point of the surface), at least 1e-9 off it.
WrongCounts count_wrong(double signed_slope, int count) {
  const kerf::TriangleSurface surface = roof(signed_slope);
  const kerf::PseudoNormals normals = kerf::angle_weighted_pseudo_normals(surface);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  WrongCounts c;
  while (c.points < count) {
    const Eigen::Vector3d x(unit(random) - 0.5, unit(random) - 0.5, -1.5 + 2.5 * unit(random));
    if (std::abs(x.z() + signed_slope * std::abs(x.x())) < 1e-9) continue;
    const int truth = analytic_side(signed_slope, x);
    ++c.points;
    c.closest += kerf::closest_triangle_side(surface, x) != truth;
    c.pseudo += kerf::pseudo_normal_side(surface, normals, x) != truth;
  }
  return c;
}

} // namespace

TEST_CASE("closest surface point: inside a face, on an edge, at a vertex") {
  const kerf::TriangleSurface surface = roof(0.0); // the plane z = 0 on 2 x 2 cells
  kerf::ClosestSurfacePoint c = kerf::closest_surface_point(surface, {0.3, 0.6, 0.25});
  CHECK(c.feature == kerf::TriangleFeature::face);
  CHECK(c.distance == kerf_test::relative(0.25, 1e-15));
  CHECK((c.point - Eigen::Vector3d(0.3, 0.6, 0.0)).norm() < 1e-15);
  // Beyond the side x = 1: the closest point is on the boundary edge, at (1, 0.5, 0).
  c = kerf::closest_surface_point(surface, {1.5, 0.5, 0.0});
  CHECK(c.feature == kerf::TriangleFeature::edge);
  CHECK(c.distance == kerf_test::relative(0.5, 1e-15));
  // Beyond the corner (1, 1): the vertex.
  c = kerf::closest_surface_point(surface, {2.0, 3.0, 0.0});
  CHECK(c.feature == kerf::TriangleFeature::vertex);
  CHECK((surface.vertices.row(c.a).transpose() - Eigen::Vector3d(1, 1, 0)).norm() == 0.0);
}

TEST_CASE("a point above a sharp ridge: the closest-triangle test says below, the pseudo-normal says above") {
  // z = -3 |x|: the normals (-3, 0, 1) and (3, 0, 1) are 143 degrees apart. The point
  // (0.3, 0.5, 0.5) is above the ridge; its closest point on both planks is the ridge line
  // (0, 0.5, 0), a tie that goes to the lower-numbered triangle, the plank x < 0, whose plane
  // has it below: (x - P0) . (-3, 0, 1) = -0.9 + 0.5 < 0.
  const kerf::TriangleSurface surface = roof(3.0);
  const Eigen::Vector3d x(0.3, 0.5, 0.5);
  const kerf::ClosestSurfacePoint c = kerf::closest_surface_point(surface, x);
  CHECK(c.feature == kerf::TriangleFeature::edge);
  CHECK(std::abs(c.point.x()) < 1e-15);
  CHECK(kerf::closest_triangle_side(surface, x) == -1);
  CHECK(kerf::pseudo_normal_side(surface, kerf::angle_weighted_pseudo_normals(surface), x) == 1);
}

TEST_CASE("random points: the pseudo-normal test is never wrong, the closest-triangle test only past a right angle") {
  constexpr int count = 20000;
  // A gentle ridge and valley (normals 53 degrees apart): both tests right everywhere.
  for (const double slope : {0.5, -0.5}) {
    CAPTURE(slope);
    const WrongCounts c = count_wrong(slope, count);
    CHECK(c.closest == 0);
    CHECK(c.pseudo == 0);
  }
  // A sharp ridge z = -3 |x|: the points whose closest point is the ridge line and whose tie
  // goes to the plank x < 0 are put below where (x, z) . (-3, 1) < 0, i.e. for x / 3 < z < 3 x
  // (the wedge between the right plank's normal and the left plank's plane). Its area in the
  // sampled box [-0.5, 0.5] x [-1.5, 1] is int_0^{1/3} (3x - x/3) dx + int_{1/3}^{1/2} (1 - x/3) dx
  // = 7/24, a fraction 7/60 = 0.1167 of the box's 2.5; with 20000 points the count's standard
  // deviation is 0.0023, and we allow 4 of them.
  const WrongCounts ridge = count_wrong(3.0, count);
  CHECK(ridge.pseudo == 0);
  CHECK(static_cast<double>(ridge.closest) / count == kerf_test::relative(7.0 / 60.0, 0.01 / (7.0 / 60.0)));
  // The sharp valley z = 3 |x|: below it, the tie goes to the plank x < 0, whose plane has the
  // point above where 3 x + z > 0, i.e. for -3 x < z < -x / 3: an area int_0^{1/2} (8/3) x dx = 1/3,
  // a fraction 2/15 = 0.1333 of the box (standard deviation 0.0024).
  const WrongCounts valley = count_wrong(-3.0, count);
  CHECK(valley.pseudo == 0);
  CHECK(static_cast<double>(valley.closest) / count == kerf_test::relative(2.0 / 15.0, 0.01 / (2.0 / 15.0)));
}
