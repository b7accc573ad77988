/// @file central_difference.hpp
/// @brief The explicit central difference (Newmark beta = 0, gamma = 1/2) with a lumped mass, and its refusal above 2 / omega_max.
#pragma once

#include "kerf/dynamics/critical_time_step.hpp"
#include "kerf/dynamics/newmark.hpp"

namespace kerf {

/// The central difference: Newmark with beta = 0 and gamma = 1/2, whose matrix M + dt/2 C is
/// the (lumped, lumped_mass.hpp) mass alone when there is no damping, or only mass damping: no
/// stiffness is factorised, which is what makes it explicit. (Stiffness damping beta K puts K
/// back into the matrix; it stays correct, just not cheap.)
///
/// Stable only for dt <= 2 / omega_max (Schoch et al. section 3.5: a real-time run needs
/// dt_compute < dt_step < dt_crit). The constructor estimates omega_max by power iteration
/// (critical_time_step.hpp) and refuses a larger step unless told to go on: above it the top
/// mode grows by |z| = (b + sqrt(b^2 - 4)) / 2, b = omega^2 dt^2 - 2, every step.
class CentralDifferenceIntegrator {
public:
  /// @param system kept by reference
  /// @param dt     the time step, s
  /// @param force  take dt even above the estimated critical step (to show the blow-up)
  /// @throws std::invalid_argument when dt exceeds the critical step and `force` is false, or the
  ///         power iteration did not converge (and `force` is false)
  CentralDifferenceIntegrator(const LinearDynamicSystem& system, double dt, bool force = false,
                              const SolverSettings& solver_settings = {});
  StepEnergy step(DynamicState& state) { return newmark_.step(state); }
  /// The estimated critical step 2 / omega_max, s.
  double critical_step() const { return critical_step_; }
  double time_step() const { return newmark_.time_step(); }

private:
  double critical_step_;
  NewmarkIntegrator newmark_;
};

} // namespace kerf
