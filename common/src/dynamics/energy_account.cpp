#include "kerf/dynamics/energy_account.hpp"

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

} // namespace kerf
