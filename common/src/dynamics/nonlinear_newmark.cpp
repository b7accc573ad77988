#include "kerf/dynamics/nonlinear_newmark.hpp"

#include <algorithm>
#include <ctime>
#include <stdexcept>
#include <string>
#include <vector>

namespace kerf {

namespace {

// What a step says when the solver finds its matrix not positive definite: which matrix, its
// size, the solver, and what can make it so (the caller adds which step, and when).
std::string step_matrix_failure(const std::string& matrix, Eigen::Index num_free, const std::string& solver) {
  return matrix + " on " + std::to_string(num_free) + " free DOFs is not positive definite (solver " + solver +
         "); with the warped R K R^T it can be so only where a free DOF has no mass or an element's "
         "stiffness is indefinite (a quadrature rule with negative weights)";
}

} // namespace

RotationUpdate rotation_update_named(const std::string& name, RotationUpdate chapter_default) {
  if (name.empty()) return chapter_default;
  for (const RotationUpdate update : {RotationUpdate::frozen, RotationUpdate::checked, RotationUpdate::newton})
    if (name == rotation_update_name(update)) return update;
  throw std::invalid_argument("rotation_update_named: expected \"frozen\", \"checked\" or \"newton\", got \"" + name + "\"");
}

const char* rotation_update_name(RotationUpdate update) {
  switch (update) {
  case RotationUpdate::frozen: return "frozen";
  case RotationUpdate::checked: return "checked";
  case RotationUpdate::newton: return "newton";
  }
  return "frozen";
}

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
  prescribed_mask_ = Eigen::VectorXd::Ones(P_.cols()) - Pt_ * Eigen::VectorXd::Ones(P_.rows());
  if (system.solver_basis.S.size() > 0) {
    if (system.solver_basis.S.rows() != dofs.num_free)
      throw std::invalid_argument("NonlinearNewmarkIntegrator: the solver's basis is not of the free DOFs' size");
    solver_->set_preconditioner_basis(system.solver_basis);
  }
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
  if (x.size() != rhs.size()) x = Eigen::VectorXd::Zero(rhs.size());
  solver_->solve(rhs, x);
}

const Eigen::SparseMatrix<double>& NonlinearNewmarkIntegrator::step_matrix(double c_M, double c_K, const Eigen::SparseMatrix<double>& K) {
  const Eigen::SparseMatrix<double>& M = system_.M;
  if (!K.isCompressed() || !M.isCompressed()) throw std::invalid_argument("NonlinearNewmarkIntegrator: M and K must be compressed");
  if (K.nonZeros() != pattern_K_nonzeros_) {
    // The pattern: the free block of M + K with every stored entry kept (nothing cancels), and
    // for each of its entries where M's and K's values sit. One merge of the two matrices'
    // sorted columns (a new cut changes K's pattern: chapter 7 pays this at every change).
    const std::vector<int>& index = system_.dofs.free_index;
    const Eigen::Index n = system_.dofs.num_free;
    std::vector<Eigen::Index> column_of_free(static_cast<std::size_t>(n), -1);
    for (std::size_t j = 0; j < index.size(); ++j)
      if (index[j] >= 0) column_of_free[static_cast<std::size_t>(index[j])] = static_cast<Eigen::Index>(j);
    struct Entry {
      int row;
      Eigen::Index from_M, from_K;
    };
    // The arrays reserved for the most entries the merge can give, so that they are not copied
    // as they grow.
    std::vector<int> outer(static_cast<std::size_t>(n) + 1, 0), inner;
    std::vector<Eigen::Index> from_M, from_K;
    const auto most = static_cast<std::size_t>(M.nonZeros() + K.nonZeros());
    inner.reserve(most);
    from_M.reserve(most);
    from_K.reserve(most);
    std::vector<Entry> column;
    for (Eigen::Index c = 0; c < n; ++c) {
      const Eigen::Index j = column_of_free[static_cast<std::size_t>(c)];
      if (j < 0) throw std::invalid_argument("NonlinearNewmarkIntegrator: the DofMap numbers its free DOFs with gaps");
      column.clear();
      Eigen::Index m = M.outerIndexPtr()[j], k = K.outerIndexPtr()[j];
      const Eigen::Index m_end = M.outerIndexPtr()[j + 1], k_end = K.outerIndexPtr()[j + 1];
      const auto add = [&](Eigen::Index row, Eigen::Index in_M, Eigen::Index in_K) {
        if (const int free_row = index[static_cast<std::size_t>(row)]; free_row >= 0) column.push_back({free_row, in_M, in_K});
      };
      // Both columns are sorted by row: merge them while both have entries, then the rest of
      // the longer one (a lumped M has one entry per column, so this is most of K's column).
      while (m < m_end && k < k_end) {
        const Eigen::Index row_M = M.innerIndexPtr()[m], row_K = K.innerIndexPtr()[k];
        const Eigen::Index row = std::min(row_M, row_K);
        add(row, row_M == row ? m++ : -1, row_K == row ? k++ : -1);
      }
      for (; m < m_end; ++m) add(M.innerIndexPtr()[m], m, -1);
      for (; k < k_end; ++k) add(K.innerIndexPtr()[k], -1, k);
      // A DofMap need not number the free DOFs in order: sort by the free row.
      if (!std::is_sorted(column.begin(), column.end(), [](const Entry& a, const Entry& b) { return a.row < b.row; }))
        std::sort(column.begin(), column.end(), [](const Entry& a, const Entry& b) { return a.row < b.row; });
      for (const Entry& entry : column) {
        inner.push_back(entry.row);
        from_M.push_back(entry.from_M);
        from_K.push_back(entry.from_K);
      }
      outer[static_cast<std::size_t>(c) + 1] = static_cast<int>(inner.size());
    }
    // The compressed arrays written in place: every entry stays stored, whatever its value.
    A_ff_.resize(n, n);
    A_ff_.resizeNonZeros(static_cast<Eigen::Index>(inner.size()));
    std::copy(outer.begin(), outer.end(), A_ff_.outerIndexPtr());
    std::copy(inner.begin(), inner.end(), A_ff_.innerIndexPtr());
    from_M_ = std::move(from_M);
    from_K_ = std::move(from_K);
    pattern_K_nonzeros_ = K.nonZeros();
    analysed_ = false;
  }
  double* value = A_ff_.valuePtr();
  for (std::size_t p = 0; p < from_M_.size(); ++p)
    value[p] = (from_M_[p] >= 0 ? c_M * M.valuePtr()[from_M_[p]] : 0.0) + (from_K_[p] >= 0 ? c_K * K.valuePtr()[from_K_[p]] : 0.0);
  return A_ff_;
}

Eigen::VectorXd NonlinearNewmarkIntegrator::damping_force(const Eigen::SparseMatrix<double>& K_R, const Eigen::VectorXd& v) const {
  Eigen::VectorXd force = system_.rayleigh_alpha * (system_.M * v);
  if (system_.rayleigh_beta != 0.0) {
    const Eigen::VectorXd K_v = K_R.selfadjointView<Eigen::Upper>() * v;
    force += system_.rayleigh_beta * K_v;
  }
  return force;
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
  const Eigen::SparseMatrix<double>* K = nullptr;
  system_.internal_force(state.u, CorotationalTangent::warped, f_int, &K);
  // M_ff a_f = (f - M a_c - C v - f_int)_f, a_c the motion's acceleration.
  const Eigen::VectorXd a_c = combine(Eigen::VectorXd::Zero(P_.rows()), motion.a);
  const Eigen::VectorXd rhs = P_ * (system_.load(t0) - system_.M * a_c - damping_force(*K, state.v) - f_int);
  Eigen::VectorXd a_f;
  try {
    solve(free_block(system_.M), rhs, a_f);
  } catch (const NotPositiveDefinite&) {
    throw NotPositiveDefinite("the mass matrix M_ff on " + std::to_string(rhs.size()) + " free DOFs is not positive definite (solver " +
                              solver_->name() + "): a free DOF carries no mass (a piece of zero volume, or a lumping with a "
                              "non-positive entry), and the start's acceleration is not defined there");
  }
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
  if (report.awaiting_end_energies) throw std::logic_error("NonlinearNewmarkIntegrator::add_step: the step is still open (close_step)");
  account.kinetic = 0.5 * state.v.dot(system_.M * state.v);
  account.elastic = elastic_energy(state.u);
  account.external_work += report.energy.external_work;
  account.damping += report.energy.damping;
  account.numerical += report.energy.numerical;
}

NonlinearStepReport NonlinearNewmarkIntegrator::open_step(DynamicState& state) {
  const double dt = dt_, beta = settings_.newmark.beta, gamma = settings_.newmark.gamma;
  const Eigen::SparseMatrix<double>& M = system_.M;
  const double t_next = state.t + dt;
  const PrescribedMotion motion = system_.motion(t_next);

  // The step's start: f_int(u_n), the warped K_R(u_n), and the damping built on it. The frozen
  // step reads K_R where the system keeps it (InternalForce); Newton asks for tangents again, which
  // would overwrite it, so there K_R is copied once. A checked step that iterates overwrites it
  // too, but from then on damps with the iterate's K_R (RotationUpdate::checked), so it needs no copy.
  const bool newton = settings_.update == RotationUpdate::newton;
  const bool checked = settings_.update == RotationUpdate::checked;
  Eigen::VectorXd f_int_start;
  const Eigen::SparseMatrix<double>* K_start_kept = nullptr;
  system_.internal_force(state.u, CorotationalTangent::warped, f_int_start, &K_start_kept);
  Eigen::SparseMatrix<double> K_start_copy;
  if (newton) K_start_copy = *K_start_kept;
  const Eigen::SparseMatrix<double>& K_start = newton ? K_start_copy : *K_start_kept;
  // Whether f_int is assembled at the iterate (Newton's from its start, a checked step's from its
  // check on) rather than the frozen step's f_int(u_n) + K_R (u - u_n).
  bool at_iterate = newton;
  const Eigen::SparseMatrix<double>* K = nullptr;
  const auto C_times = [&](const Eigen::VectorXd& v) { return damping_force(checked && at_iterate ? *K : K_start, v); };
  const Eigen::VectorXd C_v_start = C_times(state.v), M_a_start = M * state.a;
  // The load at the step's start was the last step's at its end.
  const Eigen::VectorXd f_start = load_value_.size() > 0 && load_time_ == state.t ? load_value_ : system_.load(state.t);

  // Newmark's predictor; the free DOFs then move with their acceleration, the prescribed ones as told.
  const NewmarkPrediction predicted = newmark_predict(state.u, state.v, state.a, dt, settings_.newmark);
  const Eigen::VectorXd f_next = system_.load(t_next);
  load_time_ = t_next;
  load_value_ = f_next;
  Eigen::VectorXd a_f = P_ * state.a;
  DynamicState next;
  next.t = t_next;
  Eigen::VectorXd f_int, residual, C_v_next;
  const auto evaluate = [&] {
    next.a = combine(a_f, motion.a);
    next.u = combine(P_ * (predicted.u + (beta * dt * dt) * next.a), motion.u);
    next.v = combine(P_ * (predicted.v + (gamma * dt) * next.a), motion.v);
    if (!at_iterate) {
      f_int = f_int_start + K_start.selfadjointView<Eigen::Upper>() * (next.u - state.u);
    } else {
      system_.internal_force(next.u, newton ? CorotationalTangent::consistent : CorotationalTangent::warped, f_int, &K);
    }
    C_v_next = C_times(next.v);
    residual = f_next - M * next.a - C_v_next - f_int;
  };

  NonlinearStepReport report;
  evaluate();
  double reference = std::max({(P_ * residual).norm(), (P_ * f_next).norm(), (P_ * M_a_start).norm()});
  for (;;) {
    if (checked && !at_iterate && report.iterations == 1) {
      // The check: the residual with f_int(u_{n+1}) itself, the rotations of the step's end.
      // The reference then counts this residual too: the frozen predictor's may be round-off
      // where Newton's is not (a body set spinning from rest: f_int(u_n) + K_R (u - u_n) is zero
      // on the spin, a, f and f_int(u_n) are zero), and a residual above every other scale
      // iterates in any case; it is then reduced by the tolerance relative to itself.
      at_iterate = true;
      evaluate();
      reference = std::max(reference, (P_ * residual).norm());
    }
    const Eigen::VectorXd r_f = P_ * residual;
    if (at_iterate) {
      report.relative_residual = reference > 0.0 ? r_f.norm() / reference : 0.0;
      report.converged = report.relative_residual <= settings_.tolerance;
      if (report.converged || report.iterations >= settings_.max_iterations) break;
    } else if (report.iterations == 1) {
      break; // the frozen step's residual is linear in a_f: one solve solves it
    }
    // M + gamma dt C + beta dt^2 K with C = alpha M + beta_R K_start: c_M M + c_K K (frozen: K = K_start).
    // Newton's tangent differs from K_start, so there the damping part is added as its own matrix.
    const double c_M = 1.0 + gamma * dt * system_.rayleigh_alpha;
    const std::clock_t matrix_start = std::clock();
    Eigen::SparseMatrix<double> newton_matrix;
    const auto matrix_with = [&](const Eigen::SparseMatrix<double>& tangent) -> const Eigen::SparseMatrix<double>& {
      if (!newton) return step_matrix(c_M, beta * dt * dt + gamma * dt * system_.rayleigh_beta, tangent);
      if (system_.rayleigh_beta == 0.0) return step_matrix(c_M, beta * dt * dt, tangent);
      newton_matrix = free_block(c_M * M + (gamma * dt * system_.rayleigh_beta) * K_start + (beta * dt * dt) * tangent);
      return newton_matrix;
    };
    // A checked step after its check: the frozen step's matrix with the iterate's K_R, of
    // the same pattern, which is also its damping's.
    const Eigen::SparseMatrix<double>& A_ff = matrix_with(at_iterate ? *K : K_start);
    const std::clock_t solve_start = std::clock();
    // The first solve starts from the change of acceleration the last step made (the motion
    // extrapolated linearly in a); CG then needs fewer iterations to reach its tolerance
    // relative to |r_f| than from zero. Newton's later corrections start from zero.
    const bool first = report.iterations == 0 && last_change_.size() == r_f.size();
    Eigen::VectorXd delta;
    if (first) delta = last_change_;
    try {
      solve(A_ff, r_f, delta);
    } catch (const NotPositiveDefinite&) {
      if (!newton)
        throw NotPositiveDefinite(step_matrix_failure(std::string("the frozen step's matrix M + gamma dt C + beta dt^2 K_R ") +
                                                          (at_iterate ? "(K_R = R K R^T of the step's iterate)"
                                                                      : "(K_R = R K R^T of the step's start)"),
                                                      r_f.size(), solver_->name()));
      // The consistent tangent adds to R K R^T the terms from dR/dx, which are negative where an
      // element is squeezed: in the frame of F's principal stretches s_i they act on the three
      // twists alone, with stiffness (sigma_i + sigma_j) / (s_i + s_j), sigma_i = 2 mu (s_i - 1) +
      // lambda tr(S - I) (the eigenvalues of the 2 x 2 blocks of dP/dF, Teran et al. 2005), where
      // R K R^T has none. A node that only such an element holds, with little mass, makes the
      // step's matrix indefinite: on chapter 7's demo, the phantom node of a sliver piece (8 % of
      // its tet, squeezed to det F = 0.37: twists of -9191, -12254 and -15441 Pa).
      // This iteration then solves with the frozen step's matrix, M + gamma dt C + beta dt^2 K_R
      // with the warped K_R of the step's start (Mueller and Gross), positive definite wherever
      // M_ff is: a quasi-Newton correction of the same residual, so the step still converges to its
      // tolerance, linearly while it falls back; the next iteration tries the consistent tangent
      // again. On the demo 16 of the 250 steps fall back in their first iteration and converge in
      // 3 or 4, as the others do in 2 to 6. Clamping every element's twists at zero instead
      // (Teran et al. 2005) would give up the exact tangent of every squeezed element in every
      // step to mend those few solves. The fallback's time counts as the solve's.
      // The frozen matrix's pattern need not be Newton's: analyse it, and Newton's after it.
      analysed_ = false;
      delta = first ? last_change_ : Eigen::VectorXd();
      try {
        solve(matrix_with(K_start), r_f, delta);
      } catch (const NotPositiveDefinite&) {
        throw NotPositiveDefinite("Newton iteration " + std::to_string(report.iterations + 1) + ": " +
                                  step_matrix_failure("the step's matrix M + gamma dt C + beta dt^2 K, with the consistent "
                                                      "tangent K and with the warped K_R = R K R^T of the step's start,",
                                                      r_f.size(), solver_->name()));
      }
      analysed_ = false;
      ++report.warped_fallbacks;
    }
    report.solver_iterations += solver_->iterations();
    report.matrix_seconds += static_cast<double>(solve_start - matrix_start) / CLOCKS_PER_SEC;
    report.solve_seconds += static_cast<double>(std::clock() - solve_start) / CLOCKS_PER_SEC;
    a_f += delta;
    ++report.iterations;
    evaluate();
    if (checked && (P_ * residual).norm() > r_f.norm()) {
      // The correction made the residual grow: the warped tangent at the iterate missed how the
      // rotations turn within the step, and the iterates would swing about the solution (on the
      // 10k liver cut seven times, on the few nodes of a sliver). Half the correction is taken
      // back, for one more assembly: there, 3 steps missed the tolerance in 30 iterations, 32
      // without it.
      a_f -= 0.5 * delta;
      evaluate();
    }
  }

  // The energy of the step on all DOFs. The reactions r = M a + C v + f_int - f at both ends,
  // with the step's own C and f_int, on the prescribed DOFs only.
  const Eigen::VectorXd du = next.u - state.u;
  // C is linear: C v_bar = (C v_n + C v_{n+1}) / 2; C v_{n+1} is the one the residual used.
  const Eigen::VectorXd r_start = M_a_start + C_v_start + f_int_start - f_start;
  const Eigen::VectorXd r_next = M * next.a + C_v_next + f_int - f_next;
  report.energy.external_work = du.dot(0.5 * (f_start + f_next)) + du.cwiseProduct(prescribed_mask_).dot(0.5 * (r_start + r_next));
  report.energy.damping = du.dot(0.5 * (C_v_start + C_v_next));
  // The balance without the end state's kinetic and strain energies, which close_step subtracts.
  report.energy.numerical = report.energy.external_work - report.energy.damping + 0.5 * state.v.dot(M * state.v) + elastic_energy(state.u);
  report.awaiting_end_energies = true;
  last_change_ = P_ * (next.a - state.a);
  state = std::move(next);
  return report;
}

NonlinearStepReport NonlinearNewmarkIntegrator::step(DynamicState& state) {
  NonlinearStepReport report = open_step(state);
  close_step(report, state);
  return report;
}

void NonlinearNewmarkIntegrator::close_step(NonlinearStepReport& report, const DynamicState& end) const {
  if (!report.awaiting_end_energies) throw std::logic_error("NonlinearNewmarkIntegrator::close_step: the step is not open");
  report.energy.numerical -= 0.5 * end.v.dot(system_.M * end.v) + elastic_energy(end.u);
  report.awaiting_end_energies = false;
}

} // namespace kerf
