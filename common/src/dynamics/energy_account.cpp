#include "kerf/dynamics/energy_account.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace kerf {

EnergyAccount start_energy_account(const LinearDynamicSystem& system, const DynamicState& state) {
  EnergyAccount account;
  account.kinetic = kinetic_energy(system, state);
  account.elastic = elastic_energy(system, state);
  return account;
}

void add_step(EnergyAccount& account, const LinearDynamicSystem& system, const DynamicState& state, const StepEnergy& step) {
  account.kinetic = kinetic_energy(system, state);
  account.elastic = elastic_energy(system, state);
  account.external_work += step.external_work;
  account.damping += step.damping;
  account.numerical += step.numerical;
}

void check_bounded_state(const DynamicState& state, const EnergyAccount& account, double energy_scale, int step) {
  const bool finite = state.u.allFinite() && state.v.allFinite() && state.a.allFinite() && std::isfinite(account.kinetic) &&
                      std::isfinite(account.elastic);
  const double energy = account.kinetic + account.elastic;
  if (finite && energy <= 100.0 * energy_scale + 1e-12) return;
  std::ostringstream message;
  message << "the run diverged at step " << step << " (t = " << state.t << " s): ";
  if (!finite) message << "the state is not finite";
  else message << "kinetic + elastic energy " << energy << " J exceeds 100 times the energy put in, " << energy_scale << " J";
  message << "; nothing of this step was written (a smaller dt, or a stable integrator)";
  throw std::runtime_error(message.str());
}

void write_energy_row(std::ostream& out, int step, double t, const EnergyAccount& account) {
  char row[320];
  std::snprintf(row, sizeof row, "%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", step, t, account.kinetic, account.elastic,
                account.external_work, account.dissipated(), account.damping, account.numerical);
  out << row;
}

std::string energy_summary(const EnergyAccount& account) {
  std::ostringstream line;
  line.precision(4);
  line << "energy: kinetic " << account.kinetic << " J, elastic " << account.elastic << " J, work " << account.external_work
       << " J, dissipated " << account.dissipated() << " J = damping " << account.damping << " J + numerical (the rest of the balance) "
       << account.numerical << " J";
  return line.str();
}

} // namespace kerf
