// Williams's near-front field (fracture/williams_field.hpp), checked against what it must satisfy
// rather than against a copy of its formulas: the closed-form gradient against central finite
// differences of the displacement, the closed-form stress against Hooke's law applied to that
// gradient, equilibrium (div sigma = 0 by finite differences of the stress), traction-free cut
// faces, the crack opening 8 K / E' sqrt(r / 2 pi), and the stress ahead of the front K / sqrt(2 pi r).
#include "kerf/fracture/williams_field.hpp"

#include "kerf/scene/displacement_file.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <random>

namespace {

const kerf::LinearMaterial material{300e3, 0.35, 1070};

// A front through (0.01, -0.02, 0.03) along a direction that is not a coordinate axis.
kerf::StraightFrontFrame tilted_front() {
  const Eigen::Matrix3d Q = (Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized())).toRotationMatrix();
  return kerf::make_straight_front_frame({0.01, -0.02, 0.03}, Q.col(0), Q.col(1));
}

// The point at polar (r, theta) and x_c = s about `front`.
Eigen::Vector3d at_polar(const kerf::StraightFrontFrame& front, double r, double theta, double s) {
  return front.origin + front.R * Eigen::Vector3d(r * std::cos(theta), r * std::sin(theta), s);
}

Eigen::Matrix3d hooke(const Eigen::Matrix3d& H) {
  const Eigen::Matrix3d eps = 0.5 * (H + H.transpose());
  return material.lambda() * eps.trace() * Eigen::Matrix3d::Identity() + 2.0 * material.mu() * eps;
}

const kerf::StressIntensityFactors mixed{1.3, -0.7, 0.45};

// Sample points: r in [1e-3, 1e-1], theta away from the cut faces by 0.05 (a finite-difference
// stencil must not cross them).
std::vector<Eigen::Vector3d> sample_points(const kerf::StraightFrontFrame& front) {
  std::mt19937 random(5);
  std::uniform_real_distribution<double> log_r(std::log(1e-3), std::log(1e-1)), theta(-std::numbers::pi + 0.05, std::numbers::pi - 0.05),
      along(-0.1, 0.1);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 40; ++i) points.push_back(at_polar(front, std::exp(log_r(random)), theta(random), along(random)));
  return points;
}

} // namespace

TEST_CASE("the closed-form displacement gradient matches central finite differences of the displacement") {
  const kerf::StraightFrontFrame front = tilted_front();
  for (const Eigen::Vector3d& x : sample_points(front)) {
    const double r = kerf::front_polar(front, x).r, h = 1e-5 * r;
    Eigen::Matrix3d fd;
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d e = h * Eigen::Vector3d::Unit(j);
      fd.col(j) = (kerf::williams_displacement(front, mixed, material, x + e) - kerf::williams_displacement(front, mixed, material, x - e)) / (2 * h);
    }
    const Eigen::Matrix3d H = kerf::williams_displacement_gradient(front, mixed, material, x);
    // Central differences err by h^2 |u'''| / 6 ~ (1e-5)^2 |H| (each r-derivative of sqrt(r)
    // brings 1/r) plus the round-off 1e-16 |u| / h ~ 1e-11 |H|: 1e-8 |H| is safe, a wrong term is O(|H|).
    CAPTURE(x.transpose());
    CHECK((H - fd).norm() <= 1e-8 * H.norm());
  }
}

TEST_CASE("the closed-form stress is Hooke's law of the gradient, satisfies equilibrium, and is symmetric") {
  const kerf::StraightFrontFrame front = tilted_front();
  for (const Eigen::Vector3d& x : sample_points(front)) {
    CAPTURE(x.transpose());
    const Eigen::Matrix3d S = kerf::williams_stress(front, mixed, material, x);
    // Two independent closed forms (the stress table and the derivative of the displacement
    // table): they agree to round-off.
    CHECK((S - hooke(kerf::williams_displacement_gradient(front, mixed, material, x))).norm() <= 1e-12 * S.norm());
    // Symmetric in the frame by construction; R S R^T keeps it so up to round-off.
    CHECK((S - S.transpose()).norm() <= 1e-14 * S.norm());
    // div sigma = sum_j d sigma_ij / dx_j by central differences; |div sigma| is of the order of
    // |sigma| / r for a wrong field, and the differences err by about (1e-5)^2 |sigma| / r.
    const double r = kerf::front_polar(front, x).r, h = 1e-5 * r;
    Eigen::Vector3d div = Eigen::Vector3d::Zero();
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d e = h * Eigen::Vector3d::Unit(j);
      div += (kerf::williams_stress(front, mixed, material, x + e) - kerf::williams_stress(front, mixed, material, x - e)).col(j) / (2 * h);
    }
    CHECK(div.norm() <= 1e-7 * S.norm() / r);
  }
}

TEST_CASE("the cut faces theta = +-pi are free of traction, and the faces open by the closed-form COD") {
  const kerf::StraightFrontFrame front = tilted_front();
  const Eigen::Vector3d b = front.R.col(1);
  const double E_prime = material.young / (1 - material.poisson * material.poisson);
  for (const double r : {1e-4, 3e-3, 0.2}) {
    CAPTURE(r);
    const double scale = std::max({mixed.K_I, std::abs(mixed.K_II), mixed.K_III}) / std::sqrt(2 * std::numbers::pi * r);
    // theta = +-(pi - 1e-11): the faces' limits, 1e-11 r off the cut, far above the round-off
    // of placing the point (1e-16 times the origin's 0.04 m), so each point is on its own side.
    const double t = std::numbers::pi - 1e-11;
    const Eigen::Vector3d upper = at_polar(front, r, t, 0.02), lower = at_polar(front, r, -t, 0.02);
    // The traction sigma b is O(1e-11) of the stress scale there; a wrong field gives O(1).
    for (const Eigen::Vector3d& x : {upper, lower}) CHECK((kerf::williams_stress(front, mixed, material, x) * b).norm() <= 1e-10 * scale);
    // The jump of u across the cut, in the frame: mode I opens it (b), mode II slides it (a),
    // mode III tears it (c): 8 K / E' sqrt(r / 2 pi) for I and II, 4 K_III / mu sqrt(r / 2 pi).
    const Eigen::Vector3d jump = front.R.transpose() * (kerf::williams_displacement(front, mixed, material, upper) -
                                                        kerf::williams_displacement(front, mixed, material, lower));
    const double root = std::sqrt(r / (2 * std::numbers::pi));
    const Eigen::Vector3d expected(8 * mixed.K_II / E_prime * root, 8 * mixed.K_I / E_prime * root, 4 * mixed.K_III / material.mu() * root);
    CHECK((jump - expected).norm() <= 1e-10 * expected.norm());
  }
}

TEST_CASE("ahead of the front the stress is K / sqrt(2 pi r) per mode, and the faces behind it take the + side") {
  const kerf::StraightFrontFrame front = tilted_front();
  const double r = 2e-3, s = 1 / std::sqrt(2 * std::numbers::pi * r);
  const Eigen::Vector3d ahead = at_polar(front, r, 0.0, -0.05);
  const Eigen::Matrix3d S = front.R.transpose() * kerf::williams_stress(front, mixed, material, ahead) * front.R;
  CHECK(S(1, 1) == kerf_test::relative(mixed.K_I * s, 1e-13));   // opening stress
  CHECK(S(0, 0) == kerf_test::relative(mixed.K_I * s, 1e-13));   // mode II adds no sigma_aa at theta = 0
  CHECK(S(0, 1) == kerf_test::relative(mixed.K_II * s, 1e-13));  // shear
  CHECK(S(1, 2) == kerf_test::relative(mixed.K_III * s, 1e-13)); // tearing
  CHECK(S(2, 2) == kerf_test::relative(material.poisson * 2 * mixed.K_I * s, 1e-13));
  // On the plane of the cut behind the front both zeros give theta = pi (a frame along the axes,
  // so that the points lie exactly on the plane).
  const kerf::StraightFrontFrame axes = kerf::make_straight_front_frame({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  CHECK(kerf::front_polar(axes, {-1.0, -0.0, 0.0}).theta == std::numbers::pi);
  CHECK(kerf::front_polar(axes, {-1.0, 0.0, 0.0}).theta == std::numbers::pi);
}

TEST_CASE("the field is singular on the front, and a frame needs two perpendicular directions") {
  const kerf::StraightFrontFrame front = kerf::make_straight_front_frame({0.1, 0.2, 0.3}, {0, 1, 0}, {0, 0, 1});
  const Eigen::Vector3d on_front(0.7, 0.2, 0.3);
  CHECK(kerf::williams_displacement(front, mixed, material, on_front).norm() == 0.0);
  CHECK_THROWS_AS(kerf::williams_displacement_gradient(front, mixed, material, on_front), std::invalid_argument);
  CHECK_THROWS_AS(kerf::williams_stress(front, mixed, material, on_front), std::invalid_argument);
  CHECK_THROWS_AS(kerf::make_straight_front_frame({0, 0, 0}, {1, 0, 0}, {1, 1e-3, 0}), std::invalid_argument);
  CHECK_THROWS_AS(kerf::make_straight_front_frame({0, 0, 0}, {0, 0, 0}, {0, 1, 0}), std::invalid_argument);
  const kerf::StraightFrontFrame frame = kerf::make_straight_front_frame({0, 0, 0}, {2, 0, 0}, {0, 0, 3});
  CHECK((frame.R.transpose() * frame.R - Eigen::Matrix3d::Identity()).norm() <= 1e-15);
  CHECK(frame.R.determinant() == kerf_test::relative(1.0));
}

TEST_CASE("the field written at points reads back as a displacement file with the same doubles") {
  const kerf::StraightFrontFrame front = tilted_front();
  const auto points_vector = sample_points(front);
  Eigen::MatrixXd points(static_cast<Eigen::Index>(points_vector.size()), 3);
  for (std::size_t i = 0; i < points_vector.size(); ++i) points.row(static_cast<Eigen::Index>(i)) = points_vector[i].transpose();
  const auto file = std::filesystem::current_path() / "work" / "williams_field" / "williams.csv";
  kerf::write_williams_displacement_file(file, front, mixed, material, points);
  const kerf::DisplacementFile table = kerf::read_displacement_file(file);
  // 17 significant digits round-trip every double exactly.
  CHECK(table.positions == points);
  CHECK(table.displacements == kerf::williams_displacements_at(front, mixed, material, points));
}
