/// @file linear_dynamic_system.hpp
/// @brief The semi-discrete equations M a + C v + K u = f(t) with Dirichlet DOFs (Schoch et al. eq. 25), their state,
///        and the free-free blocks every integrator steps.
#pragma once

#include "kerf/fem/dof_map.hpp"
#include "kerf/solve/linear_solver.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>

namespace kerf {

/// M a + C v + K u = f(t) (eq. 25) on all DOFs (3 per DOF node: [u; a] for a cut body), the
/// DOFs that `dofs` prescribes held at their values for all time (their v and a are zero).
/// M, C and K are symmetric with both triangles stored; M restricted to the free DOFs must be
/// positive definite, K positive semi-definite.
struct LinearDynamicSystem {
  Eigen::SparseMatrix<double> M;              ///< mass (consistent or lumped, lumped_mass.hpp), kg
  Eigen::SparseMatrix<double> C;              ///< damping (e.g. rayleigh_damping), kg/s
  Eigen::SparseMatrix<double> K;              ///< stiffness, N/m
  DofMap dofs;                                ///< which DOFs are free, and the prescribed values (m)
  std::function<Eigen::VectorXd(double)> load; ///< f(t) on all DOFs (N); only its free entries act
};

/// The state at time t, on all DOFs (prescribed DOFs at their values, v = a = 0 there).
struct DynamicState {
  double t = 0.0;    ///< time, s
  Eigen::VectorXd u; ///< displacement, m
  Eigen::VectorXd v; ///< velocity, m/s
  Eigen::VectorXd a; ///< acceleration, m/s^2, satisfying the equations of motion at t
};

/// What one step did to the energy (J), for the energy account (energy_account.hpp).
struct StepEnergy {
  double external_work = 0.0; ///< trapezoidal work of the load, (u_{n+1} - u_n) . (f_n + f_{n+1}) / 2
  double damping = 0.0;       ///< work the scheme's damping force did against the motion (>= 0)
  /// Energy the integrator itself removed: the rest of the balance, in closed form for Newmark,
  /// the central difference and backward Euler, by construction for HHT-alpha (energy_account.hpp).
  double numerical = 0.0;
};

/// The free-free blocks M_ff, C_ff, K_ff of a system and its load on the free DOFs, lifted:
/// f_f(t) - K_fc u_c. The integrators solve on the free DOFs and report full vectors.
class ReducedDynamicSystem {
public:
  explicit ReducedDynamicSystem(const LinearDynamicSystem& system);
  const LinearDynamicSystem& system() const { return system_; }
  const Eigen::SparseMatrix<double>& M_ff() const { return M_ff_; }
  const Eigen::SparseMatrix<double>& C_ff() const { return C_ff_; }
  const Eigen::SparseMatrix<double>& K_ff() const { return K_ff_; }
  /// f_f(t) - K_fc u_c (num_free).
  Eigen::VectorXd free_load(double t) const;
  /// The free entries of a full vector.
  Eigen::VectorXd restrict_to_free(const Eigen::VectorXd& full) const { return system_.dofs.restrict_to_free(full); }
  /// The full vector with `free` on the free DOFs and `constrained` (u_c, or 0 for v and a) on the others.
  Eigen::VectorXd expand(const Eigen::VectorXd& free, bool with_prescribed) const;

private:
  const LinearDynamicSystem& system_;
  Eigen::SparseMatrix<double> M_ff_, C_ff_, K_ff_;
  Eigen::VectorXd lift_; // K_fc u_c
};

/// The state at t0 from u0 and v0 (full vectors; their prescribed entries are overwritten), with
/// the acceleration that satisfies the equations there: M_ff a_f = f_f(t0) - C_ff v_f - K_ff u_f - K_fc u_c.
DynamicState consistent_initial_state(const ReducedDynamicSystem& reduced, const Eigen::VectorXd& u0,
                                      const Eigen::VectorXd& v0, double t0, const SolverSettings& solver_settings);

/// Kinetic energy (1/2) v^T M v of a state, J.
double kinetic_energy(const LinearDynamicSystem& system, const DynamicState& state);
/// Elastic energy (1/2) u^T K u of a state, J.
double elastic_energy(const LinearDynamicSystem& system, const DynamicState& state);

} // namespace kerf
