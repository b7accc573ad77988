/// @file energy_account.hpp
/// @brief The energy account of a run, step by step: kinetic, elastic, external work and dissipation since t = 0.
#pragma once

#include "kerf/dynamics/linear_dynamic_system.hpp"

#include <ostream>

namespace kerf {

/// Where the energy of a run went, in J, kept step by step (the columns of a chapter's
/// energy.csv: kinetic, elastic, external_work, dissipated).
///
/// The balance: kinetic + elastic + dissipated() - external_work stays at its value at the start
/// (the initial kinetic plus elastic energy), to round-off, for every integrator of this area.
/// For Newmark, the central difference and backward Euler that is a check: each reports the
/// dissipation of its own scheme in closed form (StepEnergy), not as whatever is left over, so a
/// wrong formula, or a step that does not satisfy its own equations, shows up as a drift of the
/// balance. HHT-alpha books the rest of the balance as numerical (hht_alpha.hpp says why).
///
/// The prescribed DOFs are held still (LinearDynamicSystem), so their reactions do no work and
/// external_work is the work of the load f alone; a prescribed motion would add the trapezoidal
/// work of the reactions, (u_c,n+1 - u_c,n) . (r_n + r_{n+1}) / 2.
struct EnergyAccount {
  double kinetic = 0.0;        ///< (1/2) v^T M v now
  double elastic = 0.0;        ///< (1/2) u^T K u now
  double external_work = 0.0;  ///< trapezoidal work of the loads since the start
  double damping = 0.0;        ///< work of the damping forces since the start (>= 0)
  double numerical = 0.0;      ///< energy the integrator removed since the start
  /// damping + numerical.
  double dissipated() const { return damping + numerical; }
  /// kinetic + elastic + dissipated() - external_work: constant along a run.
  double balance() const { return kinetic + elastic + dissipated() - external_work; }
};

/// The account at the start of a run: the state's energies, nothing worked or dissipated yet.
EnergyAccount start_energy_account(const LinearDynamicSystem& system, const DynamicState& state);

/// Books one step: `state` is the state after it, `step` what the integrator reported.
void add_step(EnergyAccount& account, const LinearDynamicSystem& system, const DynamicState& state, const StepEnergy& step);

/// Chapters 6 and 7's divergence check after a step: the state must be finite, and kinetic +
/// elastic energy may not exceed 100 times `energy_scale` (E_0 plus the sum over the steps of
/// |work done on the body|): the balance says the energy can never exceed E_0 + the work put in,
/// so only an unstable integrator gets there.
/// @throws std::runtime_error `the run diverged at step N (t = T s): ...` naming the step
void check_bounded_state(const DynamicState& state, const EnergyAccount& account, double energy_scale, int step);

/// energy.csv's row for a step: `step,t,kinetic,elastic,external_work,dissipated`, full precision.
void write_energy_row(std::ostream& out, int step, double t, const EnergyAccount& account);

} // namespace kerf
