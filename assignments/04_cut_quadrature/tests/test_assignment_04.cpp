// Assignment 04's own test cases (assignments/04_cut_quadrature/README.md), for what the
// chapter's suites leave out: the moments at every degree the function accepts, one degree at
// a time (a rule of too low a degree is exact for even degrees and wrong for odd ones), on the
// unit tet and on a tet moved and scaled, against closed forms; and the degrees it refuses.
#include "kerf/quadrature/polyhedron_moments.hpp"
#include "kerf/quadrature/simplex_polynomials.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace {

// a! b! c! / (a + b + c + 3)!: the integral of x^a y^b z^c over the unit tet, in closed form.
double unit_tet_monomial(int a, int b, int c) {
  double value = 1.0;
  for (int k = 2; k <= a; ++k) value *= k;
  for (int k = 2; k <= b; ++k) value *= k;
  for (int k = 2; k <= c; ++k) value *= k;
  for (int k = 2; k <= a + b + c + 3; ++k) value /= k;
  return value;
}

// The unit tet's faces, counter-clockwise seen from outside (e1 x e2 the outward normal).
std::vector<std::vector<Eigen::Vector3d>> unit_tet_boundary(double scale, const Eigen::Vector3d& shift) {
  const Eigen::Vector3d o(0, 0, 0), x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  std::vector<std::vector<Eigen::Vector3d>> faces{{o, y, x}, {o, x, z}, {o, z, y}, {x, y, z}};
  for (auto& face : faces)
    for (Eigen::Vector3d& p : face) p = scale * p + shift;
  return faces;
}

} // namespace

TEST_CASE("polyhedron_monomial_moments: the unit tet's monomials at every degree 0..12, one degree at a time") {
  const auto boundary = unit_tet_boundary(1.0, Eigen::Vector3d::Zero());
  for (int degree = 0; degree <= 12; ++degree) {
    CAPTURE(degree);
    const Eigen::VectorXd moments = kerf::polyhedron_monomial_moments(boundary, degree);
    const std::vector<std::array<int, 3>> exponents = kerf::monomial_exponents_3d(degree);
    REQUIRE(moments.size() == static_cast<Eigen::Index>(exponents.size()));
    double worst = 0.0;
    for (std::size_t k = 0; k < exponents.size(); ++k) {
      const auto [a, b, c] = exponents[k];
      const double exact = unit_tet_monomial(a, b, c);
      worst = std::max(worst, std::abs(moments[static_cast<Eigen::Index>(k)] - exact) / exact);
    }
    // Sums of at most 4 * 49 products of order 1: round-off is a few 1e-15 relative (measured
    // below 1e-13 up to degree 12); a rule one degree short is off by percents.
    CHECK(worst <= 1e-11);
  }
}

TEST_CASE("polyhedron_monomial_moments: a tet scaled by 2 and moved, against the unit tet's moments mapped") {
  // On x = 2 xi + t: int x^a = int (2 xi + t)^a 8 dxi; for the monomials of degree <= 1 in closed
  // form: V = 8/6, int x = 8 (2/24 + t_x / 6).
  const Eigen::Vector3d t(0.3, -0.7, 0.45);
  const auto boundary = unit_tet_boundary(2.0, t);
  for (int degree = 1; degree <= 5; ++degree) {
    CAPTURE(degree);
    const Eigen::VectorXd moments = kerf::polyhedron_monomial_moments(boundary, degree);
    CHECK(moments[0] == kerf_test::relative(8.0 / 6.0, 1e-13));
    for (int c = 0; c < 3; ++c) CHECK(moments[1 + c] == kerf_test::relative(8.0 * (2.0 / 24.0 + t[c] / 6.0), 1e-13));
  }
}

TEST_CASE("polyhedron_monomial_moments: degrees outside 0..12 are refused with std::invalid_argument") {
  const auto boundary = unit_tet_boundary(1.0, Eigen::Vector3d::Zero());
  CHECK_THROWS_AS(kerf::polyhedron_monomial_moments(boundary, 13), std::invalid_argument);
  CHECK_THROWS_AS(kerf::polyhedron_monomial_moments(boundary, -1), std::invalid_argument);
  CHECK_NOTHROW(kerf::polyhedron_monomial_moments(boundary, 12));
}
