#include "kerf/dynamics/linear_dynamic_system.hpp"

#include <stdexcept>
#include <vector>

namespace kerf {

namespace {

// P (num_free x size), the 0/1 matrix that picks the free DOFs: A_ff = P A P^T.
Eigen::SparseMatrix<double> free_selection(const DofMap& dofs) {
  std::vector<Eigen::Triplet<double>> entries;
  for (std::size_t i = 0; i < dofs.free_index.size(); ++i)
    if (dofs.free_index[i] >= 0) entries.emplace_back(dofs.free_index[i], static_cast<int>(i), 1.0);
  Eigen::SparseMatrix<double> P(dofs.num_free, static_cast<Eigen::Index>(dofs.free_index.size()));
  P.setFromTriplets(entries.begin(), entries.end());
  return P;
}

} // namespace

ReducedDynamicSystem::ReducedDynamicSystem(const LinearDynamicSystem& system) : system_(system) {
  const auto size = static_cast<Eigen::Index>(system.dofs.free_index.size());
  for (const Eigen::SparseMatrix<double>* A : {&system.M, &system.C, &system.K})
    if (A->rows() != size || A->cols() != size)
      throw std::invalid_argument("ReducedDynamicSystem: M, C and K must be square with one row per DOF of the DofMap");
  const Eigen::SparseMatrix<double> P = free_selection(system.dofs);
  const Eigen::SparseMatrix<double> Pt = P.transpose();
  M_ff_ = P * system.M * Pt;
  C_ff_ = P * system.C * Pt;
  K_ff_ = P * system.K * Pt;
  // K u_c with u_c the prescribed values (zero on free DOFs): its free rows are K_fc u_c.
  lift_ = P * (system.K * system.dofs.prescribed);
}

Eigen::VectorXd ReducedDynamicSystem::free_load(double t) const {
  return restrict_to_free(system_.load(t)) - lift_;
}

Eigen::VectorXd ReducedDynamicSystem::expand(const Eigen::VectorXd& free, bool with_prescribed) const {
  Eigen::VectorXd full = system_.dofs.expand(free);
  if (!with_prescribed)
    for (std::size_t i = 0; i < system_.dofs.free_index.size(); ++i)
      if (system_.dofs.free_index[i] < 0) full[static_cast<Eigen::Index>(i)] = 0.0;
  return full;
}

DynamicState consistent_initial_state(const ReducedDynamicSystem& reduced, const Eigen::VectorXd& u0,
                                      const Eigen::VectorXd& v0, double t0, const SolverSettings& solver_settings) {
  DynamicState state;
  state.t = t0;
  state.u = reduced.expand(reduced.restrict_to_free(u0), true);
  state.v = reduced.expand(reduced.restrict_to_free(v0), false);
  const Eigen::VectorXd rhs = reduced.free_load(t0) - reduced.C_ff() * reduced.restrict_to_free(state.v) -
                              reduced.K_ff() * reduced.restrict_to_free(state.u);
  Eigen::VectorXd a_free = solve_once(reduced.M_ff(), rhs, solver_settings);
  state.a = reduced.expand(a_free, false);
  return state;
}

double kinetic_energy(const LinearDynamicSystem& system, const DynamicState& state) {
  return 0.5 * state.v.dot(system.M * state.v);
}

double elastic_energy(const LinearDynamicSystem& system, const DynamicState& state) {
  return 0.5 * state.u.dot(system.K * state.u);
}

} // namespace kerf
