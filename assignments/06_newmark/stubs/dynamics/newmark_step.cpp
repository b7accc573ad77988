// Assignment 06 (assignments/06_newmark/README.md): one Newmark step in acceleration form. This
// file replaces common/src/dynamics/newmark_step.cpp in the graded build; the declarations, with
// their full comments, are in kerf/dynamics/newmark.hpp. The constructor (newmark.cpp, not
// handed out) has already factorised M_ff + gamma dt C_ff + beta dt^2 K_ff into solver_.
#include "kerf/dynamics/newmark.hpp"

#include <stdexcept>

namespace kerf {

/// Newmark's predictor on the free DOFs (Hughes 2000, section 9.1): where u and v get
/// in a step of dt if a_{n+1} were 0,
///   u~ = u_n + dt v_n + dt^2 (1/2 - beta) a_n,   v~ = v_n + dt (1 - gamma) a_n.
NewmarkPrediction newmark_predict([[maybe_unused]] const Eigen::VectorXd& u, [[maybe_unused]] const Eigen::VectorXd& v,
                                  [[maybe_unused]] const Eigen::VectorXd& a, [[maybe_unused]] double dt,
                                  [[maybe_unused]] const NewmarkParameters& parameters) {
  throw std::logic_error("assignment 06: implement newmark_predict (assignments/06_newmark/README.md)");
}

/// Newmark's corrector: the state at t_next from the prediction and the free DOFs' a_{n+1},
///   u_{n+1} = u~ + beta dt^2 a_{n+1},   v_{n+1} = v~ + gamma dt a_{n+1},
/// expanded to all DOFs with reduced.expand (the prescribed ones keep their values: u_c for u,
/// 0 for v and a; chapter 6's linear system holds its clamps still).
DynamicState newmark_correct([[maybe_unused]] const ReducedDynamicSystem& reduced, [[maybe_unused]] double t_next,
                             [[maybe_unused]] const NewmarkPrediction& predicted, [[maybe_unused]] const Eigen::VectorXd& a_next,
                             [[maybe_unused]] double dt, [[maybe_unused]] const NewmarkParameters& parameters) {
  throw std::logic_error("assignment 06: implement newmark_correct (assignments/06_newmark/README.md)");
}

/// Advances `state` (at t) to t + dt: predict, solve
///   (M + gamma dt C + beta dt^2 K) a_{n+1} = f_{n+1} - C v~ - K u~   (on the free DOFs),
/// correct; and returns what the step did to the energy, on full vectors, with [a] = a_{n+1} - a_n
/// and a_bar, v_bar, f_bar the step's averages:
///   external_work = Delta u . f_bar,   damping = Delta u^T C v_bar,
///   numerical = dt^2 (beta - gamma / 2) [a]^T M a_bar - dt (gamma - 1/2) v_bar^T M [a].
StepEnergy NewmarkIntegrator::step([[maybe_unused]] DynamicState& state) {
  throw std::logic_error("assignment 06: implement NewmarkIntegrator::step (assignments/06_newmark/README.md)");
}

} // namespace kerf
