/// @file quasi_static_solver.hpp
/// @brief Equilibrium of the corotated body under large loads: load steps and Newton iterations.
#pragma once

#include "kerf/corotation/quasi_static_model.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/solve/linear_solver.hpp"

#include <Eigen/Core>
#include <functional>
#include <vector>

namespace kerf {

/// Where Newton's method starts each load step.
enum class LoadStepPredictor {
  previous_state, ///< at the last equilibrium
  secant,         ///< on the line through the last two equilibria, one step further
};

/// How the quasi-static solver works.
struct QuasiStaticSettings {
  int load_steps = 10;        ///< loads and prescribed displacements ramped in equal increments
  int max_iterations = 40;    ///< Newton iterations allowed per load step
  double tolerance = 1e-9;    ///< stop when |r_f| <= tolerance * (the step's force scale)
  RotationMethod rotation = RotationMethod::automatic;
  CorotationalTangent tangent = CorotationalTangent::consistent;
  LoadStepPredictor predictor = LoadStepPredictor::previous_state;
  SolverSettings solver;      ///< for each linearised system
};

/// One Newton iteration, for the convergence history.
struct NewtonIteration {
  int step = 0;              ///< load step, 1-based
  int iteration = 0;         ///< iteration within the step, 0 = before the first update
  double relative_residual = 0.0; ///< |r_f - K_fc du_c| / force scale: at iteration 0, du_c is the step's
                                  ///< prescribed increment; later it is 0 and this is |r_f| / scale
  bool warped_fallback = false;   ///< the consistent tangent was not positive definite here
};

/// What the solver returns.
struct QuasiStaticResult {
  Eigen::VectorXd u;                  ///< displacements at the last load step (3 model.num_dof_nodes())
  std::vector<NewtonIteration> history;
  bool converged = true;              ///< every step met the tolerance
  int total_iterations = 0;           ///< linear solves in all
  int factorisations = 0;             ///< numeric factorisations in all (LinearSolver::factorisations)
  int linear_iterations = 0;          ///< the linear solver's iterations, summed (1 per direct solve)
  CorotationStatistics last_statistics;
};

/// The prescribed displacements (3#V; only the prescribed DOFs are read) at load factor
/// lambda in [0, 1]. A straight ramp, lambda u_c, is right for translations but not for a turn:
/// it moves the nodes along the chord, which squeezes a rotated face mid-way; a turn must be
/// ramped by its angle (see kerf::scene_prescribed_displacements).
using PrescribedPath = std::function<Eigen::VectorXd(double lambda)>;

/// Finds u with f_int(u) = lambda f_ext on the free DOFs and u_c = path(lambda) (by default
/// lambda u_c_final), for lambda = 1/N, 2/N, ..., 1.
///
/// Each step starts from the previous equilibrium u_n (the default) or, with the secant
/// predictor, from u_n + (u_n - u_{n-1}) on the free DOFs and the step's u_c on the prescribed
/// ones. The steps are equal, so on a smooth load path the secant start is off by O(step^2)
/// instead of O(step), and Newton's method needs fewer iterations (chapter 2's benchmark: 60
/// instead of 79 for 20 steps of the bent beam). But a straight-line extrapolation of a turning
/// body stretches and squeezes it, while the last equilibrium, a rigid turn behind, has no
/// strain a corotated element sees: on the chapter 2 demo, 9 degrees of turn per step, the
/// secant start fails in the third step (tests/chapter_02/test_quasi_static.cpp). Hence the
/// default. The first step has no secant. From the last equilibrium, the first iteration
/// linearises about it with
/// the prescribed increment lifted to the right-hand side (K_ff du_f = r_f - K_fc du_c), so that
/// the nodes next to a moving support move with it from the start; later iterations correct
/// with du_c = 0. The tangent is `settings.tangent`; when the consistent tangent is not positive
/// definite (strong compression), as any solver finds out (LinearSolver::factorize and solve
/// throw NotPositiveDefinite, CG may also fail to converge), that iteration uses the warped one,
/// R K R^T, which always is.
/// The force scale of a step is the largest of |lambda f_ext|, |f_int(u)| over all DOFs, and
/// |K_fc du_c|: the forces that are in play, so that the tolerance is relative. Below that, a
/// residual under the round-off floor 10 eps |K X| (QuasiStaticModel::position_force_norm)
/// counts as converged too: f_int is a difference of forces of size |K X|, and cannot be
/// computed more accurately than that, however small the load.
QuasiStaticResult solve_quasi_static(const QuasiStaticModel& model, const DofMap& dofs, const Eigen::VectorXd& f_ext,
                                     const QuasiStaticSettings& settings, const PrescribedPath& path = {});

} // namespace kerf
