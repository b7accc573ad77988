/// @file backward_euler.hpp
/// @brief Backward (implicit) Euler for M a + C v + K u = f(t): Koschier's integrator (Koschier et al. sections 4.1, 7), first order and dissipative.
#pragma once

#include "kerf/dynamics/linear_dynamic_system.hpp"
#include "kerf/solve/linear_solver.hpp"

#include <memory>

namespace kerf {

/// Backward Euler on the first-order form, one linear solve per step:
///
///   (M + dt C + dt^2 K) a_{n+1} = f_{n+1} - C v_n - K (u_n + dt v_n),
///   v_{n+1} = v_n + dt a_{n+1},   u_{n+1} = u_n + dt v_{n+1}.
///
/// Koschier et al. solve the nonlinear version by Newton with A = M + dt^2 K (no damping); for
/// a linear system that is this matrix. An undamped oscillator of frequency omega loses the
/// fraction 1 - 1 / (1 + omega^2 dt^2) of its energy every step, exactly: in the variables
/// (v, omega u) the step is (I - dt J)^{-1} with J skew, which shrinks lengths by sqrt(1 + omega^2 dt^2).
///
/// Energy [derived]: Delta(v^T M v / 2 + u^T K u / 2) = Delta u . f_{n+1} - Delta u^T C v_{n+1}
/// - Delta v^T M Delta v / 2 - Delta u^T K Delta u / 2, so against the trapezoidal work of the load
/// the scheme removes numerical = Delta v^T M Delta v / 2 + Delta u^T K Delta u / 2 - Delta u . [f] / 2.
class BackwardEulerIntegrator {
public:
  /// @param system kept by reference
  /// @param dt     the time step, s, positive
  BackwardEulerIntegrator(const LinearDynamicSystem& system, double dt, const SolverSettings& solver_settings = {});
  /// Advances `state` (at t) to t + dt and returns what the step did to the energy.
  StepEnergy step(DynamicState& state);
  double time_step() const { return dt_; }

private:
  ReducedDynamicSystem reduced_;
  double dt_;
  std::unique_ptr<LinearSolver> solver_;
};

} // namespace kerf
