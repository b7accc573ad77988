/// @file hht_alpha.hpp
/// @brief The HHT-alpha method (Hilber, Hughes and Taylor 1977): Newmark with the elastic and damping forces averaged, for controlled high-frequency dissipation.
#pragma once

#include "kerf/dynamics/linear_dynamic_system.hpp"
#include "kerf/solve/linear_solver.hpp"

#include <memory>

namespace kerf {

/// HHT-alpha (Hilber, Hughes and Taylor 1977; Hughes 2000, section 9.3.3) with alpha in [-1/3, 0]:
///
///   M a_{n+1} + (1 + alpha)(C v_{n+1} + K u_{n+1}) - alpha (C v_n + K u_n) = (1 + alpha) f_{n+1} - alpha f_n,
///
/// with Newmark's updates for beta = (1 - alpha)^2 / 4 and gamma = 1/2 - alpha. Second order,
/// unconditionally stable, and at high frequency (omega dt -> infinity) its amplification has a
/// double eigenvalue -(1 + alpha) / (1 - alpha) [derived from the updates: trace and determinant
/// of the 2x2 block in (dt v, dt^2 a)] and a third alpha / (1 + alpha): the spectral radius
/// rho_inf = (1 + alpha) / (1 - alpha), 1/2 at alpha = -1/3. alpha = 0 is the average acceleration rule.
///
/// The acceleration it keeps does not satisfy the equations of motion at t_{n+1} (the forces are
/// averaged), so StepEnergy::numerical is the rest of the balance, not a closed form as for
/// the other integrators: the energy account still balances, by construction.
class HhtAlphaIntegrator {
public:
  /// @param system kept by reference
  /// @param dt     the time step, s, positive
  /// @param alpha  in [-1/3, 0]
  HhtAlphaIntegrator(const LinearDynamicSystem& system, double dt, double alpha, const SolverSettings& solver_settings = {});
  /// Advances `state` (at t) to t + dt.
  StepEnergy step(DynamicState& state);
  double time_step() const { return dt_; }

private:
  ReducedDynamicSystem reduced_;
  double dt_, alpha_, beta_, gamma_;
  std::unique_ptr<LinearSolver> solver_;
};

} // namespace kerf
