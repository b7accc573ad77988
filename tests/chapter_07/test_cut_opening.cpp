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
