// The fronts of cuts that end inside a mesh (cut/crack_front.hpp): which boundary edges are
// front, how they chain, the frame's orientation, the polar coordinates against their closed form
// for a straight front, and their continuity along a curved (polyline) front.
#include "kerf/cut/crack_front.hpp"
#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace {

constexpr double pi = std::numbers::pi;

kerf::CrackFronts fronts_of(const kerf::TetMesh& mesh, std::vector<kerf::TriangleSurface> surfaces) {
  const kerf::CutSurfaces cuts(std::move(surfaces));
  return kerf::find_crack_fronts(mesh, cuts);
}

// A fan of n triangles about `centre` in the plane z = height: the arc of radius R from angle
// phi0 to phi1 is its outer boundary, oriented so that the normals point to +z.
kerf::TriangleSurface arc_fan(const Eigen::Vector3d& centre, double R, double phi0, double phi1, int n) {
  kerf::TriangleSurface s;
  s.vertices.resize(n + 2, 3);
  s.vertices.row(0) = centre.transpose();
  for (int k = 0; k <= n; ++k) {
    const double phi = phi0 + (phi1 - phi0) * k / n;
    s.vertices.row(k + 1) = (centre + R * Eigen::Vector3d(std::cos(phi), std::sin(phi), 0.0)).transpose();
  }
  s.triangles.resize(n, 3);
  for (int k = 0; k < n; ++k) s.triangles.row(k) << 0, k + 1, k + 2;
  return s;
}

} // namespace

TEST_CASE("a rectangle ending mid-element has one straight front: the edge inside the mesh, with a ahead and b the normal") {
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {4, 4, 4});
  // x in [-0.1, 0.4], y in [-0.1, 1.1], z = 0.55: three edges lie outside the box, the edge
  // x = 0.4 crosses it from y = 0 to y = 1. Normal edge1 x edge2 = +z.
  const kerf::RectangleCut cut({-0.1, -0.1, 0.55}, {0.5, 0, 0}, {0, 1.2, 0});
  const kerf::CrackFronts fronts = fronts_of(mesh, {kerf::rectangle_surface(cut)});
  REQUIRE(fronts.polylines.size() == 1);
  CHECK(fronts.length() == kerf_test::relative(1.0, 1e-12));
  const kerf::FrontPolyline& line = fronts.polylines[0];
  CHECK_FALSE(line.closed);
  for (const kerf::FrontSegment& s : line.segments) {
    CHECK((s.a - Eigen::Vector3d(1, 0, 0)).norm() < 1e-14); // ahead: +x, into the uncut material
    CHECK((s.b - Eigen::Vector3d(0, 0, 1)).norm() < 1e-14); // the rectangle's normal
    CHECK((s.c - s.a.cross(s.b)).norm() < 1e-14);           // right-handed, c = a x b = -y
    CHECK(std::abs(s.start.x() - 0.4) < 1e-14);
    CHECK(std::abs(s.start.z() - 0.55) < 1e-14);
  }
  // The ends are where the edge leaves the box.
  CHECK(std::abs(line.points.front().y() - 1.0) < 1e-12);
  CHECK(std::abs(line.points.back().y()) < 1e-12);

  // Polar coordinates: the closed form r = |(x - 0.4, z - 0.55)|, theta = atan2(z - 0.55, x - 0.4).
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double worst = 0.0;
  for (int k = 0; k < 200; ++k) {
    const Eigen::Vector3d x(u(rng), u(rng), u(rng));
    const kerf::FrontPolar p = fronts.polar(x);
    worst = std::max(worst, std::abs(p.r - std::hypot(x.x() - 0.4, x.z() - 0.55)));
    worst = std::max(worst, std::abs(p.theta - std::atan2(x.z() - 0.55, x.x() - 0.4)));
  }
  CHECK(worst < 1e-14);
  // On the cut behind the front: theta = +pi (the range (-pi, pi]), or the side the caller names.
  CHECK(fronts.polar({0.2, 0.5, 0.55}).theta == pi);
  CHECK(fronts.polar({0.2, 0.5, 0.55}, -1).theta == -pi);
  CHECK(fronts.polar({0.2, 0.5, 0.55}, +1).theta == pi);
  CHECK(fronts.polar({0.2, 0.5, 0.55 + 1e-9}).theta > 0.0);
  CHECK(fronts.polar({0.2, 0.5, 0.55 - 1e-9}).theta < 0.0);
  CHECK(fronts.distance({0.4, 0.5, 0.75}) == kerf_test::relative(0.2, 1e-14));
}

TEST_CASE("edges outside the mesh or in its skin are not front; a flipped rectangle flips c, not a") {
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {4, 4, 4});
  // x in [0, 0.4], y in [0, 1]: the edges x = 0, y = 0 and y = 1 lie in the box's faces.
  const kerf::RectangleCut flush({0, 0, 0.55}, {0.4, 0, 0}, {0, 1, 0});
  const kerf::CrackFronts f1 = fronts_of(mesh, {kerf::rectangle_surface(flush)});
  REQUIRE(f1.polylines.size() == 1);
  CHECK(f1.length() == kerf_test::relative(1.0, 1e-12));
  CHECK((f1.polylines[0].segments[0].a - Eigen::Vector3d(1, 0, 0)).norm() < 1e-14);
  // The same rectangle with its edges swapped: normal -z, so b = -z, a still +x, c = a x b = +y.
  const kerf::RectangleCut flipped({0, 0, 0.55}, {0, 1, 0}, {0.4, 0, 0});
  const kerf::CrackFronts f2 = fronts_of(mesh, {kerf::rectangle_surface(flipped)});
  REQUIRE(f2.polylines.size() == 1);
  const kerf::FrontSegment& s = f2.polylines[0].segments[0];
  CHECK((s.a - Eigen::Vector3d(1, 0, 0)).norm() < 1e-14);
  CHECK((s.b - Eigen::Vector3d(0, 0, -1)).norm() < 1e-14);
  CHECK((s.c - Eigen::Vector3d(0, 1, 0)).norm() < 1e-14);
  // theta > 0 is still the side b points to: here below z = 0.55.
  CHECK(f2.polar({0.2, 0.5, 0.5}).theta > pi / 2);
  // A cut that crosses the whole mesh has no front.
  const kerf::RectangleCut through({-1, -1, 0.55}, {3, 0, 0}, {0, 3, 0});
  CHECK(fronts_of(mesh, {kerf::rectangle_surface(through)}).empty());
}

TEST_CASE("a rectangle inside the mesh has one closed front of four segments; two cuts have two fronts") {
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {3, 3, 3});
  const kerf::RectangleCut inner({0.2, 0.3, 0.45}, {0.5, 0, 0}, {0, 0.4, 0});
  const kerf::CrackFronts loop = fronts_of(mesh, {kerf::rectangle_surface(inner)});
  REQUIRE(loop.polylines.size() == 1);
  CHECK(loop.polylines[0].closed);
  CHECK(loop.num_segments() == 4);
  CHECK(loop.length() == kerf_test::relative(1.8, 1e-12));
  // Every segment's a points out of the rectangle: from its centre to the segment's middle.
  const Eigen::Vector3d centre(0.45, 0.5, 0.45);
  for (const kerf::FrontSegment& s : loop.polylines[0].segments) CHECK(s.a.dot(0.5 * (s.start + s.end) - centre) > 0.0);
  const kerf::RectangleCut other({-0.5, -0.5, 0.8}, {1.2, 0, 0}, {0, 2, 0});
  const kerf::CrackFronts two = fronts_of(mesh, {kerf::rectangle_surface(inner), kerf::rectangle_surface(other)});
  CHECK(two.polylines.size() == 2);
  CHECK(two.length() == kerf_test::relative(1.8 + 1.0, 1e-12));
}

TEST_CASE("a curved front: the arc inside the box, with polar coordinates continuous across its vertices") {
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {3, 3, 3});
  // Centre outside the box, arc radius 0.8 from -100 to +100 degrees: the arc enters and leaves
  // the box through y = 0 and y = 1; the radial edges lie at x < 0, outside.
  const Eigen::Vector3d centre(-0.3, 0.5, 0.5);
  const double R = 0.8;
  const int n = 40;
  const double phi0 = -100.0 * pi / 180.0, phi1 = 100.0 * pi / 180.0;
  const kerf::CrackFronts fronts = fronts_of(mesh, {arc_fan(centre, R, phi0, phi1, n)});
  REQUIRE(fronts.polylines.size() == 1);
  const kerf::FrontPolyline& line = fronts.polylines[0];
  // The chords' parts with 0 <= y <= 1 (their x stays inside [0, 1]), summed in closed form.
  double expected = 0.0;
  for (int k = 0; k < n; ++k) {
    const double pa = phi0 + (phi1 - phi0) * k / n, pb = phi0 + (phi1 - phi0) * (k + 1) / n;
    const Eigen::Vector2d p(centre.x() + R * std::cos(pa), centre.y() + R * std::sin(pa));
    const Eigen::Vector2d q(centre.x() + R * std::cos(pb), centre.y() + R * std::sin(pb));
    // y is monotone on each chord here (phi in (-pi/2, pi/2) where it matters).
    const double t0 = std::clamp((0.0 - p.y()) / (q.y() - p.y()), 0.0, 1.0), t1 = std::clamp((1.0 - p.y()) / (q.y() - p.y()), 0.0, 1.0);
    expected += std::abs(t1 - t0) * (q - p).norm();
  }
  CHECK(fronts.length() == kerf_test::relative(expected, 1e-12));
  CHECK(std::abs(std::abs(line.points.front().y() - 0.5) - 0.5) < 1e-12);
  CHECK(std::abs(std::abs(line.points.back().y() - 0.5) - 0.5) < 1e-12);
  for (const kerf::FrontSegment& s : line.segments) {
    CHECK((s.b - Eigen::Vector3d(0, 0, 1)).norm() < 1e-14);
    CHECK(s.a.dot(0.5 * (s.start + s.end) - centre) > 0.0); // ahead = outwards from the centre
  }

  // Walk along the front at a fixed (rho, psi) about the true circle: theta must follow psi
  // within the polyline's error and never jump, also across the vertices. A frame that is
  // constant per segment would jump by up to the kink angle h = 5 degrees (0.087 rad) there.
  for (const double psi : {0.3, 2.0, -2.8, 3.0}) {
    const double rho = 0.05;
    double previous_theta = 0.0, previous_r = 0.0, largest_jump = 0.0, largest_r_jump = 0.0, worst_theta = 0.0;
    double previous_naive = 0.0, largest_naive_jump = 0.0;
    const int samples = 4000;
    for (int k = 0; k <= samples; ++k) {
      const double phi = -0.5 + 1.0 * k / samples; // inside |phi| < phi_exit = 0.675
      const Eigen::Vector3d radial(std::cos(phi), std::sin(phi), 0.0);
      const Eigen::Vector3d x = centre + (R + rho * std::cos(psi)) * radial + rho * std::sin(psi) * Eigen::Vector3d::UnitZ();
      const kerf::FrontPolar p = fronts.polar(x);
      worst_theta = std::max(worst_theta, std::abs(p.theta - psi));
      // Paulus's frame for comparison: the closest point of the polyline and its segment's frame.
      double closest = 1e300, naive = 0.0;
      for (const kerf::FrontSegment& s : line.segments) {
        const Eigen::Vector3d e = s.end - s.start;
        const Eigen::Vector3d foot = s.start + std::clamp((x - s.start).dot(e) / e.squaredNorm(), 0.0, 1.0) * e;
        if ((x - foot).norm() >= closest) continue;
        closest = (x - foot).norm();
        naive = std::atan2((x - foot).dot(s.b), (x - foot).dot(s.a));
      }
      if (k > 0) {
        largest_jump = std::max(largest_jump, std::abs(p.theta - previous_theta));
        largest_r_jump = std::max(largest_r_jump, std::abs(p.r - previous_r));
        largest_naive_jump = std::max(largest_naive_jump, std::abs(naive - previous_naive));
      }
      previous_theta = p.theta;
      previous_r = p.r;
      previous_naive = naive;
    }
    MESSAGE("psi = " << psi << ": largest theta step " << largest_jump << " (a frame constant per segment: " << largest_naive_jump
                     << "), largest r step " << largest_r_jump << ", largest |theta - psi| " << worst_theta);
    // A sample step is 2.5e-4 rad of arc; theta and r change smoothly by O(rho/R) of that
    // per step plus the chords' wobble, O(h) over a segment: 1e-3 is 80 times below a jump.
    CHECK(largest_jump < 1e-3);
    // In a plane, Paulus's closest-point frame is continuous behind the front (the closest
    // distance is); ahead, in the wedge of a vertex, it drops x_c and jumps (a twisted cut, next
    // test case, makes it jump everywhere).
    if (psi == 0.3) CHECK(largest_naive_jump > 10 * largest_jump);
    CHECK(largest_r_jump < 1e-4);
    // The chord lies up to R (1 - cos(h/2)) = 7.6e-4 inside the circle: a shift of the origin
    // by that much moves theta by up to about 7.6e-4 / rho = 0.015.
    CHECK(worst_theta < 0.03);
  }
}

TEST_CASE("a straight front of a twisted cut: theta continuous where a frame constant per segment jumps by the twist") {
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {3, 3, 3});
  // The front x = 0.5, z = 0.5 along y (from -0.5 to 1.5, beyond the box); behind it a strip
  // 0.8 wide whose direction turns by phi(y) = 0.4 (y - 0.5) about y: 16 segments, each pair of
  // neighbouring triangles' normals 0.05 rad apart.
  const int n = 16;
  kerf::TriangleSurface strip;
  strip.vertices.resize(2 * (n + 1), 3);
  for (int k = 0; k <= n; ++k) {
    const double y = -0.5 + 2.0 * k / n, phi = 0.4 * (y - 0.5);
    strip.vertices.row(2 * k) << 0.5, y, 0.5;
    strip.vertices.row(2 * k + 1) << 0.5 - 0.8 * std::cos(phi), y, 0.5 - 0.8 * std::sin(phi);
  }
  strip.triangles.resize(2 * n, 3);
  for (int k = 0; k < n; ++k) {
    strip.triangles.row(2 * k) << 2 * k, 2 * k + 1, 2 * k + 2;
    strip.triangles.row(2 * k + 1) << 2 * k + 1, 2 * k + 3, 2 * k + 2;
  }
  const kerf::CrackFronts fronts = fronts_of(mesh, {strip});
  REQUIRE(fronts.polylines.size() == 1);
  CHECK(fronts.length() == kerf_test::relative(1.0, 1e-12));
  const kerf::FrontPolyline& line = fronts.polylines[0];
  for (const double psi : {0.5, 2.5, -2.0}) {
    const double rho = 0.1;
    double previous = 0.0, previous_naive = 0.0, largest = 0.0, largest_naive = 0.0;
    const int samples = 2000;
    for (int k = 0; k <= samples; ++k) {
      const Eigen::Vector3d x(0.5 + rho * std::cos(psi), 0.02 + 0.96 * k / samples, 0.5 + rho * std::sin(psi));
      const double theta = fronts.polar(x).theta;
      // The segment whose closest point is nearest, with its own frame (Paulus).
      double closest = 1e300, naive = 0.0;
      for (const kerf::FrontSegment& s : line.segments) {
        const Eigen::Vector3d e = s.end - s.start;
        const Eigen::Vector3d foot = s.start + std::clamp((x - s.start).dot(e) / e.squaredNorm(), 0.0, 1.0) * e;
        if ((x - foot).norm() >= closest - 1e-15) continue;
        closest = (x - foot).norm();
        naive = std::atan2((x - foot).dot(s.b), (x - foot).dot(s.a));
      }
      if (k > 0) {
        largest = std::max(largest, std::abs(theta - previous));
        largest_naive = std::max(largest_naive, std::abs(naive - previous_naive));
      }
      previous = theta;
      previous_naive = naive;
    }
    MESSAGE("twisted cut, psi = " << psi << ": largest theta step " << largest << ", with a frame constant per segment " << largest_naive);
    // A step is 4.8e-4 in y; theta turns with the frame at 0.4 rad per unit y (2e-4 per step):
    // the interpolated frame stays below 1e-3; the constant one jumps by the 0.05 rad between
    // neighbouring triangles' normals at every vertex.
    CHECK(largest < 1e-3);
    CHECK(largest_naive > 0.04);
  }
  // The coordinates' gradients include the normal's turning along the front: central
  // differences of x_a and x_b agree (step 1e-6 at r = 0.1: truncation ~1e-10).
  double worst = 0.0;
  for (int k = 0; k < 30; ++k) {
    const double psi = -3.0 + 6.0 * k / 29.0;
    const Eigen::Vector3d x(0.5 + 0.1 * std::cos(psi), 0.03 + 0.031 * k, 0.5 + 0.1 * std::sin(psi));
    const kerf::FrontPolar p = fronts.polar(x);
    for (int d = 0; d < 3; ++d) {
      const Eigen::Vector3d dx = 1e-6 * Eigen::Vector3d::Unit(d);
      const kerf::FrontPolar plus = fronts.polar(x + dx), minus = fronts.polar(x - dx);
      worst = std::max(worst, std::abs((plus.x_a - minus.x_a) / 2e-6 - p.grad_x_a(d)));
      worst = std::max(worst, std::abs((plus.x_b - minus.x_b) / 2e-6 - p.grad_x_b(d)));
    }
  }
  MESSAGE("twisted cut: largest difference of grad x_a, grad x_b to central differences " << worst);
  CHECK(worst < 1e-6);
}
