#include "kerf/dynamics/central_difference.hpp"

#include <sstream>
#include <stdexcept>

namespace kerf {

namespace {

double checked_critical_step(const LinearDynamicSystem& system, double dt, bool force, const SolverSettings& solver_settings) {
  const ReducedDynamicSystem reduced(system);
  const LargestEigenvalue top = largest_eigenvalue(reduced.M_ff(), reduced.K_ff(), 1e-12, 20000, solver_settings);
  const double critical = central_difference_critical_step(top.lambda);
  if (force) return critical;
  if (!top.converged) {
    std::ostringstream message;
    message << "CentralDifferenceIntegrator: the power iteration for omega_max did not converge in " << top.iterations
            << " iterations, so the critical step is unknown (pass force = true to step anyway)";
    throw std::invalid_argument(message.str());
  }
  if (dt > critical) {
    std::ostringstream message;
    message << "CentralDifferenceIntegrator: dt = " << dt << " s exceeds the critical step 2 / omega_max = " << critical
            << " s; the central difference would blow up (pass force = true to step anyway)";
    throw std::invalid_argument(message.str());
  }
  return critical;
}

} // namespace

CentralDifferenceIntegrator::CentralDifferenceIntegrator(const LinearDynamicSystem& system, double dt, bool force,
                                                         const SolverSettings& solver_settings)
    : critical_step_(checked_critical_step(system, dt, force, solver_settings)),
      newmark_(system, dt, NewmarkParameters{0.0, 0.5}, solver_settings) {}

} // namespace kerf
