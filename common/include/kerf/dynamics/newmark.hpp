/// @file newmark.hpp
/// @brief Newmark's family of implicit integrators for M a + C v + K u = f(t) (Schoch et al. section 3.5; Bathe's form, as the paper refers to Bathe).
#pragma once

#include "kerf/dynamics/linear_dynamic_system.hpp"
#include "kerf/solve/linear_solver.hpp"

#include <memory>

namespace kerf {

/// Newmark's parameters (Bathe's alpha is beta here, his delta is gamma). The default is the
/// average acceleration (trapezoidal) rule: unconditionally stable, second order, and without
/// numerical dissipation. Unconditionally stable iff 2 beta >= gamma >= 1/2; gamma > 1/2 damps
/// (take beta = (gamma + 1/2)^2 / 4); beta = 0, gamma = 1/2 is the central difference
/// (central_difference.hpp), stable only below 2 / omega_max.
struct NewmarkParameters {
  double beta = 0.25;
  double gamma = 0.5;
};

/// Newmark's predictor on the free DOFs: where u and v get in a step of dt if a_{n+1} were 0,
///   u~ = u_n + dt v_n + dt^2 (1/2 - beta) a_n,   v~ = v_n + dt (1 - gamma) a_n.
struct NewmarkPrediction {
  Eigen::VectorXd u, v;
};
NewmarkPrediction newmark_predict(const Eigen::VectorXd& u, const Eigen::VectorXd& v, const Eigen::VectorXd& a, double dt,
                                  const NewmarkParameters& parameters);

/// Newmark's corrector: the state at t_next from the prediction and the free DOFs' a_{n+1},
///   u_{n+1} = u~ + beta dt^2 a_{n+1},   v_{n+1} = v~ + gamma dt a_{n+1},
/// expanded to all DOFs (the prescribed ones keep their values). HHT-alpha shares both steps.
DynamicState newmark_correct(const ReducedDynamicSystem& reduced, double t_next, const NewmarkPrediction& predicted,
                             const Eigen::VectorXd& a_next, double dt, const NewmarkParameters& parameters);

/// Newmark in its acceleration form (Hughes 2000, section 9.1), one linear solve per step:
///
///   predict   u~ = u_n + dt v_n + dt^2 (1/2 - beta) a_n,   v~ = v_n + dt (1 - gamma) a_n,
///   solve     (M + gamma dt C + beta dt^2 K) a_{n+1} = f_{n+1} - C v~ - K u~,
///   correct   u_{n+1} = u~ + beta dt^2 a_{n+1},            v_{n+1} = v~ + gamma dt a_{n+1}.
///
/// The matrix is Bathe's K^ = K + a0 M + a1 C divided by a0 = 1 / (beta dt^2): the same
/// steps, with the acceleration as the unknown, so that beta = 0 needs no special case. It is
/// factorised once, in the constructor.
///
/// Energy [derived from the updates and the equations averaged over the step]: with
/// [a] = a_{n+1} - a_n, a_bar and v_bar the step's averages,
///
///   Delta(v^T M v / 2 + u^T K u / 2) = Delta u . f_bar - Delta u^T C v_bar - numerical,
///   numerical = dt^2 (beta - gamma / 2) [a]^T M a_bar - dt (gamma - 1/2) v_bar^T M [a],
///
/// which is zero for the average acceleration rule (it conserves energy exactly), a loss that
/// telescopes for the central difference (beta = 0: -dt^2/8 Delta(a^T M a)), and a dissipation of
/// the high frequencies for gamma > 1/2.
class NewmarkIntegrator {
public:
  /// @param system kept by reference; C and K as they are now (rebuild the integrator when they change)
  /// @param dt     the time step, s, positive
  NewmarkIntegrator(const LinearDynamicSystem& system, double dt, NewmarkParameters parameters = {},
                    const SolverSettings& solver_settings = {});
  /// Advances `state` (at t) to t + dt and returns what the step did to the energy.
  StepEnergy step(DynamicState& state);
  double time_step() const { return dt_; }
  const ReducedDynamicSystem& reduced() const { return reduced_; }

private:
  ReducedDynamicSystem reduced_;
  double dt_;
  NewmarkParameters parameters_;
  std::unique_ptr<LinearSolver> solver_;
};

} // namespace kerf
