/// @file nonlinear_newmark.hpp
/// @brief Newmark's method for M a + C v + f_int(u) = f(t) with a nonlinear internal force (the corotated body, Schoch et al.
///        eq. 40) and prescribed DOFs that move in time: rotations frozen per step (Mueller and Gross),
///        the frozen step checked at its end, or Newton.
#pragma once

#include "kerf/corotation/corotated_element.hpp"
#include "kerf/dynamics/energy_account.hpp"
#include "kerf/dynamics/newmark.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/solve/linear_solver.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace kerf {

/// Displacement, velocity and acceleration of the prescribed DOFs at one time, on all DOFs
/// (the free entries are not read). Derivatives of one function of time, or the step's energy
/// account books a work the clamp never did.
struct PrescribedMotion {
  Eigen::VectorXd u, v, a;
};

/// The internal force f_int(u) on all DOFs and, when `K` is given, its tangent on all DOFs
/// (both triangles): the warped R K R^T (eq. 38) or the consistent one, as `tangent` asks. A
/// linear body returns K u and K whatever `tangent` says. The warped tangent is symmetric (so is
/// the linear K): the step's products with it read its upper triangle only, half the memory
/// traffic of the full matrix (chapter 7's results).
///
/// The tangent is handed out, not copied: *K points at a matrix the system keeps (its
/// assembler's), valid until the next call of internal_force or elastic_energy. A step of 10k
/// tets would otherwise copy some 0.5 M entries and their indices once more every step.
using InternalForce = std::function<void(const Eigen::VectorXd& u, CorotationalTangent tangent, Eigen::VectorXd& f_int,
                                         const Eigen::SparseMatrix<double>** K)>;

/// M a + C v + f_int(u) = f(t) + r(t) on all DOFs, r the reactions, non-zero on the prescribed DOFs only.
struct NonlinearDynamicSystem {
  Eigen::SparseMatrix<double> M;                    ///< mass, all DOFs, symmetric; M_ff positive definite (kg)
  double rayleigh_alpha = 0.0;                      ///< C = alpha M + beta K_R, 1/s
  double rayleigh_beta = 0.0;                       ///< s; K_R the warped tangent at the start of each step
  DofMap dofs;                                      ///< which DOFs are prescribed (its values are not read: `motion` gives them)
  std::function<Eigen::VectorXd(double)> load;      ///< f(t) on all DOFs (N)
  std::function<PrescribedMotion(double)> motion;   ///< the prescribed DOFs' u, v, a at t
  InternalForce internal_force;                     ///< f_int and its tangent
  std::function<double(const Eigen::VectorXd&)> elastic_energy; ///< W(u) with f_int = dW/du (J)
  /// The basis the steps' iterative solver preconditions in (LinearSolver::set_preconditioner_basis),
  /// on the free DOFs; empty: the free DOFs themselves. A cut body's is
  /// cut_body_preconditioner_basis (part_basis.hpp).
  PreconditionerBasis solver_basis;
};

/// How a step treats f_int.
enum class RotationUpdate {
  /// Mueller and Gross (2004): the rotations of the step's start, f_int(u) ~
  /// f_int(u_n) + K_R (u - u_n) with the warped K_R, so the step is one linear solve. Exact
  /// for a linear body; for the corotated one it lags the rotations by a step.
  frozen,
  /// Newton's method on the step's equations with the consistent tangent, until the relative
  /// residual |r_f| / max(|r_f^0|, |f_f|, |(M a_n)_f|) is at most the tolerance. An iteration
  /// whose matrix the solver finds not positive definite (the consistent tangent of a squeezed
  /// element that little else holds) solves with the frozen step's matrix instead, whose warped
  /// tangent is positive semi-definite; the next iteration tries the consistent one again.
  newton,
  /// The frozen step, checked at its end: f_int and the warped K_R are assembled at u_{n+1} (an
  /// assembly the next step's start needs anyway), and where the step's relative residual with
  /// them exceeds the tolerance (its rotations lagged: a piece turned a good part of a radian in
  /// the step), the step solves again with the rotations frozen at its latest iterate, until the
  /// residual is within the tolerance. A quasi-Newton iteration on Newton's equations with the
  /// warped tangent, positive semi-definite where the consistent one need not be; while it
  /// iterates, the damping C = alpha M + beta K_R takes its K_R at the iterate too, and a
  /// correction that makes the residual grow is taken back by half. Chapter 7's default: its
  /// blade carves chips that turn faster than the frozen step follows, whose energy the lag feeds.
  checked,
};

/// The update a scene's `time.corotation` names: "frozen", "checked" or "newton"; empty (the
/// scene names none): the chapter's own default.
/// @throws std::invalid_argument for any other name (the scene reader refuses those first)
RotationUpdate rotation_update_named(const std::string& name, RotationUpdate chapter_default);
/// The scene's name of an update: "frozen", "checked" or "newton".
const char* rotation_update_name(RotationUpdate update);

struct NonlinearNewmarkSettings {
  NewmarkParameters newmark;                   ///< beta, gamma (default: average acceleration)
  RotationUpdate update = RotationUpdate::frozen;
  double tolerance = 1e-8;                     ///< newton, checked: relative residual of each step
  int max_iterations = 30;                     ///< newton, checked: iterations per step before giving up
  SolverSettings solver;
};

/// What one step did.
struct NonlinearStepReport {
  StepEnergy energy;              ///< external work (loads and reactions), damping, numerical (the rest of the balance)
  int iterations = 0;             ///< linear solves
  double relative_residual = 0.0; ///< newton, checked: the last one; frozen: 0 (not measured)
  bool converged = true;          ///< newton, checked: whether it met the tolerance
  int warped_fallbacks = 0;       ///< newton: iterations that solved with the frozen step's matrix instead
  int solver_iterations = 0;      ///< iterations of the linear solver summed over the step's solves (1 per direct solve)
  /// Processor time (std::clock: not inflated by other programs on a shared machine) spent
  /// building the solves' matrices A_ff, and factorising and solving: the benchmark's phases.
  double matrix_seconds = 0.0;
  double solve_seconds = 0.0;
  /// open_step's report: `energy.numerical` still lacks the end state's kinetic and strain
  /// energies, which close_step subtracts.
  bool awaiting_end_energies = false;
};

/// Newmark in acceleration form (as newmark.hpp) on all DOFs: the free ones predicted and
/// corrected by Newmark's updates, the prescribed ones set to the motion at t_{n+1}. The
/// matrix of each solve is M_ff + gamma dt C_ff + beta dt^2 K_ff (K the step's tangent), its
/// pattern analysed once (and again around a Newton iteration that falls back). With
/// C = alpha M + beta K_R that matrix is c_M M_ff + c_K K_ff, which the step writes straight
/// into a pattern found once (StepMatrix below): no sparse sums or products per step, only one
/// pass over the stored values.
///
/// Damping is Rayleigh's on the current rotated stiffness, C = alpha M + beta K_R(u_n) (as SOFA
/// and Vega do; the papers do not say), rebuilt every step and held through the step's Newton
/// iterations, so that beta damps the rate of strain and not a rigid rotation (a checked step
/// that iterates takes K_R at its iterate, see RotationUpdate::checked).
///
/// The energy account (StepEnergy): external work = trapezoidal work of the loads on all DOFs
/// plus that of the reactions r = M a + C v + f_int - f on the prescribed ones,
/// Delta u_c . (r_n + r_{n+1}) / 2; damping = Delta u . C v_bar; numerical = the rest, so that
/// kinetic + W(u) + dissipated - external work stays at its start value by construction. For a
/// linear body, still clamps and the average acceleration rule the rest is round-off (the
/// closed form of newmark.hpp is zero); a frozen corotated step or a moving clamp (whose
/// motion need not obey Newmark's updates) leave a small rest, which the account shows.
class NonlinearNewmarkIntegrator {
public:
  /// @param system kept by reference
  /// @param dt the time step (s), positive
  NonlinearNewmarkIntegrator(const NonlinearDynamicSystem& system, double dt, NonlinearNewmarkSettings settings);

  /// The state at t0 from u0 and v0 (full; the prescribed entries are taken from the motion)
  /// with the acceleration that satisfies the equations there.
  DynamicState initial_state(const Eigen::VectorXd& u0, const Eigen::VectorXd& v0, double t0);
  /// The energy account at the start of a run: kinetic 1/2 v^T M v, elastic W(u).
  EnergyAccount start_account(const DynamicState& state) const;
  /// Advances `state` to t + dt: open_step, then close_step on this integrator.
  NonlinearStepReport step(DynamicState& state);
  /// step() with its energy balance left open at the end state's energies. For a run whose
  /// model changes between steps (chapter 7: the blade cuts the body as this step leaves it,
  /// before the next step), which closes the step with the integrator of the new model: its
  /// kinetic energy and W at the carried-over state. The new model assembles there for the next
  /// step's start anyway, so the step's energies need no assembly of the old one at u_{n+1} (a
  /// checked step has made one for its check, which the new model's replaces). Where the new model
  /// holds the same field (cut_state_transfer.hpp) the energies are the old ones to round-off;
  /// where it does not (a fit near a crack front) their change shows in the step's numerical rest.
  NonlinearStepReport open_step(DynamicState& state);
  /// Completes open_step's energy balance with the kinetic energy 1/2 v^T M v and W(u) of `end`,
  /// the state the step ended in, as this integrator's system measures them.
  /// @throws std::logic_error if the report is not open_step's, or was closed already
  void close_step(NonlinearStepReport& report, const DynamicState& end) const;
  /// Books a step in the account: the state's energies, the step's works.
  /// @throws std::logic_error if the report is still open (open_step without close_step)
  void add_step(EnergyAccount& account, const DynamicState& state, const NonlinearStepReport& report) const;
  /// Numeric factorisations (or preconditioner set-ups) of the run so far (LinearSolver::factorisations).
  int factorisations() const { return solver_->factorisations(); }

private:
  Eigen::SparseMatrix<double> free_block(const Eigen::SparseMatrix<double>& A) const { return P_ * A * Pt_; }
  // A_ff = c_M M_ff + c_K K_ff in A_ff_, on the pattern of the free block of M + K, found at
  // the first call and again whenever K's pattern changes (a new cut): for each stored entry of
  // A_ff, where its M and its K value sit in their matrices' value arrays (-1: not stored).
  const Eigen::SparseMatrix<double>& step_matrix(double c_M, double c_K, const Eigen::SparseMatrix<double>& K);
  // C v = alpha M v + beta K_R v, without forming C.
  Eigen::VectorXd damping_force(const Eigen::SparseMatrix<double>& K_R, const Eigen::VectorXd& v) const;
  // The full vector: `free` on the free DOFs, `prescribed`'s entries on the others.
  Eigen::VectorXd combine(const Eigen::VectorXd& free, const Eigen::VectorXd& prescribed) const;
  // x: the initial guess of an iterative solver if it has rhs's size, else zero; the solution.
  void solve(const Eigen::SparseMatrix<double>& A_ff, const Eigen::VectorXd& rhs, Eigen::VectorXd& x);
  // W(u), remembered for the last u asked about: a step needs W at its start, which the step
  // before computed at its end, and the account asks again (a corotated W costs an assembly).
  double elastic_energy(const Eigen::VectorXd& u) const;

  const NonlinearDynamicSystem& system_;
  double dt_;
  NonlinearNewmarkSettings settings_;
  Eigen::SparseMatrix<double> P_, Pt_; // picks the free DOFs: A_ff = P A P^T
  Eigen::VectorXd prescribed_mask_;     // 1 on the prescribed DOFs, 0 on the free ones (all DOFs)
  double load_time_ = 0.0;              // the last load asked for, at load_time_ (empty: none yet)
  Eigen::VectorXd load_value_;
  std::unique_ptr<LinearSolver> solver_;
  bool analysed_ = false;
  Eigen::SparseMatrix<double> A_ff_;                 // the step's matrix, pattern fixed
  std::vector<Eigen::Index> from_M_, from_K_;        // per stored entry of A_ff_: index into M's, K's values or -1
  Eigen::Index pattern_K_nonzeros_ = -1;             // K.nonZeros() when the pattern was found
  Eigen::VectorXd last_change_; // a_f(t_n) - a_f(t_n-1): the first solve's guess for the next step's change
  mutable Eigen::VectorXd energy_u_;
  mutable double energy_value_ = 0.0;
};

} // namespace kerf
