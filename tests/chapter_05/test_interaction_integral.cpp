// The interaction integral in domain form (fracture/interaction_integral.hpp), fed Williams's
// exact gradients on tet meshes of a slab around a straight front that runs through the middle
// of elements. With the exact field the integral's only errors are the quadrature's over the
// ring where q falls (the field is smooth there, q is C1 at the ring's edges) and none from the
// front itself (q is flat around it), so K must come out close to its value and closer as the
// mesh refines; these tests measure how close, for modes I, II and III and mixed mode, and check
// that the answer does not depend on the domain's radii.
#include "kerf/fracture/interaction_integral.hpp"

#include "kerf/mesh/box_mesh.hpp"

#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

namespace {

const kerf::LinearMaterial material{300e3, 0.35, 1070};

// The slab [-1, 1] x [-1, 1] x [0, 0.5] (m) with n x n x n/4 cells, and a front along z through
// (0.0137, -0.0071): off every node plane of the ladder, so it crosses elements in their middle.
kerf::TetMesh slab(int n) { return kerf::make_box_mesh({-1, -1, 0}, {1, 1, 0.5}, Eigen::Vector3i(n, n, std::max(1, n / 4))); }

// The front's frame: a turned by `angle` about z from +x (the cut lies behind, at x_a < 0).
kerf::StraightFrontFrame front(double angle) {
  const Eigen::Vector3d a(std::cos(angle), std::sin(angle), 0.0), b(-std::sin(angle), std::cos(angle), 0.0);
  return kerf::make_straight_front_frame({0.0137, -0.0071, 0.0}, a, b);
}

kerf::InteractionDomain domain(const kerf::StraightFrontFrame& f, double inner, double outer) {
  kerf::InteractionDomain d;
  d.front = f;
  d.front_begin = 0.0;
  d.front_end = 0.5;
  d.end_ramp = 0.1;
  d.inner_radius = inner;
  d.outer_radius = outer;
  return d;
}

// K of the exact Williams field with factors K on `mesh`, relative error of each mode against the
// largest of the three.
Eigen::Vector3d relative_errors(const kerf::TetMesh& mesh, const kerf::InteractionDomain& d, const kerf::StressIntensityFactors& K) {
  const auto exact_gradient = [&](Eigen::Index, const Eigen::Vector3d& x) { return kerf::williams_displacement_gradient(d.front, K, material, x); };
  const kerf::StressIntensityFactors measured = kerf::interaction_integral_sifs(mesh, exact_gradient, material, d);
  const double scale = std::max({std::abs(K.K_I), std::abs(K.K_II), std::abs(K.K_III)});
  return Eigen::Vector3d(measured.K_I - K.K_I, measured.K_II - K.K_II, measured.K_III - K.K_III).cwiseAbs() / scale;
}

} // namespace

TEST_CASE("K_I and K_II of the exact field within 2e-4 on the finest mesh, modes I, II and mixed, the error falling as the mesh refines") {
  // The front turned by 0.5 rad from the mesh's axes, so that the cut's plane crosses the tets
  // obliquely. What is left is the Gauss rule's error over the ring where q falls: the field is
  // smooth there, but q's second derivative jumps at the ring's edges, and the ring is 1.6
  // elements wide on the coarsest mesh. The mode-III factor that a mode-II field shows
  // (cross-talk) is the weak spot: w's ramps make q vary along the front close to it, where the
  // c-term of the integrand (sigma_ic du2_i/dx_a + sigma2_ic du_i/dx_a, mode-II field against the
  // mode-III auxiliary field) grows like 1/r, which a Gauss rule integrates with an error of O(h).
  const kerf::StraightFrontFrame f = front(0.5);
  const kerf::InteractionDomain d = domain(f, 0.2, 0.6);
  const kerf::StressIntensityFactors cases[] = {{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {1.0, -0.6, 0.0}};
  for (const kerf::StressIntensityFactors& K : cases) {
    std::vector<Eigen::Vector3d> errors;
    for (const int n : {8, 16, 32}) errors.push_back(relative_errors(slab(n), d, K));
    MESSAGE("K_I " << K.K_I << ", K_II " << K.K_II << ": relative errors of K_I, K_II, K_III on 8, 16, 32 cells: " << errors[0].transpose()
                   << " / " << errors[1].transpose() << " / " << errors[2].transpose());
    CAPTURE(K.K_I);
    CAPTURE(K.K_II);
    // The target is 1 % on the finest mesh for an FE field; with the exact field the
    // integral itself must do 50 times better, and 4 times better than on the coarse mesh.
    const double coarse = errors[0].head<2>().maxCoeff(), fine = errors[2].head<2>().maxCoeff();
    CHECK(fine <= 2e-4);
    CHECK(fine <= coarse / 4);
    // The O(h) cross-talk: 2e-3 on the finest mesh (measured up to 1.0e-3), falling too.
    CHECK(errors[2][2] <= 2e-3);
    CHECK(errors[2][2] <= std::max(errors[0][2], 1e-4));
  }
}

TEST_CASE("K does not depend on the domain's radii") {
  const kerf::StraightFrontFrame f = front(0.5);
  const kerf::TetMesh mesh = slab(32);
  const kerf::StressIntensityFactors K{1.0, -0.6, 0.0};
  for (const auto& [inner, outer] : {std::pair{0.1, 0.4}, std::pair{0.2, 0.6}, std::pair{0.3, 0.8}, std::pair{0.0, 0.5}}) {
    CAPTURE(inner);
    CAPTURE(outer);
    const Eigen::Vector3d errors = relative_errors(mesh, domain(f, inner, outer), K);
    MESSAGE("radii " << inner << ", " << outer << ": relative errors of K_I, K_II, K_III " << errors.transpose());
    // The bounds of the test above: each domain gives the exact K_I and K_II up to its quadrature
    // error. Even the domain with inner radius 0, whose q falls from the front itself so that
    // the Gauss points of the tets along the front see the 1/r integrand, stays within them.
    CHECK(errors.head<2>().maxCoeff() <= 2e-4);
    CHECK(errors[2] <= 2e-3);
  }
}

TEST_CASE("mode III: K_III within 1e-3, its cross-talk into K_II within 3e-3 on the finest mesh") {
  // Mode III is the weak case: w's ramps along the front make q vary along c close to the front,
  // where the c-term sigma_ic du2_i/dx_a + sigma2_ic du_i/dx_a of a mode-III field against the
  // mode-II auxiliary field grows like 1/r; a Gauss rule integrates it with an error of O(h).
  // Measured: K_II error 3.4e-2, 7.2e-3, 2.1e-3 on 8, 16, 32 cells; K_III 1.5e-4, 5.5e-4, 7.1e-5.
  const kerf::InteractionDomain d = domain(front(0.5), 0.2, 0.6);
  const Eigen::Vector3d coarse = relative_errors(slab(8), d, {0.0, 0.0, 1.0});
  const Eigen::Vector3d fine = relative_errors(slab(32), d, {0.0, 0.0, 1.0});
  MESSAGE("mode III, relative errors of K_I, K_II, K_III on 8 and 32 cells: " << coarse.transpose() << " / " << fine.transpose());
  CHECK(fine[2] <= 1e-3);
  CHECK(fine.maxCoeff() <= 3e-3);
  CHECK(fine[1] <= coarse[1] / 4);
}

TEST_CASE("the weight q: its gradient matches finite differences, and L_q is the integral of w along the front") {
  kerf::InteractionDomain d = domain(front(0.5), 0.2, 0.6);
  for (const Eigen::Vector3d& y : {Eigen::Vector3d(0.3, 0.1, 0.05), Eigen::Vector3d(-0.25, -0.2, 0.47), Eigen::Vector3d(0.1, 0.1, 0.25),
                                  Eigen::Vector3d(-0.05, 0.5, 0.42)}) {
    const Eigen::Vector3d x = d.front.origin + d.front.R * y;
    Eigen::Vector3d gradient, unused;
    d.weight(x, gradient);
    Eigen::Vector3d fd;
    const double h = 1e-6;
    for (int j = 0; j < 3; ++j)
      fd[j] = (d.weight(x + h * Eigen::Vector3d::Unit(j), unused) - d.weight(x - h * Eigen::Vector3d::Unit(j), unused)) / (2 * h);
    CAPTURE(y.transpose());
    // q is a product of cubics in r and in x_c: central differences err by h^2 times its third
    // derivatives (~1e3 here), 1e-9, and round-off 1e-16 / h = 1e-10.
    CHECK((gradient - fd).norm() <= 1e-8);
  }
  // w along the front (r = 0) by the midpoint rule with 10^5 points: error ~ 1e-10.
  double integral = 0.0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3d unused;
    integral += d.weight(d.front.origin + d.front.R.col(2) * ((i + 0.5) / n * 0.5), unused) * 0.5 / n;
  }
  CHECK(integral == doctest::Approx(d.weighted_front_length()).epsilon(1e-9));
}

TEST_CASE("a domain that reaches the mesh's boundary, and a domain out of range, are refused") {
  const kerf::TetMesh mesh = slab(4);
  const auto zero = [](Eigen::Index, const Eigen::Vector3d&) { return Eigen::Matrix3d::Zero().eval(); };
  // Outer radius 1.2 m: the ring crosses the slab's sides at x, y = +-1.
  CHECK_THROWS_WITH_AS(kerf::interaction_integral_sifs(mesh, zero, material, domain(front(0.0), 0.2, 1.2)),
                       doctest::Contains("reaches the mesh's boundary"), std::invalid_argument);
  // A segment longer than the slab (0.5 m): w > 0 on its face z = 0.5.
  kerf::InteractionDomain long_segment = domain(front(0.0), 0.2, 0.6);
  long_segment.front_end = 0.7;
  CHECK_THROWS_WITH_AS(kerf::interaction_integral_sifs(mesh, zero, material, long_segment), doctest::Contains("reaches the mesh's boundary"),
                       std::invalid_argument);
  kerf::InteractionDomain bad = domain(front(0.0), 0.6, 0.2);
  CHECK_THROWS_WITH_AS(kerf::interaction_integral_sifs(mesh, zero, material, bad), doctest::Contains("outer_radius"), std::invalid_argument);
  bad = domain(front(0.0), 0.2, 0.6);
  bad.end_ramp = 0.3;
  CHECK_THROWS_WITH_AS(kerf::interaction_integral_sifs(mesh, zero, material, bad), doctest::Contains("end_ramp"), std::invalid_argument);
  // A field with no strain has no K (and the domain that fits is accepted).
  const kerf::StressIntensityFactors none = kerf::interaction_integral_sifs(mesh, zero, material, domain(front(0.0), 0.2, 0.6));
  CHECK(none.K_I == 0.0);
  CHECK(none.K_II == 0.0);
  CHECK(none.K_III == 0.0);
}
