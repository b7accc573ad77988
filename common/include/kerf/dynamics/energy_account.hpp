/// @file energy_account.hpp
/// @brief The energy account of a run, step by step: kinetic, elastic, external work and dissipation since t = 0.
#pragma once

#include "kerf/dynamics/linear_dynamic_system.hpp"

#include <ostream>
#include <string>

namespace kerf {

/// Where the energy of a run went, in J, kept step by step (the columns of a chapter's
/// energy.csv: kinetic, elastic, external_work, dissipated, damping, numerical).
///
/// The balance: kinetic + elastic + dissipated() - external_work stays at its value at the start
/// (the initial kinetic plus elastic energy). Whether that is a check or an identity depends on
/// how the integrator gets `numerical`. Every integrator measures kinetic and elastic from the
/// state and computes external_work and damping from the step's own vectors; per integrator:
///
/// - Newmark (newmark.hpp): damping Delta u^T C v_bar; numerical the closed form
///   dt^2 (beta - gamma/2) [a]^T M a_bar - dt (gamma - 1/2) v_bar^T M [a] (zero for the average
///   acceleration rule).
/// - the central difference (Newmark with beta = 0, gamma = 1/2): the same two, numerical
///   -dt^2/4 [a]^T M a_bar.
/// - backward Euler (backward_euler.hpp): damping Delta u^T C v_{n+1}; numerical the closed form
///   Delta v^T M Delta v / 2 + Delta u^T K Delta u / 2 - Delta u . [f] / 2.
/// - HHT-alpha (hht_alpha.hpp): damping Delta u^T C v_bar; numerical the rest of the balance, by
///   construction.
/// - nonlinear Newmark (nonlinear_newmark.hpp: the corotated body, clamps that move): damping
///   Delta u^T C v_bar with the step's C; numerical the rest of the balance, by construction.
///
/// For the three closed forms the balance is a check: a wrong formula, or a step that does not
/// satisfy its own equations, shows up as a drift of the balance (to round-off otherwise). For
/// HHT-alpha and the nonlinear step the balance holds by definition and proves nothing; there
/// `numerical` is what to read: whatever the step did to the energy that neither the work nor the
/// damping accounts for. On the nonlinear path that is the frozen-rotation step's error (O(dt)
/// over a fixed time; negative when the step puts energy in) or, with a step solved at its end's
/// rotations (checked, Newton), the average acceleration rule's on the corotated force (O(dt^2)),
/// a moving clamp's motion that does not
/// follow Newmark's updates, an iterative solve's tolerance, and (chapter 7) the change of the
/// energies when a new model takes over the state. Damping is computed on its own in every
/// scheme, so the damping column is the dissipation of C, and the numerical column the rest.
///
/// The prescribed DOFs are held still (LinearDynamicSystem), so their reactions do no work and
/// external_work is the work of the load f alone; a prescribed motion would add the trapezoidal
/// work of the reactions, (u_c,n+1 - u_c,n) . (r_n + r_{n+1}) / 2 (nonlinear_newmark.hpp does).
struct EnergyAccount {
  double kinetic = 0.0;        ///< (1/2) v^T M v now
  double elastic = 0.0;        ///< (1/2) u^T K u (or the corotated W(u)) now
  double external_work = 0.0;  ///< trapezoidal work of the loads (and a moving clamp's reactions) since the start
  /// Work of the damping forces since the start, by the step's rule (above); for the average
  /// acceleration rule and still clamps Delta u = dt v_bar, so each step adds dt v_bar^T C v_bar >= 0.
  double damping = 0.0;
  /// Energy the integrator removed since the start (negative: put in). A closed form of the
  /// scheme for Newmark, the central difference and backward Euler; for HHT-alpha and the
  /// nonlinear step the rest of the balance, external_work - damping - change of kinetic + elastic.
  double numerical = 0.0;
  /// damping + numerical.
  double dissipated() const { return damping + numerical; }
  /// kinetic + elastic + dissipated() - external_work: constant along a run (a check only where
  /// `numerical` is a closed form, see above).
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

/// energy.csv's header line, with its newline: the columns of write_energy_row. The first six are
/// those of earlier versions; damping and numerical, whose sum is dissipated, came after them.
inline constexpr const char* energy_csv_header = "step,t,kinetic,elastic,external_work,dissipated,damping,numerical\n";

/// energy.csv's row for a step: `step,t,kinetic,elastic,external_work,dissipated,damping,numerical`,
/// full precision.
void write_energy_row(std::ostream& out, int step, double t, const EnergyAccount& account);

/// One line for a program's summary: `energy: kinetic K J, elastic W J, work ... J, dissipated D
/// J = damping ... J + numerical (the rest of the balance) ... J`, 4 significant digits.
std::string energy_summary(const EnergyAccount& account);

} // namespace kerf
