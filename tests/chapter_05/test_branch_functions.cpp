// The four branch functions (xfem/branch_functions.hpp): closed-form gradients against central
// finite differences, the jump of F_1 across the cut and the continuity of the others, the
// shifted form, and the Williams mode-I field as a combination of them in the front's frame.
#include "kerf/cut/crack_front.hpp"
#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/fem/tet_shape_functions.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/xfem/branch_functions.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

namespace {

constexpr double pi = std::numbers::pi;

// A straight front in a general direction: the rectangle's edge at the far end of edge1, inside
// the box [0, 1]^3 (the other three edges far outside).
struct TiltedFront {
  kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {2, 2, 2});
  Eigen::Vector3d a, b, c, point;
  kerf::CrackFronts fronts;
  TiltedFront() {
    const Eigen::Matrix3d rotation =
        (Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()) * Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX())).toRotationMatrix();
    const Eigen::Vector3d e1 = rotation * Eigen::Vector3d::UnitX(), e2 = rotation * Eigen::Vector3d::UnitY();
    point = Eigen::Vector3d(0.5, 0.5, 0.5);
    // The front is the edge through `point` along e2; the rectangle lies behind it along -e1.
    const kerf::RectangleCut cut(point - 3.0 * e1 - 3.0 * e2, 3.0 * e1, 6.0 * e2);
    fronts = kerf::find_crack_fronts(mesh, kerf::CutSurfaces({kerf::rectangle_surface(cut)}));
    b = e1.cross(e2).normalized();
    a = e1;
    c = a.cross(b);
  }
};

} // namespace

TEST_CASE("the closed-form gradients of F_1..F_4 agree with central differences at random points") {
  const TiltedFront f;
  REQUIRE(f.fronts.polylines.size() == 1);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double worst = 0.0;
  int tested = 0;
  for (int k = 0; k < 500; ++k) {
    const Eigen::Vector3d x(u(rng), u(rng), u(rng));
    const kerf::FrontPolar p = f.fronts.polar(x);
    // Away from the cut (where F_1 jumps) by more than the step.
    if (p.r < 1e-3 || std::abs(std::abs(p.theta) - pi) < 1e-3) continue;
    const kerf::BranchValues v = kerf::branch_functions(p);
    // Step 1e-5 r: truncation O(step^2 F''') ~ 1e-10 relative, round-off 1e-16 / 1e-5 = 1e-11.
    const double h = 1e-5 * p.r;
    for (int d = 0; d < 3; ++d) {
      const Eigen::Vector3d dx = h * Eigen::Vector3d::Unit(d);
      const Eigen::Vector4d fd = (kerf::branch_functions(f.fronts.polar(x + dx)).F - kerf::branch_functions(f.fronts.polar(x - dx)).F) / (2 * h);
      for (int l = 0; l < 4; ++l) worst = std::max(worst, std::abs(fd(l) - v.dF_dx(l, d)) / v.dF_dx.row(l).norm());
    }
    ++tested;
  }
  CHECK(tested > 400);
  MESSAGE("largest relative difference " << worst);
  CHECK(worst < 1e-6);
}

TEST_CASE("the branch functions in closed form at r = 1/4, theta = pi/3, and F_1 = +-sqrt(r) on the cut's two faces") {
  // sqrt(r) = 1/2, sin(pi/6) = 1/2, cos(pi/6) = sin(pi/3) = sqrt(3)/2.
  const Eigen::Vector4d at = kerf::branch_function_values(0.25, pi / 3);
  const double s3 = std::sqrt(3.0);
  CHECK(at(0) == kerf_test::relative(0.25, 1e-14));    // 1/2 sin(pi/6)
  CHECK(at(1) == kerf_test::relative(s3 / 4, 1e-14));  // 1/2 cos(pi/6)
  CHECK(at(2) == kerf_test::relative(s3 / 8, 1e-14));  // 1/2 sin(pi/6) sin(pi/3)
  CHECK(at(3) == kerf_test::relative(3.0 / 8, 1e-14)); // 1/2 cos(pi/6) sin(pi/3)
  // On the faces theta = +-pi: F_1 = +-sqrt(r), F_2 = 0, and F_3 = F_4 = 0 (sin(pi) = 0).
  for (const double side : {1.0, -1.0}) {
    const Eigen::Vector4d face = kerf::branch_function_values(0.09, side * pi);
    CHECK(face(0) == kerf_test::relative(side * 0.3, 1e-14));
    CHECK(std::abs(face(1)) < 1e-15);
    CHECK(std::abs(face(2)) < 1e-15);
    CHECK(std::abs(face(3)) < 1e-15);
  }
}

TEST_CASE("the frame derivatives are the central differences of F in x_a and x_b") {
  // F at (x_a, x_b) through its polar coordinates; theta kept 0.1 from the cut, where atan2 wraps.
  const auto F = [](double xa, double xb) { return kerf::branch_function_values(std::hypot(xa, xb), std::atan2(xb, xa)); };
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> radius(0.01, 1.0), angle(-pi + 0.1, pi - 0.1);
  double worst = 0.0;
  for (int k = 0; k < 200; ++k) {
    const double r = radius(rng), theta = angle(rng), xa = r * std::cos(theta), xb = r * std::sin(theta);
    const Eigen::Matrix<double, 4, 2> d = kerf::branch_function_frame_derivatives(r, theta);
    // Step 1e-5 r: truncation ~ 1e-10 relative, round-off 1e-16 / 1e-5 = 1e-11.
    const double h = 1e-5 * r;
    const Eigen::Vector4d d_a = (F(xa + h, xb) - F(xa - h, xb)) / (2 * h), d_b = (F(xa, xb + h) - F(xa, xb - h)) / (2 * h);
    // Relative to the whole matrix (~ 1 / sqrt(r)): a row of it vanishes where theta = 0 (F_3, F_4).
    const double scale = d.norm();
    for (int l = 0; l < 4; ++l) {
      worst = std::max({worst, std::abs(d_a(l) - d(l, 0)) / scale, std::abs(d_b(l) - d(l, 1)) / scale});
    }
  }
  MESSAGE("largest relative difference " << worst);
  CHECK(worst < 1e-6);
}

TEST_CASE("F_1 jumps by 2 sqrt(r) across the cut, F_2..F_4 are continuous, all vanish on the front") {
  const TiltedFront f;
  for (const double behind : {0.01, 0.1, 0.3}) {
    // Points just above and below the cut, a distance `behind` behind the front.
    const Eigen::Vector3d on_cut = f.point - behind * f.a + 0.1 * f.c;
    const Eigen::Vector4d above = kerf::branch_functions(f.fronts.polar(on_cut + 1e-13 * f.b)).F;
    const Eigen::Vector4d below = kerf::branch_functions(f.fronts.polar(on_cut - 1e-13 * f.b)).F;
    // r = behind to 1e-13, theta = +-(pi - 1e-13 / behind): jump 2 sqrt(r) cos(1e-13 / (2 behind)).
    CHECK(std::abs((above(0) - below(0)) - 2.0 * std::sqrt(behind)) < 1e-10);
    for (int l = 1; l < 4; ++l) CHECK(std::abs(above(l) - below(l)) < 1e-10);
    // The two values a node on the cut can take, by its side.
    CHECK(kerf::branch_function_values(f.fronts.polar(on_cut, +1).r, f.fronts.polar(on_cut, +1).theta)(0) ==
          kerf_test::relative(std::sqrt(behind), 1e-12));
    CHECK(kerf::branch_function_values(f.fronts.polar(on_cut, -1).r, f.fronts.polar(on_cut, -1).theta)(0) ==
          kerf_test::relative(-std::sqrt(behind), 1e-12));
  }
  // Exactly on the front: zero values and a zero (not NaN) gradient.
  const kerf::BranchValues zero = kerf::branch_functions(f.fronts.polar(f.point + 0.2 * f.c));
  CHECK(zero.F.norm() < 1e-7);
  CHECK(zero.dF_dx.allFinite());
}

TEST_CASE("the shifted functions vanish at their node and their gradient agrees with central differences") {
  const TiltedFront f;
  // A tet next to the front and its Tet4 shape functions.
  Eigen::Matrix<double, 4, 3> X;
  X << 0.45, 0.40, 0.42, 0.70, 0.45, 0.48, 0.50, 0.72, 0.50, 0.47, 0.50, 0.75;
  double det_J = 0.0;
  const Eigen::Matrix<double, 4, 3> grad_N = kerf::physical_shape_gradients<4>(X, kerf::tet4_shape_gradients(), det_J);
  REQUIRE(det_J > 0.0);
  const auto shape = [&](const Eigen::Vector3d& x) {
    Eigen::Matrix3d J;
    for (int k = 0; k < 3; ++k) J.col(k) = (X.row(k + 1) - X.row(0)).transpose();
    return kerf::tet4_shape(J.inverse() * (x - X.row(0).transpose()));
  };
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double worst = 0.0;
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d xi = X.row(i).transpose();
    const kerf::FrontPolar pi_node = f.fronts.polar(xi);
    const Eigen::Vector4d at_node = kerf::branch_function_values(pi_node.r, pi_node.theta);
    const kerf::BranchValues at_own_node =
        kerf::shifted_branch_functions(shape(xi)(i), grad_N.row(i).transpose(), kerf::branch_functions(pi_node), at_node);
    CHECK(at_own_node.F.norm() < 1e-15);
    for (int k = 0; k < 50; ++k) {
      Eigen::Vector4d lambda(u(rng), u(rng), u(rng), u(rng));
      lambda /= lambda.sum();
      const Eigen::Vector3d x = X.transpose() * lambda;
      const kerf::FrontPolar p = f.fronts.polar(x);
      if (p.r < 1e-3 || std::abs(std::abs(p.theta) - pi) < 1e-3) continue;
      const auto value = [&](const Eigen::Vector3d& y) {
        return kerf::shifted_branch_functions(shape(y)(i), grad_N.row(i).transpose(), kerf::branch_functions(f.fronts.polar(y)), at_node);
      };
      const kerf::BranchValues v = value(x);
      const double h = 1e-5 * p.r;
      for (int d = 0; d < 3; ++d) {
        const Eigen::Vector3d dx = h * Eigen::Vector3d::Unit(d);
        const Eigen::Vector4d fd = (value(x + dx).F - value(x - dx).F) / (2 * h);
        for (int l = 0; l < 4; ++l) worst = std::max(worst, std::abs(fd(l) - v.dF_dx(l, d)) / v.dF_dx.row(l).norm());
      }
    }
  }
  MESSAGE("largest relative difference " << worst);
  CHECK(worst < 1e-6);
}

TEST_CASE("the Williams mode-I field is (K_I / (2 mu sqrt(2 pi))) ((kappa - 1) F_2 + F_3, (kappa + 1) F_1 - F_4) in the frame") {
  // A front along -y at x = 0.4, z = 0.55 of the box, the cut behind it (x < 0.4), normal +z:
  // the Williams field written in global coordinates with x_a = x - 0.4, x_b = z - 0.55, and
  // compared with the combination of the branch functions the frame gives, as a vector field.
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {4, 4, 4});
  const kerf::RectangleCut cut({-0.1, -0.1, 0.55}, {0.5, 0, 0}, {0, 1.2, 0});
  const kerf::CrackFronts fronts = kerf::find_crack_fronts(mesh, kerf::CutSurfaces({kerf::rectangle_surface(cut)}));
  const double E = 3e5, nu = 0.35, mu = E / (2 * (1 + nu)), kappa = 3 - 4 * nu, K = 1e3;
  const auto williams = [&](const Eigen::Vector3d& x) {
    const double xa = x.x() - 0.4, xb = x.z() - 0.55, r = std::hypot(xa, xb), t = std::atan2(xb, xa);
    const double k = K / (2 * mu) * std::sqrt(r / (2 * pi));
    const double ua = k * std::cos(t / 2) * (kappa - 1 + 2 * std::sin(t / 2) * std::sin(t / 2));
    const double ub = k * std::sin(t / 2) * (kappa + 1 - 2 * std::cos(t / 2) * std::cos(t / 2));
    return Eigen::Vector3d(ua, 0.0, ub); // a = +x, b = +z
  };
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double worst = 0.0, scale = 0.0;
  for (int k = 0; k < 300; ++k) {
    const Eigen::Vector3d x(u(rng), u(rng), u(rng));
    const kerf::FrontPolar p = fronts.polar(x);
    const Eigen::Vector4d F = kerf::branch_functions(p).F;
    const double factor = K / (2 * mu * std::sqrt(2 * pi));
    const Eigen::Vector3d from_F = factor * (((kappa - 1) * F(1) + F(2)) * p.a + ((kappa + 1) * F(0) - F(3)) * p.b);
    worst = std::max(worst, (from_F - williams(x)).norm());
    scale = std::max(scale, williams(x).norm());
  }
  CHECK(scale > 0.0);
  CHECK(worst < 1e-13 * scale);
  // The opening: above the cut u_b > 0, below u_b < 0 (mode I opens the crack).
  CHECK(williams({0.2, 0.5, 0.55 + 1e-9}).z() > 0.0);
  CHECK(williams({0.2, 0.5, 0.55 - 1e-9}).z() < 0.0);
}

TEST_CASE("on a curved (polyline) front the gradient includes the frame's turning and agrees with central differences") {
  // The arc of radius R = 0.8 of a planar cut (a fan about a centre outside the box), 64 chords.
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {3, 3, 3});
  const Eigen::Vector3d centre(-0.3, 0.5, 0.5);
  const double R = 0.8;
  const int n = 64;
  kerf::TriangleSurface fan;
  fan.vertices.resize(n + 2, 3);
  fan.vertices.row(0) = centre.transpose();
  for (int k = 0; k <= n; ++k) {
    const double phi = -1.7 + 3.4 * k / n;
    fan.vertices.row(k + 1) = (centre + R * Eigen::Vector3d(std::cos(phi), std::sin(phi), 0.0)).transpose();
  }
  fan.triangles.resize(n, 3);
  for (int k = 0; k < n; ++k) fan.triangles.row(k) << 0, k + 1, k + 2;
  const kerf::CrackFronts fronts = kerf::find_crack_fronts(mesh, kerf::CutSurfaces({fan}));
  REQUIRE(fronts.polylines.size() == 1);
  for (const double r : {0.02, 0.08}) {
    double worst = 0.0, frame_constant = 0.0;
    for (int k = 0; k < 20; ++k) {
      const double phi = -0.4 + 0.8 * k / 19.0, psi = -2.5 + 5.0 * k / 19.0;
      const Eigen::Vector3d radial(std::cos(phi), std::sin(phi), 0.0);
      const Eigen::Vector3d x = centre + (R + r * std::cos(psi)) * radial + r * std::sin(psi) * Eigen::Vector3d::UnitZ();
      const kerf::FrontPolar p = fronts.polar(x);
      const kerf::BranchValues v = kerf::branch_functions(p);
      // Paulus's gradient, the frame held constant.
      const Eigen::Matrix<double, 4, 2> dF = kerf::branch_function_frame_derivatives(p.r, p.theta);
      const Eigen::Matrix<double, 4, 3> constant = dF.col(0) * p.a.transpose() + dF.col(1) * p.b.transpose();
      const double h = 1e-6;
      for (int d = 0; d < 3; ++d) {
        const Eigen::Vector3d dx = h * Eigen::Vector3d::Unit(d);
        const Eigen::Vector4d fd = (kerf::branch_functions(fronts.polar(x + dx)).F - kerf::branch_functions(fronts.polar(x - dx)).F) / (2 * h);
        for (int l = 0; l < 4; ++l) {
          worst = std::max(worst, std::abs(fd(l) - v.dF_dx(l, d)) / v.dF_dx.row(l).norm());
          frame_constant = std::max(frame_constant, std::abs(fd(l) - constant(l, d)) / v.dF_dx.row(l).norm());
        }
      }
    }
    MESSAGE("curved front, r = " << r << ": largest relative difference to central differences " << worst
                                  << ", with the frame held constant " << frame_constant);
    // Step 1e-6 at r >= 0.02: truncation ~ (h / r)^2 = 2.5e-9, round-off 1e-16 / 1e-6 = 1e-10.
    // The points stay inside segments (the gradient kinks at vertices, where the foot changes
    // segment), at most 1e-6 from a vertex with probability about 1e-4: none here.
    CHECK(worst < 1e-6);
    // Holding the frame constant misses up to half the chords' kink (0.053 rad / 2).
    CHECK(frame_constant > 0.005);
  }
}
