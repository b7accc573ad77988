// Newmark's average acceleration rule and backward Euler on single-DOF oscillators, against
// their closed-form discrete solutions: the period elongation omega_h dt = 2 atan(omega dt / 2)
// and exact energy conservation of the one, the amplification 1 / (1 + omega^2 dt^2) of the
// other's energy, and both with Rayleigh damping, whose dissipated work is the energy lost;
// the central difference's limit 2 / omega, unmoved by damping; HHT-alpha: the average
// acceleration rule at alpha = 0, and its high-frequency spectral
// radius (1 + alpha) / (1 - alpha) as a double root.
#include "dynamics/oscillators.hpp"
#include "kerf/dynamics/backward_euler.hpp"
#include "kerf/dynamics/central_difference.hpp"
#include "kerf/dynamics/energy_account.hpp"
#include "kerf/dynamics/hht_alpha.hpp"
#include "kerf/dynamics/newmark.hpp"
#include "kerf/dynamics/rayleigh_damping.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <vector>

namespace {

const Eigen::Vector3d masses(2.0, 2.0, 2.0);
const Eigen::Vector3d omegas(1.0, 10.0, 100.0); // rad/s: omega dt = 0.05, 0.5 and 5 at dt = 0.05
const Eigen::Vector3d stiffnesses = masses.cwiseProduct(omegas.cwiseProduct(omegas));
const double dt = 0.05;
const kerf::SolverSettings solver;

} // namespace

TEST_CASE("average acceleration turns (u, v / omega) by 2 atan(omega dt / 2) a step and keeps the energy") {
  const kerf::LinearDynamicSystem system = oscillators::make_system(masses, Eigen::Vector3d::Zero(), stiffnesses);
  kerf::NewmarkIntegrator newmark(system, dt);
  kerf::DynamicState state = kerf::consistent_initial_state(newmark.reduced(), Eigen::Vector3d(1, 1, 1), Eigen::Vector3d::Zero(), 0.0, solver);
  kerf::EnergyAccount account = kerf::start_energy_account(system, state);
  const double E0 = account.kinetic + account.elastic;
  const int steps = 2000;
  double worst_phase = 0.0, worst_energy = 0.0;
  for (int n = 1; n <= steps; ++n) {
    kerf::add_step(account, system, state, newmark.step(state));
    for (int c = 0; c < 3; ++c) {
      const double theta = 2.0 * std::atan(omegas[c] * dt / 2.0); // omega_h dt
      worst_phase = std::max(worst_phase, std::abs(state.u[c] - std::cos(n * theta)));
    }
    worst_energy = std::max(worst_energy, std::abs(account.kinetic + account.elastic - E0));
  }
  // The step is an exact rotation; round-off adds ~1e-16 a step and cos(n theta) at arguments up
  // to 5000 rad is good to ~1e-12: 1e-10 over 2000 steps.
  CHECK(worst_phase <= 1e-10);
  CHECK(worst_energy <= 1e-12 * E0);
  CHECK(account.numerical == 0.0); // beta - gamma / 2 = gamma - 1/2 = 0: no numerical term at all
  // The test can tell: at omega dt = 5 the discrete period is 2.10 times the true one.
  CHECK(5.0 / (2.0 * std::atan(2.5)) == kerf_test::relative(2.1004, 1e-4));
  MESSAGE("average acceleration: worst |u_n - cos(n omega_h dt)| = " << worst_phase << ", worst energy drift = " << worst_energy / E0);
}

TEST_CASE("average acceleration with Rayleigh damping follows its discrete solution and loses what the damping dissipates") {
  const double alpha = 0.4, beta = 0.002; // xi = alpha / (2 omega) + beta omega / 2: 0.2, 0.03, 0.1
  const kerf::LinearDynamicSystem undamped = oscillators::make_system(masses, Eigen::Vector3d::Zero(), stiffnesses);
  kerf::LinearDynamicSystem system = undamped;
  system.C = kerf::rayleigh_damping(undamped.M, undamped.K, alpha, beta);
  kerf::NewmarkIntegrator newmark(system, dt);
  const Eigen::Vector3d u0(1.0, -0.5, 0.2), v0(0.3, 2.0, -10.0);
  kerf::DynamicState state = kerf::consistent_initial_state(newmark.reduced(), u0, v0, 0.0, solver);
  kerf::EnergyAccount account = kerf::start_energy_account(system, state);
  const double E0 = account.kinetic + account.elastic;
  double worst = 0.0;
  for (int n = 1; n <= 400; ++n) {
    kerf::add_step(account, system, state, newmark.step(state));
    for (int c = 0; c < 3; ++c) {
      const double m = masses[c], k = stiffnesses[c], cc = alpha * m + beta * k;
      worst = std::max(worst, std::abs(state.u[c] - oscillators::discrete_solution(m, cc, k, u0[c], v0[c], dt, n, oscillators::trapezoidal)));
    }
  }
  CHECK(worst <= 1e-12);
  const double lost = E0 - (account.kinetic + account.elastic);
  CHECK(lost > 0.99 * E0); // the damping has taken nearly all of it: the check below is not 0 = 0
  CHECK(account.damping == kerf_test::relative(lost, 1e-12));
  CHECK(account.numerical == 0.0);
  MESSAGE("damped average acceleration: worst |u_n - closed form| = " << worst << ", lost " << lost / E0 << " E0, damping "
                                                                       << account.damping / E0 << " E0");
}

TEST_CASE("backward Euler shrinks an oscillator's energy by 1 / (1 + omega^2 dt^2) every step") {
  const kerf::LinearDynamicSystem system = oscillators::make_system(masses, Eigen::Vector3d::Zero(), stiffnesses);
  kerf::BackwardEulerIntegrator euler(system, dt);
  const kerf::ReducedDynamicSystem reduced(system);
  kerf::DynamicState state = kerf::consistent_initial_state(reduced, Eigen::Vector3d(1, 1, 1), Eigen::Vector3d::Zero(), 0.0, solver);
  kerf::EnergyAccount account = kerf::start_energy_account(system, state);
  const double E0 = account.kinetic + account.elastic;
  Eigen::Vector3d energy0, worst = Eigen::Vector3d::Zero();
  for (int c = 0; c < 3; ++c) energy0[c] = 0.5 * stiffnesses[c];
  for (int n = 1; n <= 60; ++n) {
    kerf::add_step(account, system, state, euler.step(state));
    for (int c = 0; c < 3; ++c) {
      const double energy = 0.5 * masses[c] * state.v[c] * state.v[c] + 0.5 * stiffnesses[c] * state.u[c] * state.u[c];
      const double predicted = energy0[c] * std::pow(1.0 + omegas[c] * omegas[c] * dt * dt, -n);
      worst[c] = std::max(worst[c], std::abs(energy / predicted - 1.0));
    }
  }
  // Relative round-off ~1e-16 a step, compounded over 60 steps.
  CHECK(worst.maxCoeff() <= 1e-12);
  // Its numerical dissipation is all the energy lost (no damping, no load), booked in closed form.
  CHECK(account.damping == 0.0);
  CHECK(account.numerical == kerf_test::relative(E0 - account.kinetic - account.elastic, 1e-12));
  MESSAGE("backward Euler: worst relative error of E_n against E_0 (1 + omega^2 dt^2)^-n = " << worst.maxCoeff());
}

TEST_CASE("backward Euler with Rayleigh damping follows its discrete solution") {
  const double alpha = 0.4, beta = 0.002;
  kerf::LinearDynamicSystem system = oscillators::make_system(masses, Eigen::Vector3d::Zero(), stiffnesses);
  system.C = kerf::rayleigh_damping(system.M, system.K, alpha, beta);
  kerf::BackwardEulerIntegrator euler(system, dt);
  const Eigen::Vector3d u0(1.0, -0.5, 0.2), v0(0.3, 2.0, -10.0);
  const kerf::ReducedDynamicSystem reduced(system);
  kerf::DynamicState state = kerf::consistent_initial_state(reduced, u0, v0, 0.0, solver);
  kerf::EnergyAccount account = kerf::start_energy_account(system, state);
  double worst = 0.0;
  for (int n = 1; n <= 100; ++n) {
    kerf::add_step(account, system, state, euler.step(state));
    for (int c = 0; c < 3; ++c) {
      const double m = masses[c], k = stiffnesses[c], cc = alpha * m + beta * k;
      worst = std::max(worst, std::abs(state.u[c] - oscillators::discrete_solution(m, cc, k, u0[c], v0[c], dt, n, oscillators::backward_euler)));
    }
  }
  CHECK(worst <= 1e-12);
  CHECK(account.balance() == kerf_test::relative(0.5 * u0.dot(stiffnesses.cwiseProduct(u0)) + 0.5 * v0.dot(masses.cwiseProduct(v0)), 1e-12));
}

TEST_CASE("HHT-alpha is the average acceleration rule at alpha = 0 and damps the highest frequencies by (1 + alpha) / (1 - alpha) a step") {
  {
    const kerf::LinearDynamicSystem system = oscillators::make_system(masses, Eigen::Vector3d::Zero(), stiffnesses);
    kerf::HhtAlphaIntegrator hht(system, dt, 0.0);
    const kerf::ReducedDynamicSystem reduced(system);
    kerf::DynamicState state = kerf::consistent_initial_state(reduced, Eigen::Vector3d(1, 1, 1), Eigen::Vector3d::Zero(), 0.0, solver);
    double worst = 0.0;
    for (int n = 1; n <= 500; ++n) {
      hht.step(state);
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(state.u[c] - std::cos(n * 2.0 * std::atan(omegas[c] * dt / 2.0))));
    }
    CHECK(worst <= 1e-11);
  }
  // At omega dt = 1e8 the step is, to O(1 / (omega dt)^2) = 1e-16, its limit: in (dt v, dt^2 a) a
  // 2x2 block with the double eigenvalue lambda = -(1 + alpha) / (1 - alpha), and a third
  // eigenvalue alpha / (1 + alpha), which has died out (relative to lambda^n) by step 30. So the
  // sequence x_n = dt v_n obeys x_{n+2} - 2 lambda x_{n+1} + lambda^2 x_n = 0.
  for (const double alpha : {-0.1, -1.0 / 3.0}) {
    CAPTURE(alpha);
    const double omega = 1e8 / dt;
    const kerf::LinearDynamicSystem system =
        oscillators::make_system(Eigen::Vector3d::Ones(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(omega * omega));
    kerf::HhtAlphaIntegrator hht(system, dt, alpha);
    const kerf::ReducedDynamicSystem reduced(system);
    kerf::DynamicState state = kerf::consistent_initial_state(reduced, Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(0.5, 0, -0.5) * omega, 0.0, solver);
    std::vector<double> x;
    for (int n = 0; n < 60; ++n) {
      hht.step(state);
      x.push_back(dt * state.v[0]);
    }
    const double lambda = -(1.0 + alpha) / (1.0 - alpha);
    double worst = 0.0;
    for (std::size_t n = 30; n + 2 < x.size(); ++n)
      worst = std::max(worst, std::abs(x[n + 2] - 2.0 * lambda * x[n + 1] + lambda * lambda * x[n]) / std::abs(x[n]));
    CHECK(worst <= 1e-9);
    // The test can tell: the average acceleration rule's lambda would be -1, a residual of order 1.
    CHECK(std::abs(x[42] + 2.0 * x[41] + x[40]) > 0.01 * std::abs(x[40]));
    MESSAGE("HHT alpha = " << alpha << ": worst recurrence residual with lambda = " << lambda << ": " << worst);
  }
}

TEST_CASE("damping does not move the central difference's limit 2 / omega (gamma = 1/2, Hughes' Omega_crit = 2)") {
  // Three equal oscillators of omega = 10 rad/s with damping ratio 1/2 (c = 2 xi omega m).
  const double omega = 10.0, xi = 0.5;
  const kerf::LinearDynamicSystem system = oscillators::make_system(Eigen::Vector3d::Ones(), Eigen::Vector3d::Constant(2.0 * xi * omega),
                                                                    Eigen::Vector3d::Constant(omega * omega));
  const kerf::ReducedDynamicSystem reduced(system);
  const auto amplitude_after = [&](double factor, int steps) {
    kerf::CentralDifferenceIntegrator central(system, factor * 2.0 / omega, true);
    kerf::DynamicState state = kerf::consistent_initial_state(reduced, Eigen::Vector3d(1, 1, 1), Eigen::Vector3d::Zero(), 0.0, solver);
    for (int n = 0; n < steps; ++n) central.step(state);
    return std::abs(state.u[0]) + std::abs(state.v[0]) * factor * 2.0 / omega;
  };
  const kerf::CentralDifferenceIntegrator check(system, 0.999 * 2.0 / omega);
  CHECK(check.critical_step() == kerf_test::relative(2.0 / omega, 1e-12));
  const double below = amplitude_after(0.99, 2000), above = amplitude_after(1.01, 2000);
  CHECK(below < 1e-3); // damped away
  CHECK(above > 1e3);  // grown, damping or not
  MESSAGE("central difference, xi = 0.5: |u| + dt |v| after 2000 steps at 0.99 dt_crit " << below << ", at 1.01 dt_crit " << above);
}
