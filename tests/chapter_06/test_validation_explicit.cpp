// The central difference forced above its critical step, on the demo's
// flap (coarse: 3 x 2 x 6 cells), linear XFEM, per-piece lumped mass, gravity from t = 0.
// Three claims, each against something independent of the integrator:
//  - its estimate 2 / omega_max (power iteration, critical_time_step.hpp) is the true critical
//    step, omega_max from a dense generalized eigensolver (Eigen, LAPACK-style QR on M^-1/2 K M^-1/2);
//  - below it the run is bounded by the modal solution: from rest under a constant load each
//    mode follows q_n = q_s (1 - cos n theta) exactly (cos theta = 1 - omega^2 dt^2 / 2), and
//    with v_n = (q_{n+1} - q_{n-1}) / (2 dt) its energy is at most (2 + 1/2) omega^2 q_s^2, so
//    the total stays below 2.5 f . u_s, u_s the static solution;
//  - above it the energy grows every step by |z|^2, z the top mode's larger root of
//    z^2 - b z + 1 = 0, b = 2 - omega_max^2 dt^2.
#include "../examples/cut_dynamics_scenes.hpp"
#include "kerf/dynamics/central_difference.hpp"
#include "kerf/solve/linear_solver.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <vector>

namespace {

struct ExplicitFlap {
  std::unique_ptr<cut_dynamics::CutDynamicBody> body = cut_dynamics::demo_flap({3, 2, 6}, false);
  kerf::LinearDynamicSystem linear;
  ExplicitFlap() {
    linear.M = body->system.M;
    linear.K = body->K;
    linear.C = Eigen::SparseMatrix<double>(linear.M.rows(), linear.M.cols());
    linear.dofs = body->system.dofs;
    linear.load = body->system.load;
  }
  // The energy 1/2 v.M v + 1/2 u.K u at every step, stopped at 1e40 J.
  std::vector<double> energies(double dt, int steps) const {
    kerf::CentralDifferenceIntegrator integrator(linear, dt, true);
    kerf::DynamicState state = kerf::consistent_initial_state(kerf::ReducedDynamicSystem(linear), body->zero(), body->zero(), 0.0, {});
    std::vector<double> e{0.0};
    for (int n = 0; n < steps && e.back() < 1e40; ++n) {
      integrator.step(state);
      e.push_back(kerf::kinetic_energy(linear, state) + kerf::elastic_energy(linear, state));
    }
    return e;
  }
};

} // namespace

TEST_CASE("the central difference: its critical step, bounded below it, growing by |z|^2 a step above it") {
  const ExplicitFlap flap;
  const kerf::ReducedDynamicSystem reduced(flap.linear);
  const Eigen::MatrixXd K = Eigen::MatrixXd(reduced.K_ff()), M = Eigen::MatrixXd(reduced.M_ff());
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> dense(K, M, Eigen::EigenvaluesOnly);
  REQUIRE(dense.info() == Eigen::Success);
  const double omega_max = std::sqrt(dense.eigenvalues().maxCoeff()), critical = 2.0 / omega_max;
  // The power iteration stops when two Rayleigh quotients agree to 1e-12: 1e-8 leaves room for
  // the dense solver's round-off on a matrix of condition ~1e6 (measured agreement 2e-12).
  const double estimate = kerf::CentralDifferenceIntegrator(flap.linear, critical, true).critical_step();
  CHECK(estimate == kerf_test::relative(critical, 1e-8));

  // Below: bounded by 2.5 f . u_s (the closed form above; round-off adds ~1e-12 of it).
  const Eigen::VectorXd f = reduced.free_load(0.0);
  const double bound = 2.5 * f.dot(kerf::solve_once(reduced.K_ff(), f, {}));
  const std::vector<double> stable = flap.energies(0.9 * critical, 300);
  REQUIRE(stable.size() == 301);
  CHECK(*std::max_element(stable.begin(), stable.end()) <= bound * (1 + 1e-9));

  for (const double factor : {1.01, 1.1}) {
    CAPTURE(factor);
    const double dt = factor * critical, b = 2.0 - omega_max * omega_max * dt * dt;
    const double closed = std::pow((std::abs(b) + std::sqrt(b * b - 4.0)) / 2.0, 2.0);
    const std::vector<double> e = flap.energies(dt, 300);
    // It blew up past 1e40 J (from round-off: gravity hardly loads the top mode).
    CHECK(e.back() >= 1e40);
    // Over the last 20 steps the top mode has overtaken every other (the next unstable ones grow
    // more slowly, and by then by a factor of more than 1e10 less): the growth is its |z|^2
    // to 1e-3 (measured 1e-6).
    const std::size_t last = e.size() - 1;
    CHECK(std::pow(e[last] / e[last - 20], 1.0 / 20.0) == kerf_test::relative(closed, 1e-3));
  }
}
