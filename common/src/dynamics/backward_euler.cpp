#include "kerf/dynamics/backward_euler.hpp"

#include <stdexcept>

namespace kerf {

BackwardEulerIntegrator::BackwardEulerIntegrator(const LinearDynamicSystem& system, double dt,
                                                 const SolverSettings& solver_settings)
    : reduced_(system), dt_(dt), solver_(make_linear_solver(solver_settings)) {
  if (!(dt > 0.0)) throw std::invalid_argument("BackwardEulerIntegrator: the time step must be positive");
  const Eigen::SparseMatrix<double> A = reduced_.M_ff() + dt * reduced_.C_ff() + (dt * dt) * reduced_.K_ff();
  solver_->analyze_pattern(A);
  solver_->factorize(A);
}

StepEnergy BackwardEulerIntegrator::step(DynamicState& state) {
  const double dt = dt_;
  const ReducedDynamicSystem& R = reduced_;
  const Eigen::VectorXd u = R.restrict_to_free(state.u), v = R.restrict_to_free(state.v);
  const Eigen::VectorXd rhs = R.free_load(state.t + dt) - R.C_ff() * v - R.K_ff() * (u + dt * v);
  Eigen::VectorXd a_next = R.restrict_to_free(state.a);
  solver_->solve(rhs, a_next);
  const Eigen::VectorXd v_next = v + dt * a_next;

  DynamicState next;
  next.t = state.t + dt;
  next.u = R.expand(u + dt * v_next, true);
  next.v = R.expand(v_next, false);
  next.a = R.expand(a_next, false);

  const LinearDynamicSystem& S = R.system();
  const Eigen::VectorXd du = next.u - state.u, dv = next.v - state.v;
  const Eigen::VectorXd f_now = S.load(state.t), f_next = S.load(next.t);
  StepEnergy energy;
  energy.external_work = du.dot(0.5 * (f_now + f_next));
  energy.damping = du.dot(S.C * next.v);
  energy.numerical = 0.5 * dv.dot(S.M * dv) + 0.5 * du.dot(S.K * du) - 0.5 * du.dot(f_next - f_now);
  state = std::move(next);
  return energy;
}

} // namespace kerf
