#include "kerf/dynamics/nonlinear_newmark.hpp"

#include <algorithm>
#include <stdexcept>
#include <vector>

namespace kerf {

NonlinearNewmarkIntegrator::NonlinearNewmarkIntegrator(const NonlinearDynamicSystem& system, double dt,
                                                       NonlinearNewmarkSettings settings)
    : system_(system), dt_(dt), settings_(settings), solver_(make_linear_solver(settings.solver)) {
  if (!(dt > 0.0)) throw std::invalid_argument("NonlinearNewmarkIntegrator: the time step must be positive");
  const DofMap& dofs = system.dofs;
  std::vector<Eigen::Triplet<double>> entries;
  for (std::size_t i = 0; i < dofs.free_index.size(); ++i)
    if (dofs.free_index[i] >= 0) entries.emplace_back(dofs.free_index[i], static_cast<int>(i), 1.0);
  P_.resize(dofs.num_free, static_cast<Eigen::Index>(dofs.free_index.size()));
  P_.setFromTriplets(entries.begin(), entries.end());
  Pt_ = P_.transpose();
}

Eigen::VectorXd NonlinearNewmarkIntegrator::combine(const Eigen::VectorXd& free, const Eigen::VectorXd& prescribed) const {
  Eigen::VectorXd full = prescribed;
  const std::vector<int>& index = system_.dofs.free_index;
  for (std::size_t i = 0; i < index.size(); ++i)
    if (index[i] >= 0) full[static_cast<Eigen::Index>(i)] = free[index[i]];
  return full;
}

void NonlinearNewmarkIntegrator::solve(const Eigen::SparseMatrix<double>& A_ff, const Eigen::VectorXd& rhs, Eigen::VectorXd& x) {
  // Every matrix is M + c1 C + c2 K over the same sparsity pattern (Eigen's sums keep the union of
  // their operands' patterns, explicit zeros included), so one analysis serves the whole run.
  if (!analysed_) {
    solver_->analyze_pattern(A_ff);
    analysed_ = true;
  }
  solver_->factorize(A_ff);
  x = Eigen::VectorXd::Zero(rhs.size());
  solver_->solve(rhs, x);
}

double NonlinearNewmarkIntegrator::elastic_energy(const Eigen::VectorXd& u) const {
  if (energy_u_.size() != u.size() || energy_u_ != u) {
    energy_value_ = system_.elastic_energy(u);
    energy_u_ = u;
  }
  return energy_value_;
}

DynamicState NonlinearNewmarkIntegrator::initial_state(const Eigen::VectorXd& u0, const Eigen::VectorXd& v0, double t0) {
  const PrescribedMotion motion = system_.motion(t0);
  DynamicState state;
  state.t = t0;
  state.u = combine(P_ * u0, motion.u);
  state.v = combine(P_ * v0, motion.v);
  Eigen::VectorXd f_int;
  Eigen::SparseMatrix<double> K;
  system_.internal_force(state.u, CorotationalTangent::warped, f_int, &K);
  const Eigen::SparseMatrix<double> C = system_.rayleigh_alpha * system_.M + system_.rayleigh_beta * K;
  // M_ff a_f = (f - M a_c - C v - f_int)_f, a_c the motion's acceleration.
  const Eigen::VectorXd a_c = combine(Eigen::VectorXd::Zero(P_.rows()), motion.a);
  const Eigen::VectorXd rhs = P_ * (system_.load(t0) - system_.M * a_c - C * state.v - f_int);
  Eigen::VectorXd a_f;
  solve(free_block(system_.M), rhs, a_f);
  analysed_ = false; // the mass alone may have a smaller pattern than the step's matrix
  state.a = combine(a_f, motion.a);
  return state;
}

EnergyAccount NonlinearNewmarkIntegrator::start_account(const DynamicState& state) const {
  EnergyAccount account;
  account.kinetic = 0.5 * state.v.dot(system_.M * state.v);
  account.elastic = elastic_energy(state.u);
  return account;
}

void NonlinearNewmarkIntegrator::add_step(EnergyAccount& account, const DynamicState& state, const NonlinearStepReport& report) const {
  account.kinetic = 0.5 * state.v.dot(system_.M * state.v);
  account.elastic = elastic_energy(state.u);
  account.external_work += report.energy.external_work;
  account.damping += report.energy.damping;
  account.numerical += report.energy.numerical;
}

NonlinearStepReport NonlinearNewmarkIntegrator::step(DynamicState& state) {
  const double dt = dt_, beta = settings_.newmark.beta, gamma = settings_.newmark.gamma;
  const Eigen::SparseMatrix<double>& M = system_.M;
  const double t_next = state.t + dt;
  const PrescribedMotion motion = system_.motion(t_next);

  // The step's start: f_int(u_n), the warped K_R(u_n), and the damping built on it.
  Eigen::VectorXd f_int_start;
  Eigen::SparseMatrix<double> K_start;
  system_.internal_force(state.u, CorotationalTangent::warped, f_int_start, &K_start);
  const Eigen::SparseMatrix<double> C = system_.rayleigh_alpha * M + system_.rayleigh_beta * K_start;

  // Newmark's predictor; the free DOFs then move with their acceleration, the prescribed ones as told.
  const NewmarkPrediction predicted = newmark_predict(state.u, state.v, state.a, dt, settings_.newmark);
  const Eigen::VectorXd f_next = system_.load(t_next);
  Eigen::VectorXd a_f = P_ * state.a;
  DynamicState next;
  next.t = t_next;
  Eigen::VectorXd f_int, residual;
  Eigen::SparseMatrix<double> K;
  const auto evaluate = [&] {
    next.a = combine(a_f, motion.a);
    next.u = combine(P_ * (predicted.u + (beta * dt * dt) * next.a), motion.u);
    next.v = combine(P_ * (predicted.v + (gamma * dt) * next.a), motion.v);
    if (settings_.update == RotationUpdate::frozen) {
      f_int = f_int_start + K_start * (next.u - state.u);
    } else {
      system_.internal_force(next.u, CorotationalTangent::consistent, f_int, &K);
    }
    residual = f_next - M * next.a - C * next.v - f_int;
  };

  NonlinearStepReport report;
  evaluate();
  const double reference = std::max({(P_ * residual).norm(), (P_ * f_next).norm(), (P_ * (M * state.a)).norm()});
  for (;;) {
    const Eigen::VectorXd r_f = P_ * residual;
    if (settings_.update == RotationUpdate::newton) {
      report.relative_residual = reference > 0.0 ? r_f.norm() / reference : 0.0;
      report.converged = report.relative_residual <= settings_.tolerance;
      if (report.converged || report.iterations >= settings_.max_iterations) break;
    } else if (report.iterations == 1) {
      break; // the frozen step's residual is linear in a_f: one solve solves it
    }
    const Eigen::SparseMatrix<double>& tangent = settings_.update == RotationUpdate::frozen ? K_start : K;
    Eigen::VectorXd delta;
    solve(free_block(M + (gamma * dt) * C + (beta * dt * dt) * tangent), r_f, delta);
    a_f += delta;
    ++report.iterations;
    evaluate();
  }

  // The energy of the step on all DOFs. The reactions r = M a + C v + f_int - f at both ends,
  // with the step's own C and f_int, on the prescribed DOFs only.
  const Eigen::VectorXd f_start = system_.load(state.t);
  const Eigen::VectorXd du = next.u - state.u, v_bar = 0.5 * (next.v + state.v);
  const Eigen::VectorXd free_mask = Pt_ * Eigen::VectorXd::Ones(P_.rows());
  const Eigen::VectorXd prescribed_mask = Eigen::VectorXd::Ones(du.size()) - free_mask;
  const Eigen::VectorXd r_start = M * state.a + C * state.v + f_int_start - f_start;
  const Eigen::VectorXd r_next = M * next.a + C * next.v + f_int - f_next;
  report.energy.external_work = du.dot(0.5 * (f_start + f_next)) + du.cwiseProduct(prescribed_mask).dot(0.5 * (r_start + r_next));
  report.energy.damping = du.dot(C * v_bar);
  const double kinetic_change = 0.5 * next.v.dot(M * next.v) - 0.5 * state.v.dot(M * state.v);
  const double elastic_start = elastic_energy(state.u);
  const double elastic_change = elastic_energy(next.u) - elastic_start;
  report.energy.numerical = report.energy.external_work - report.energy.damping - kinetic_change - elastic_change;
  state = std::move(next);
  return report;
}

} // namespace kerf
