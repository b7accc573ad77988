#include "kerf/dynamics/quasi_newton_newmark.hpp"

#include <Eigen/SparseCholesky>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

namespace kerf {

namespace {

double inner(const Eigen::MatrixXd& x, const Eigen::MatrixXd& y) { return x.cwiseProduct(y).sum(); }

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The scalar part m_ij of a mass whose 3x3 blocks are m_ij I_3: its x entries, each checked
// against the y and z entries of its block (the others must be zero).
Eigen::SparseMatrix<double> scalar_mass(const Eigen::SparseMatrix<double>& M) {
  std::vector<Eigen::Triplet<double>> scalar;
  for (Eigen::Index j = 0; j < M.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(M, j); it; ++it)
      if (it.row() % 3 == 0 && it.col() % 3 == 0)
        scalar.emplace_back(static_cast<int>(it.row() / 3), static_cast<int>(it.col() / 3), it.value());
  Eigen::SparseMatrix<double> M_s(M.rows() / 3, M.cols() / 3);
  M_s.setFromTriplets(scalar.begin(), scalar.end());
  const double tolerance = 1e-12 * M_s.norm();
  for (Eigen::Index j = 0; j < M.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(M, j); it; ++it) {
      const double expected = it.row() % 3 == it.col() % 3 ? M_s.coeff(it.row() / 3, it.col() / 3) : 0.0;
      if (std::abs(it.value() - expected) > tolerance)
        throw std::invalid_argument("QuasiNewtonNewmark: the mass is not the same in x, y and z (m_ij I_3 per node pair)");
    }
  return M_s;
}

// The rows and columns of a node-indexed matrix at the nodes with a position in [0, size), in that
// order.
Eigen::SparseMatrix<double> restrict_to(const Eigen::SparseMatrix<double>& A, const std::vector<int>& position, Eigen::Index size) {
  std::vector<Eigen::Triplet<double>> entries;
  for (Eigen::Index j = 0; j < A.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, j); it; ++it) {
      const int r = position[static_cast<std::size_t>(it.row())], c = position[static_cast<std::size_t>(it.col())];
      if (r >= 0 && c >= 0 && r < size && c < size) entries.emplace_back(r, c, it.value());
    }
  Eigen::SparseMatrix<double> restricted(size, size);
  restricted.setFromTriplets(entries.begin(), entries.end());
  return restricted;
}

} // namespace

QuasiNewtonNewmark::QuasiNewtonNewmark(double dt, const LinearMaterial& material, QuasiNewtonNewmarkSettings settings)
    : dt_(dt), material_(material), settings_(settings) {
  if (!(dt > 0.0)) throw std::invalid_argument("QuasiNewtonNewmark: the time step must be positive");
  if (!(settings_.newmark.beta > 0.0)) throw std::invalid_argument("QuasiNewtonNewmark: Newmark's beta must be positive (an implicit step)");
  if (settings_.history < 0 || settings_.iterations < 0) throw std::invalid_argument("QuasiNewtonNewmark: negative iteration counts");
}

void QuasiNewtonNewmark::set_body(QuasiNewtonBody body) {
  body_ = std::move(body);
  last_valid_ = false;
  pairs_.clear();
  // The rotations the last body ended with start the new body's (a cut turns nothing).
  if (last_rotations_.size() >= static_cast<std::size_t>(body_.pieces->num_tets())) body_.pieces->warm_rotations(last_rotations_);
  const Eigen::Index nodes = body_.pieces->num_dof_nodes();
  if (body_.M.rows() != 3 * nodes || body_.load.size() != 3 * nodes || static_cast<Eigen::Index>(body_.dofs.free_index.size()) != 3 * nodes)
    throw std::invalid_argument("QuasiNewtonNewmark::set_body: the mass, load and DOF map must have 3 entries per DOF node");
  // The free DOF nodes, the mesh's first: each node free in all three components or in none.
  free_nodes_.clear();
  Eigen::Index num_standard = 0;
  for (int pass = 0; pass < 2; ++pass)
    for (Eigen::Index i = 0; i < nodes; ++i) {
      if ((i < body_.num_standard_nodes) != (pass == 0)) continue;
      int free = 0;
      for (int c = 0; c < 3; ++c) free += body_.dofs.free_index[static_cast<std::size_t>(3 * i + c)] >= 0;
      if (free != 0 && free != 3)
        throw std::invalid_argument("QuasiNewtonNewmark: DOF node " + std::to_string(i) +
                                    " is held in some components only; chapter 8's matrix holds whole nodes");
      if (free == 3) {
        free_nodes_.push_back(static_cast<int>(i));
        num_standard += pass == 0;
      }
    }
  // (8.4)'s constants and (8.6)'s matrix on the free nodes.
  const double beta = settings_.newmark.beta, gamma = settings_.newmark.gamma;
  c_M_ = 1.0 / (beta * dt_ * dt_) + body_.rayleigh_alpha * gamma / (beta * dt_);
  c_D_ = body_.rayleigh_beta * gamma / (beta * dt_);
  const double mu = material_.mu();
  c_L_ = (1.0 + c_D_) * mu * (settings_.stiffness_in_mu > 0.0 ? settings_.stiffness_in_mu : 2.0 + material_.lambda() / mu);
  free_position_.assign(static_cast<std::size_t>(nodes), -1);
  for (std::size_t k = 0; k < free_nodes_.size(); ++k) free_position_[static_cast<std::size_t>(free_nodes_[k])] = static_cast<int>(k);
  free_mask_.setZero(3 * nodes);
  for (int node : free_nodes_) free_mask_.segment<3>(3 * node).setOnes();
  // A's block of the mesh's nodes is the uncut body's when the same nodes are free, the pieces'
  // volumes sum to their tets' and the mass's block of the mesh's nodes is the one factorised:
  // then its factor stays, and only the enrichments' rows are built (growing_cholesky.hpp).
  const Eigen::SparseMatrix<double> M_s = scalar_mass(body_.M);
  const Eigen::SparseMatrix<double> M_ss = restrict_to(M_s, free_position_, num_standard);
  const bool grows = factor_ && free_standard_nodes_ == std::vector<int>(free_nodes_.begin(), free_nodes_.begin() + num_standard) &&
                     body_.pieces->largest_volume_mismatch() <= 1e-12 && (M_ss - standard_mass_).norm() <= 1e-14 * standard_mass_.norm();
  if (!grows) {
    factor_ = std::make_unique<GrowingCholesky>(restrict_to(c_M_ * M_s + c_L_ * body_.pieces->laplacian(), free_position_, num_standard));
    ++factorisations_;
    free_standard_nodes_.assign(free_nodes_.begin(), free_nodes_.begin() + num_standard);
    standard_mass_ = M_ss;
  }
  // The enrichments' columns of A: from the mass's and the Laplacian's enrichment entries.
  std::vector<Eigen::Triplet<double>> se, ee;
  const auto add = [&](const Eigen::SparseMatrix<double>& X, double scale) {
    for (Eigen::Index j = 0; j < X.outerSize(); ++j)
      for (Eigen::SparseMatrix<double>::InnerIterator it(X, j); it; ++it) {
        const int r = free_position_[static_cast<std::size_t>(it.row())], c = free_position_[static_cast<std::size_t>(it.col())];
        if (r < 0 || c < num_standard) continue;
        if (r < num_standard) se.emplace_back(r, c - num_standard, scale * it.value());
        else ee.emplace_back(r - num_standard, c - num_standard, scale * it.value());
      }
  };
  add(M_s, c_M_);
  add(body_.pieces->enrichment_laplacian(), c_L_);
  const auto k = static_cast<Eigen::Index>(free_nodes_.size()) - num_standard;
  Eigen::SparseMatrix<double> A_se(num_standard, k), A_ee(k, k);
  A_se.setFromTriplets(se.begin(), se.end());
  A_ee.setFromTriplets(ee.begin(), ee.end());
  factor_->set_trailing(A_se, A_ee);
}

Eigen::SparseMatrix<double> QuasiNewtonNewmark::step_matrix() const {
  return restrict_to(c_M_ * scalar_mass(body_.M) + c_L_ * body_.pieces->laplacian(), free_position_,
                     static_cast<Eigen::Index>(free_nodes_.size()));
}

void QuasiNewtonNewmark::remember(const Eigen::VectorXd& u, double W) {
  last_u_ = u;
  last_W_ = W;
  last_valid_ = true;
}

double QuasiNewtonNewmark::elastic_energy(const Eigen::VectorXd& u) {
  if (last_valid_ && last_u_.size() == u.size() && last_u_ == u) return last_W_;
  Eigen::VectorXd f_int;
  remember(u, body_.pieces->energy(u, f_int, last_rotations_));
  return last_W_;
}

Eigen::MatrixXd QuasiNewtonNewmark::gather(const Eigen::VectorXd& full) const {
  Eigen::MatrixXd free(static_cast<Eigen::Index>(free_nodes_.size()), 3);
  for (std::size_t k = 0; k < free_nodes_.size(); ++k) free.row(static_cast<Eigen::Index>(k)) = full.segment<3>(3 * free_nodes_[k]).transpose();
  return free;
}

void QuasiNewtonNewmark::scatter_add(const Eigen::MatrixXd& free, Eigen::VectorXd& full) const {
  for (std::size_t k = 0; k < free_nodes_.size(); ++k) full.segment<3>(3 * free_nodes_[k]) += free.row(static_cast<Eigen::Index>(k)).transpose();
}

DynamicState QuasiNewtonNewmark::initial_state(const Eigen::VectorXd& u0, const Eigen::VectorXd& v0, double t0) {
  DynamicState state{t0, u0, v0, Eigen::VectorXd::Zero(u0.size())};
  Eigen::VectorXd f_int, Kv;
  remember(u0, body_.pieces->energy(u0, f_int, last_rotations_));
  body_.pieces->warped_product(last_rotations_, v0, Kv);
  const Eigen::VectorXd r = body_.load - f_int - body_.rayleigh_alpha * (body_.M * v0) - body_.rayleigh_beta * Kv;
  // M_ff a_f = r_f with the scalar mass of the free nodes.
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> mass(
      restrict_to(scalar_mass(body_.M), free_position_, static_cast<Eigen::Index>(free_nodes_.size())));
  if (mass.info() != Eigen::Success) throw std::runtime_error("QuasiNewtonNewmark: the free nodes' mass is not positive definite");
  const Eigen::MatrixXd a_f = mass.solve(gather(r));
  scatter_add(a_f, state.a);
  return state;
}

EnergyAccount QuasiNewtonNewmark::start_account(const DynamicState& state) {
  EnergyAccount account;
  account.kinetic = 0.5 * state.v.dot(body_.M * state.v);
  account.elastic = elastic_energy(state.u);
  return account;
}

void QuasiNewtonNewmark::solve(Eigen::MatrixXd& B, QuasiNewtonStepReport& report) {
  const auto start = std::chrono::steady_clock::now();
  factor_->solve(B);
  report.solve_seconds += seconds_since(start);
}

double QuasiNewtonNewmark::step_energy(const Eigen::VectorXd& u, Eigen::VectorXd& gradient, QuasiNewtonStepReport& report) {
  // Your code: E_n(u) (8.4), up to a constant, and its gradient on all DOFs into `gradient`
  // (README.md). The pieces' pass, CorotatedPieces::step_terms, gives W(u) + c_D/2 d^T K_R d and
  // its gradient in one call; keep W with remember(u, W) and time the pass into
  // report.pieces_seconds, as the rest of this file does.
  (void)u, (void)gradient, (void)report;
  throw std::logic_error("assignment 08: implement QuasiNewtonNewmark::step_energy (assignments/08_real_time/README.md)");
}

Eigen::MatrixXd QuasiNewtonNewmark::descent_direction(const Eigen::MatrixXd& g, QuasiNewtonStepReport& report) {
  // Your code: L-BFGS's direction d = -H g (README.md), from the pairs in pairs_ (oldest first)
  // and A^{-1} as the initial inverse Hessian (solve(q, report) replaces q by A^{-1} q); if that
  // is not a descent direction, forget the pairs and take -A^{-1} g.
  (void)g, (void)report;
  throw std::logic_error("assignment 08: implement QuasiNewtonNewmark::descent_direction (assignments/08_real_time/README.md)");
}

StepEnergy QuasiNewtonNewmark::step_balance(const DynamicState& state, double kinetic_n, double W_n, const Eigen::VectorXd& x,
                                            const Eigen::VectorXd& v_tilde, QuasiNewtonStepReport& report) {
  const double beta = settings_.newmark.beta, gamma = settings_.newmark.gamma;
  // Newmark's correctors at x.
  const Eigen::VectorXd a = ((x - u_tilde_) / (beta * dt_ * dt_)).cwiseProduct(free_mask_);
  const Eigen::VectorXd v = v_tilde + gamma * dt_ * a;
  // The works: the load's, and the damping's Delta u . C v_bar with the step's C; the rest of the
  // balance is the step's own (energy_account.hpp).
  const Eigen::VectorXd du = x - state.u;
  const Eigen::VectorXd v_bar = 0.5 * (state.v + v);
  Eigen::VectorXd K_vbar;
  const auto start = std::chrono::steady_clock::now();
  body_.pieces->warped_product(rotations_n_, v_bar, K_vbar);
  report.pieces_seconds += seconds_since(start);
  StepEnergy energy;
  energy.external_work = du.dot(body_.load);
  energy.damping = du.dot(body_.rayleigh_alpha * (body_.M * v_bar) + body_.rayleigh_beta * K_vbar);
  const double kinetic_change = 0.5 * v.dot(body_.M * v) - kinetic_n;
  energy.numerical = energy.external_work - energy.damping - kinetic_change - (elastic_energy(x) - W_n); // x: the last evaluated
  return energy;
}

QuasiNewtonStepReport QuasiNewtonNewmark::step(DynamicState& state) {
  const double beta = settings_.newmark.beta, gamma = settings_.newmark.gamma;
  QuasiNewtonStepReport report;
  const double W_n = elastic_energy(state.u); // found by the step before, at its end
  const double kinetic_n = 0.5 * state.v.dot(body_.M * state.v);
  rotations_n_ = last_rotations_;
  // Newmark's predictors, zero on the held (still) DOFs.
  u_tilde_ = (state.u + dt_ * state.v + dt_ * dt_ * (0.5 - beta) * state.a).cwiseProduct(free_mask_);
  const Eigen::VectorXd v_tilde = (state.v + dt_ * (1.0 - gamma) * state.a).cwiseProduct(free_mask_);
  b_ = body_.load - body_.rayleigh_alpha * (body_.M * v_tilde);
  // (8.4)'s stiffness damping, c_D/2 |u - u~|^2_{K_R} + beta_R (K_R v~) . u, is c_D/2 |u - u^|^2_{K_R}
  // with u^ = u~ - (beta dt / gamma) v~ and a constant more: one warped term in the pieces' pass.
  auto start = std::chrono::steady_clock::now();
  body_.pieces->gradient_sums(u_tilde_ - (beta * dt_ / gamma) * v_tilde, damping_reference_sums_);
  report.pieces_seconds += seconds_since(start);

  // L-BFGS on (8.4) from the guess a_{n+1} = a_n, with A^{-1} (8.6) as the initial inverse Hessian.
  Eigen::VectorXd x = u_tilde_ + beta * dt_ * dt_ * state.a.cwiseProduct(free_mask_);
  Eigen::VectorXd gradient;
  double E = step_energy(x, gradient, report);
  Eigen::MatrixXd g = gather(gradient);
  const double scale = std::max(g.norm(), gather(body_.load).norm());
  if (!settings_.keep_history) pairs_.clear();
  const bool tight = settings_.tolerance > 0.0;
  // L-BFGS's iterations until `done`, from x; `it` counts them over the whole step.
  int it = 0;
  const auto minimise = [&](const auto& done) {
    for (;; ++it) {
      report.relative_gradient = scale > 0.0 ? g.norm() / scale : 0.0;
      if (done()) break;
      if (it >= settings_.max_iterations) {
        report.converged = false;
        break;
      }
      const Eigen::MatrixXd d = descent_direction(g, report);
      const double slope = inner(g, d);
      // Backtracking on E_n: the full step unless it fails Armijo's test.
      double step_length = 1.0;
      Eigen::VectorXd x_new, gradient_new;
      double E_new = 0.0;
      for (;;) {
        x_new = x;
        scatter_add(step_length * d, x_new);
        E_new = step_energy(x_new, gradient_new, report);
        ++report.iterations;
        if (E_new <= E + 1e-4 * step_length * slope || step_length < 1.0 / 64.0) break;
        step_length *= 0.5;
      }
      const Eigen::MatrixXd g_new = gather(gradient_new);
      Eigen::MatrixXd s = step_length * d, y = g_new - g;
      if (inner(s, y) > 1e-12 * s.norm() * y.norm()) {
        pairs_.emplace_back(std::move(s), std::move(y));
        if (static_cast<int>(pairs_.size()) > settings_.history) pairs_.pop_front();
      }
      x = std::move(x_new);
      g = g_new;
      E = E_new;
    }
  };
  if (tight) minimise([&] { return report.relative_gradient <= settings_.tolerance; });
  else minimise([&] { return it >= settings_.iterations; });
  StepEnergy balance = step_balance(state, kinetic_n, W_n, x, v_tilde, report);
  // The check of a step of a fixed number of iterations: near E_n's minimum a step creates little
  // energy; a few iterations from it, where a flap or a sliver the blade left turns fast, it can
  // create some every step, and the run diverges. Such a step goes on, with exact rotations and
  // fresh pairs, to a relative gradient of 1e-6 or check_iterations more iterations.
  if (!tight && settings_.energy_tolerance > 0.0 &&
      -balance.numerical > settings_.energy_tolerance * (kinetic_n + W_n + std::abs(balance.external_work))) {
    report.checked = true;
    pairs_.clear();
    E = step_energy(x, gradient, report);
    g = gather(gradient);
    const int limit = it + settings_.check_iterations;
    minimise([&] { return report.relative_gradient <= 1e-6 || it >= limit; });
    balance = step_balance(state, kinetic_n, W_n, x, v_tilde, report);
  }
  report.energy = balance;
  // Newmark's correctors.
  DynamicState end{state.t + dt_, x, Eigen::VectorXd(), (x - u_tilde_) / (beta * dt_ * dt_)};
  end.a = end.a.cwiseProduct(free_mask_);
  end.v = v_tilde + gamma * dt_ * end.a;
  state = std::move(end);
  return report;
}

void QuasiNewtonNewmark::add_step(EnergyAccount& account, const DynamicState& state, const QuasiNewtonStepReport& report) {
  account.kinetic = 0.5 * state.v.dot(body_.M * state.v);
  account.elastic = elastic_energy(state.u);
  account.external_work += report.energy.external_work;
  account.damping += report.energy.damping;
  account.numerical += report.energy.numerical;
}

} // namespace kerf
