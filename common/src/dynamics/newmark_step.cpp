#include "kerf/dynamics/newmark.hpp"

#include <utility>

namespace kerf {

NewmarkPrediction newmark_predict(const Eigen::VectorXd& u, const Eigen::VectorXd& v, const Eigen::VectorXd& a, double dt,
                                  const NewmarkParameters& parameters) {
  return {u + dt * v + (dt * dt * (0.5 - parameters.beta)) * a, v + (dt * (1.0 - parameters.gamma)) * a};
}

DynamicState newmark_correct(const ReducedDynamicSystem& reduced, double t_next, const NewmarkPrediction& predicted,
                             const Eigen::VectorXd& a_next, double dt, const NewmarkParameters& parameters) {
  DynamicState next;
  next.t = t_next;
  next.u = reduced.expand(predicted.u + (parameters.beta * dt * dt) * a_next, true);
  next.v = reduced.expand(predicted.v + (parameters.gamma * dt) * a_next, false);
  next.a = reduced.expand(a_next, false);
  return next;
}

StepEnergy NewmarkIntegrator::step(DynamicState& state) {
  const double beta = parameters_.beta, gamma = parameters_.gamma, dt = dt_;
  const ReducedDynamicSystem& R = reduced_;
  const Eigen::VectorXd a = R.restrict_to_free(state.a);
  const NewmarkPrediction predicted = newmark_predict(R.restrict_to_free(state.u), R.restrict_to_free(state.v), a, dt, parameters_);
  const Eigen::VectorXd rhs = R.free_load(state.t + dt) - R.C_ff() * predicted.v - R.K_ff() * predicted.u;
  Eigen::VectorXd a_next = a;
  solver_->solve(rhs, a_next);
  DynamicState next = newmark_correct(R, state.t + dt, predicted, a_next, dt, parameters_);

  // The energy of the step, on full vectors (the prescribed entries do not change).
  const LinearDynamicSystem& S = R.system();
  const Eigen::VectorXd du = next.u - state.u, v_bar = 0.5 * (next.v + state.v);
  const Eigen::VectorXd a_jump = next.a - state.a, a_bar = 0.5 * (next.a + state.a);
  StepEnergy energy;
  energy.external_work = du.dot(0.5 * (S.load(state.t) + S.load(next.t)));
  energy.damping = du.dot(S.C * v_bar);
  const Eigen::VectorXd M_a_jump = S.M * a_jump;
  energy.numerical = dt * dt * (beta - 0.5 * gamma) * M_a_jump.dot(a_bar) - dt * (gamma - 0.5) * v_bar.dot(M_a_jump);
  state = std::move(next);
  return energy;
}

} // namespace kerf
