#include "kerf/dynamics/hht_alpha.hpp"
#include "kerf/dynamics/newmark.hpp"

#include <stdexcept>

namespace kerf {

HhtAlphaIntegrator::HhtAlphaIntegrator(const LinearDynamicSystem& system, double dt, double alpha,
                                       const SolverSettings& solver_settings)
    : reduced_(system), dt_(dt), alpha_(alpha), beta_((1.0 - alpha) * (1.0 - alpha) / 4.0), gamma_(0.5 - alpha),
      solver_(make_linear_solver(solver_settings)) {
  if (!(dt > 0.0)) throw std::invalid_argument("HhtAlphaIntegrator: the time step must be positive");
  if (!(alpha >= -1.0 / 3.0 && alpha <= 0.0)) throw std::invalid_argument("HhtAlphaIntegrator: alpha must lie in [-1/3, 0]");
  const Eigen::SparseMatrix<double> A = reduced_.M_ff() + ((1.0 + alpha) * gamma_ * dt) * reduced_.C_ff() +
                                        ((1.0 + alpha) * beta_ * dt * dt) * reduced_.K_ff();
  solver_->analyze_pattern(A);
  solver_->factorize(A);
}

StepEnergy HhtAlphaIntegrator::step(DynamicState& state) {
  const double alpha = alpha_, beta = beta_, gamma = gamma_, dt = dt_;
  const ReducedDynamicSystem& R = reduced_;
  const NewmarkParameters newmark{beta, gamma};
  const Eigen::VectorXd u = R.restrict_to_free(state.u), v = R.restrict_to_free(state.v), a = R.restrict_to_free(state.a);
  const NewmarkPrediction predicted = newmark_predict(u, v, a, dt, newmark);
  // f_n on the free DOFs, lifted, is what the averaged K u_n term needs too: free_load(t) is
  // f_f(t) - K_fc u_c, and K_fc u_c is the same at both ends (u_c is held).
  const Eigen::VectorXd rhs = (1.0 + alpha) * (R.free_load(state.t + dt) - R.C_ff() * predicted.v - R.K_ff() * predicted.u) -
                              alpha * (R.free_load(state.t) - R.C_ff() * v - R.K_ff() * u);
  Eigen::VectorXd a_next = a;
  solver_->solve(rhs, a_next);
  DynamicState next = newmark_correct(R, state.t + dt, predicted, a_next, dt, newmark);

  const LinearDynamicSystem& S = R.system();
  const Eigen::VectorXd du = next.u - state.u, v_bar = 0.5 * (next.v + state.v);
  StepEnergy energy;
  energy.external_work = du.dot(0.5 * (S.load(state.t) + S.load(next.t)));
  energy.damping = du.dot(S.C * v_bar);
  const double change = 0.5 * next.v.dot(S.M * next.v) + 0.5 * next.u.dot(S.K * next.u) -
                        0.5 * state.v.dot(S.M * state.v) - 0.5 * state.u.dot(S.K * state.u);
  energy.numerical = energy.external_work - energy.damping - change;
  state = std::move(next);
  return energy;
}

} // namespace kerf
