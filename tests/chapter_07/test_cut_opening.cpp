// The opening of a cut (xfem/cut_opening.hpp): the jump of the field across the cut, summed
// over it. Two fields whose jump is known in closed form, on the tilted plane through the unit
// box that test_cut_faces.cpp cuts too (tilted_plane_cut.hpp: it crosses every column of tets
// and passes through no node):
// - each side moved by d along the normal away from the plane (chapter 4's u_i and a_k): the
//   jump is 2 d n at every point, so the normal opening is 2 d everywhere, V_gap = 2 d A_cut;
// - an affine field u = G X, continuous (every enrichment 0): the jump across 2 eps is
//   2 eps G n, the normal opening 2 eps n.G n, the same at every point.
// A_cut must be the plane's area in the box, sqrt(1 + 0.17^2), to within the sub-triangles the
// box's faces cut through.
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/point_locator.hpp"
#include "kerf/xfem/cut_opening.hpp"

#include "chapter_07/tilted_plane_cut.hpp"
#include "support/cut_body.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>

namespace {

using namespace tilted_cut;

// The sub-triangles the box's boundary can cut through: its perimeter in the plane (two sides
// of length 1, two of sqrt(1 + 0.17^2)) times a sub-triangle's diameter. The rectangle's
// triangles have legs of 3 m and 3.04 m and a 4.3 m hypotenuse, m = ceil(4.3 / spacing) steps.
double area_tolerance(double spacing) {
  const double perimeter = 2.0 + 2.0 * area_in_box();
  const double steps = std::ceil(std::sqrt(9.0 + 9.0 * (1.0 + plane_slope * plane_slope)) / spacing);
  const double diameter = std::sqrt(9.0 + 9.0 * (1.0 + plane_slope * plane_slope)) / steps;
  return perimeter * diameter;
}

} // namespace

TEST_CASE("cut opening: two sides moved apart by 2 d open by 2 d everywhere, over the cut's area in the body") {
  const support::CutBody body(kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {4, 4, 4}), {tilted_plane()}, {3000.0, 0.45, 1000.0});
  const kerf::PointLocator locator(body.mesh);
  const double d = 2.5e-3;
  for (const double spacing : {0.1, 0.02}) {
    CAPTURE(spacing);
    const kerf::CutOpening opening = kerf::measure_cut_opening(body.model, locator, separated_sides(body, d), {tilted_plane()}, spacing, 1e-7);
    CHECK(opening.samples > 0);
    CHECK(std::abs(opening.area - area_in_box()) <= area_tolerance(spacing));
    CHECK(opening.mean_opening() == kerf_test::relative(2.0 * d, 1e-12));
    CHECK(opening.gap_volume == kerf_test::relative(2.0 * d * opening.area, 1e-12));
    CHECK(opening.max_normal_opening == kerf_test::relative(2.0 * d, 1e-12));
    CHECK(opening.max_jump == kerf_test::relative(2.0 * d, 1e-12));
  }
  // The finer sampling finds the area more closely: within 2 % here.
  const kerf::CutOpening fine = kerf::measure_cut_opening(body.model, locator, separated_sides(body, d), {tilted_plane()}, 0.01, 1e-7);
  CHECK(fine.area == kerf_test::relative(area_in_box(), 0.02));
}

TEST_CASE("cut opening: a continuous field jumps by 2 eps G n only, so an unopened cut measures no opening") {
  const support::CutBody body(kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {4, 4, 4}), {tilted_plane()}, {3000.0, 0.45, 1000.0});
  const kerf::PointLocator locator(body.mesh);
  Eigen::Matrix3d G;
  G << 0.01, -0.02, 0.005, 0.003, 0.015, -0.01, 0.02, 0.004, -0.012;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * body.model.num_dof_nodes());
  for (Eigen::Index i = 0; i < body.mesh.num_nodes(); ++i) u.segment<3>(3 * i) = G * body.mesh.nodes.row(i).transpose();
  const double eps = 1e-4;
  const kerf::CutOpening opening = kerf::measure_cut_opening(body.model, locator, u, {tilted_plane()}, 0.05, eps);
  const Eigen::Vector3d n = plane_normal();
  REQUIRE(opening.samples > 0);
  CHECK(opening.mean_opening() == kerf_test::relative(2.0 * eps * n.dot(G * n), 1e-9));
  CHECK(opening.max_jump == kerf_test::relative(2.0 * eps * (G * n).norm(), 1e-9));
}

TEST_CASE("cut opening: a cut outside the body measures nothing, and bad arguments are refused") {
  const support::CutBody body(kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {4, 4, 4}), {tilted_plane()}, {3000.0, 0.45, 1000.0});
  const kerf::PointLocator locator(body.mesh);
  const Eigen::VectorXd u = separated_sides(body, 1e-3);
  const kerf::TriangleSurface far_away = kerf::rectangle_surface(kerf::RectangleCut({5, 5, 5}, {1, 0, 0}, {0, 1, 0}));
  const kerf::CutOpening none = kerf::measure_cut_opening(body.model, locator, u, {far_away}, 0.1, 1e-7);
  CHECK(none.samples == 0);
  CHECK(none.area == 0.0);
  CHECK(none.mean_opening() == 0.0);
  CHECK(none.max_normal_opening == 0.0);
  CHECK_THROWS_AS(kerf::measure_cut_opening(body.model, locator, u, {tilted_plane()}, 0.0, 1e-7), std::invalid_argument);
  CHECK_THROWS_AS(kerf::measure_cut_opening(body.model, locator, u, {tilted_plane()}, 0.1, -1.0), std::invalid_argument);
  CHECK_THROWS_AS(kerf::measure_cut_opening(body.model, locator, u, {tilted_plane()}, 0.1, std::nan("")), std::invalid_argument);
  CHECK_THROWS_AS(kerf::measure_cut_opening(body.model, locator, u.head(3), {tilted_plane()}, 0.1, 1e-7), std::invalid_argument);
}

TEST_CASE("cut opening: sample points kept across a growing cut are the points a fresh sampling finds, and so is the opening") {
  // A cut grows as chapters 7 and 8 grow theirs: the same first surface, then a second one, then
  // the first with one triangle moved. Each update keeps the triangles it has seen and locates
  // the others; what it holds must be what sampling the cuts afresh holds, point by point.
  const support::CutBody body(kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {4, 4, 4}), {tilted_plane()}, {3000.0, 0.45, 1000.0});
  const kerf::PointLocator locator(body.mesh);
  const double spacing = 0.05, eps = 1e-7;
  const auto points_of = [&](const kerf::CutSamplePoints& points) {
    std::vector<kerf::CutSamplePoints::Sample> all;
    points.for_each_sample([&](const kerf::CutSamplePoints::Sample& s) { all.push_back(s); });
    return all;
  };
  kerf::TriangleSurface second = kerf::rectangle_surface(kerf::RectangleCut({0.5, 0.2, 0.5}, {1, 0, 0}, {0, 0, 1}));
  kerf::TriangleSurface moved = tilted_plane();
  moved.vertices.row(moved.triangles(0, 0)).z() += 0.01;
  kerf::CutSamplePoints grown(locator, spacing, eps);
  for (const std::vector<kerf::TriangleSurface>& cuts : {std::vector{tilted_plane()}, std::vector{tilted_plane(), second}, std::vector{moved, second}}) {
    grown.update(cuts);
    kerf::CutSamplePoints fresh(locator, spacing, eps);
    fresh.update(cuts);
    const auto kept = points_of(grown), found = points_of(fresh);
    REQUIRE(kept.size() == found.size());
    for (std::size_t k = 0; k < kept.size(); ++k) {
      CHECK(kept[k].area == found[k].area);
      CHECK(kept[k].n == found[k].n);
      CHECK(kept[k].above.X == found[k].above.X);
      CHECK(kept[k].above.tet == found[k].above.tet);
      CHECK(kept[k].below.X == found[k].below.X);
      CHECK(kept[k].below.tet == found[k].below.tet);
    }
  }
  // The opening on the grown points is the one-call opening of the whole cut.
  const Eigen::VectorXd u = separated_sides(body, 2.5e-3);
  const kerf::CutOpening from_grown = kerf::CutOpeningSampler(body.model, grown).measure(u);
  const kerf::CutOpening at_once = kerf::measure_cut_opening(body.model, locator, u, {moved, second}, spacing, eps);
  CHECK(from_grown.samples == at_once.samples);
  CHECK(from_grown.gap_volume == at_once.gap_volume);
  CHECK(from_grown.area == at_once.area);
}
