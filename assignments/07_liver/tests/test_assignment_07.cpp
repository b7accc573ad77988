// Assignment 07's own test cases (assignments/07_liver/README.md), for what the chapter's suite
// leaves out: ends a hair off the triangle's plane, which exact predicates put on their side and a
// tolerance would put on the sheet; and the crossing point's parameter in closed form.
#include "kerf/cut/semi_progressive_cut.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <Eigen/Dense>

namespace {

// The triangle z = 1/4 over (0, 0), (2, 0), (0, 2): dyadic, so that the exact answers are known.
const kerf::SweptTriangle sheet{Eigen::Vector3d(0, 0, 0.25), Eigen::Vector3d(2, 0, 0.25), Eigen::Vector3d(0, 2, 0.25)};

} // namespace

TEST_CASE("edge_triangle_contact: ends 1e-12 off the plane are on their side, not on the sheet") {
  for (const double offset : {1e-12, 1e-9, 1e-6}) {
    CAPTURE(offset);
    // Both ends above, one a hair above: neither on the sheet, not crossed.
    const kerf::EdgeTriangleContact above = kerf::edge_triangle_contact(sheet, {0.5, 0.5, 0.25 + offset}, {0.5, 0.5, 1.0});
    CHECK_FALSE(above.end_on_sheet[0]);
    CHECK_FALSE(above.end_on_sheet[1]);
    CHECK_FALSE(above.crossed);
    // One end a hair below: crossed, at s = h_a / (h_a - h_b) = (1/4 - z) / (1 - z) from that end.
    const double z = 0.25 - offset; // rounded; 0.25 - z is then exact (Sterbenz)
    const kerf::EdgeTriangleContact below = kerf::edge_triangle_contact(sheet, {0.5, 0.5, z}, {0.5, 0.5, 1.0});
    CHECK_FALSE(below.end_on_sheet[0]);
    CHECK(below.crossed);
    CHECK(below.parameter == kerf_test::relative((0.25 - z) / (1.0 - z), 1e-12));
  }
  // Exactly in the plane: on the sheet, not crossed.
  const kerf::EdgeTriangleContact on = kerf::edge_triangle_contact(sheet, {0.5, 0.5, 0.25}, {0.5, 0.5, 1.0});
  CHECK(on.end_on_sheet[0]);
  CHECK_FALSE(on.crossed);
}

TEST_CASE("edge_triangle_contact: the crossing parameter s = h_a / (h_a - h_b) from either end") {
  // An edge from z = 0 to z = 1 through z = 1/4: s = 1/4 from x_a, 3/4 the other way round.
  const kerf::EdgeTriangleContact up = kerf::edge_triangle_contact(sheet, {0.5, 0.25, 0.0}, {0.25, 0.5, 1.0});
  REQUIRE(up.crossed);
  CHECK(up.parameter == kerf_test::relative(0.25, 1e-15));
  const kerf::EdgeTriangleContact down = kerf::edge_triangle_contact(sheet, {0.25, 0.5, 1.0}, {0.5, 0.25, 0.0});
  REQUIRE(down.crossed);
  CHECK(down.parameter == kerf_test::relative(0.75, 1e-15));
  // Beside the triangle (x + y > 2 at z = 1/4): not crossed.
  CHECK_FALSE(kerf::edge_triangle_contact(sheet, {1.5, 1.5, 0.0}, {1.5, 1.5, 1.0}).crossed);
}
