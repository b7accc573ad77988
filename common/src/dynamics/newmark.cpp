#include "kerf/dynamics/newmark.hpp"

#include <stdexcept>

namespace kerf {

// The step itself (predict, solve, correct, and its energy) is in newmark_step.cpp, a file of its
// own so that chapter 6's assignment can hand it out.
NewmarkIntegrator::NewmarkIntegrator(const LinearDynamicSystem& system, double dt, NewmarkParameters parameters,
                                     const SolverSettings& solver_settings)
    : reduced_(system), dt_(dt), parameters_(parameters), solver_(make_linear_solver(solver_settings)) {
  if (!(dt > 0.0)) throw std::invalid_argument("NewmarkIntegrator: the time step must be positive");
  const Eigen::SparseMatrix<double> A = reduced_.M_ff() + (parameters.gamma * dt) * reduced_.C_ff() +
                                        (parameters.beta * dt * dt) * reduced_.K_ff();
  solver_->analyze_pattern(A);
  solver_->factorize(A);
}

} // namespace kerf
