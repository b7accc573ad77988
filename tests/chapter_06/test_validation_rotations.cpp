// Frozen rotations against Newton per step on the demo's flap, coarse (3 x 2
// x 6 cells), 0.16 s of its first swing: the flap tip's largest distance from a Newton run at
// dt = 0.625 ms, at dt = 10, 5 and 2.5 ms. Newton solves each implicit step, so its error is
// Newmark's, second order in dt; the frozen step's force f_int(u_n) + K_R (u - u_n) lags the
// rotations by a step, an O(dt) error in the force, so it is first order.
#include "../examples/cut_dynamics_scenes.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace {

std::vector<Eigen::Vector3d> tip_history(const cut_dynamics::CutDynamicBody& body, int tip, double dt, int steps, kerf::RotationUpdate update) {
  kerf::NonlinearNewmarkSettings settings;
  settings.update = update;
  settings.tolerance = 1e-10;
  kerf::NonlinearNewmarkIntegrator integrator(body.system, dt, settings);
  kerf::DynamicState state = integrator.initial_state(body.zero(), body.zero(), 0.0);
  std::vector<Eigen::Vector3d> tip_u{state.u.segment<3>(3 * tip)};
  for (int n = 0; n < steps; ++n) {
    REQUIRE(integrator.step(state).converged);
    tip_u.push_back(state.u.segment<3>(3 * tip));
  }
  return tip_u;
}

} // namespace

TEST_CASE("on the swinging flap Newton per step converges at second order in dt, frozen rotations at first") {
  const auto body = cut_dynamics::demo_flap({3, 2, 6}, true);
  const int tip = cut_dynamics::node_at(body->mesh, {0, 0.06, 0.2});
  const double T = 0.16, dt_reference = 0.000625;
  const std::vector<Eigen::Vector3d> reference = tip_history(*body, tip, dt_reference, 256, kerf::RotationUpdate::newton);
  for (const kerf::RotationUpdate update : {kerf::RotationUpdate::newton, kerf::RotationUpdate::frozen}) {
    const bool newton = update == kerf::RotationUpdate::newton;
    CAPTURE(newton);
    std::vector<double> errors;
    for (const double dt : {0.01, 0.005, 0.0025}) {
      const int steps = static_cast<int>(std::lround(T / dt)), stride = static_cast<int>(std::lround(dt / dt_reference));
      const std::vector<Eigen::Vector3d> run = tip_history(*body, tip, dt, steps, update);
      double error = 0.0;
      for (int n = 0; n <= steps; ++n) error = std::max(error, (run[n] - reference[n * stride]).norm());
      errors.push_back(error);
    }
    const double order_1 = std::log2(errors[0] / errors[1]), order_2 = std::log2(errors[1] / errors[2]);
    MESSAGE("errors " << errors[0] << ", " << errors[1] << ", " << errors[2] << " m; observed orders " << order_1 << ", " << order_2);
    // The reference's own error is (0.625 / 2.5)^2 = 1/16 of Newton's at the finest step: it
    // lowers that step's observed order by about log2(1 + 1/16) ~ 0.1. Measured: Newton 1.93 and
    // 2.04; frozen 1.34 and 1.15, nearing 1 as dt shrinks (at the larger step the second-order
    // part of its error is not yet negligible). Orders within 0.4 of the theory leave room for
    // both; Newton's bound 1.6 is well above any first-order method.
    if (newton) {
      CHECK(order_1 > 1.6);
      CHECK(order_2 > 1.6);
    } else {
      CHECK(order_1 == kerf_test::relative(1.0, 0.4));
      CHECK(order_2 == kerf_test::relative(1.0, 0.4));
    }
  }
}
