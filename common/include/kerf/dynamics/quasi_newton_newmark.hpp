/// @file quasi_newton_newmark.hpp
/// @brief Chapter 8's time step: Newmark's step for the corotated body written as the minimum of
///        one energy, minimised by a few quasi-Newton iterations whose matrix is one scalar
///        Laplacian plus mass, factorised once and grown (not redone) when a cut adds unknowns.
#pragma once
#include "kerf/corotation/corotated_pieces.hpp"
#include "kerf/dynamics/energy_account.hpp"
#include "kerf/dynamics/linear_dynamic_system.hpp"
#include "kerf/dynamics/newmark.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/solve/growing_cholesky.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <deque>
#include <memory>
#include <vector>

namespace kerf {

struct QuasiNewtonNewmarkSettings {
  NewmarkParameters newmark;  ///< beta, gamma (default: the average acceleration rule)
  /// Iterations per step when `tolerance` is 0: a fixed cost, the real-time setting.
  int iterations = 4;
  /// > 0: iterate until |g_f| <= tolerance max(|g_f^0|, |f_f|) (g the energy's gradient on the
  /// free DOFs, f the load), at most max_iterations: the tight solve the chapter charts against.
  double tolerance = 0.0;
  int max_iterations = 1000;
  int history = 5; ///< L-BFGS's pairs (s, y) kept
  /// The pieces' rotations are iterated until a correction is below this (rad) when the step
  /// runs a fixed number of iterations (CorotatedPieces::step_terms); with a tolerance, to
  /// round-off.
  double turn_tolerance = 1e-2;
  /// Whether a step starts with the pairs the step before ended with (the Hessian changes
  /// little in a step) instead of A^{-1} alone; a change of the body forgets them.
  bool keep_history = true;
  /// kappa of the matrix's stiffness part, kappa L (Pa), as a multiple of mu: (8.6).
  double stiffness_in_mu = 0.0; ///< 0: 2 + lambda / mu, the stiffness of a pure dilatation
  /// With a fixed number of iterations: a step that would create more energy than this times
  /// the body's energy at its start (kinetic + elastic) plus the load's work in the step goes on,
  /// with exact rotations, to a relative gradient of 1e-6 or check_iterations more iterations;
  /// 0: never checked.
  double energy_tolerance = 1e-2;
  int check_iterations = 40;
};

/// What one step did.
struct QuasiNewtonStepReport {
  StepEnergy energy;          ///< the step's works (energy_account.hpp); numerical: the rest of the balance
  int iterations = 0;         ///< gradient evaluations after the first (one per iteration, more when the line search halves)
  double relative_gradient = 0.0; ///< |g_f| / max(|g_f^0|, |f_f|) at the step's end
  bool converged = true;      ///< with a tolerance: whether it was met
  bool checked = false;       ///< the energy check sent the step on
  /// Wall-clock seconds of the step's two kinds of work (the rest is vector work, the mass's
  /// products and the energy account): the passes over the pieces (forces, energies, rotations)
  /// and the solves with the factor of A.
  double pieces_seconds = 0.0;
  double solve_seconds = 0.0;
};

/// The body a step moves: its corotated energy, mass, held DOFs and load.
struct QuasiNewtonBody {
  const CorotatedPieces* pieces = nullptr; ///< kept by pointer: must outlive its use
  Eigen::SparseMatrix<double> M;            ///< mass on all DOFs, m_ij I_3 per node pair (kg)
  DofMap dofs;                              ///< each node held in all three components or none (held still)
  Eigen::VectorXd load;                     ///< f, constant in time (N): gravity
  Eigen::Index num_standard_nodes = 0;      ///< the mesh's nodes: DOF nodes from here on are enrichments
  double rayleigh_alpha = 0.0;              ///< C = alpha M + beta K_R(u_n) (1/s)
  double rayleigh_beta = 0.0;               ///< (s)
};

/// Newmark's step for M a + C v + f_int(u) = f (C = alpha M + beta K_R(u_n), as chapter 6's,
/// its rotations held through the step) is the stationary point of
///
///   E_n(u) = c_M/2 |u - u~|_M^2 + c_D/2 |u - u~|_{K_R(u_n)}^2 + W(u) - b . u,     (8.4)
///   u~ = u_n + dt v_n + dt^2 (1/2 - beta) a_n,   v~ = v_n + dt (1 - gamma) a_n,
///   c_M = 1/(beta dt^2) + alpha gamma/(beta dt),   c_D = beta_R gamma/(beta dt),
///   b = f - alpha M v~ - beta_R K_R(u_n) v~,
///
/// whose gradient is M a + C v + f_int - f with a = (u - u~)/(beta dt^2), v = v~ + gamma dt a.
/// Chapter 7 solves it by Newton's method or by frozen rotations; here L-BFGS minimises it with
/// the initial inverse Hessian A^{-1},
///
///   A = c_M M_s + (1 + c_D) kappa L,                                              (8.6)
///
/// M_s the mass's scalar part and L the scalar Laplacian (corotated_pieces.hpp), one n x n
/// matrix for x, y and z: A's rows of the mesh's nodes do not change when a cut adds
/// enrichments (its pieces' volumes sum to the tet's), so the factor only grows
/// (growing_cholesky.hpp). Converged, the step is chapter 7's Newton step; at a fixed number of
/// iterations it is not: on a cut bar of liver tissue swinging 18 cm under its weight, 3, 4, 5
/// and 10 iterations a step stay within 2.2 %, 0.43 %, 0.24 % and 0.022 % of the largest
/// displacement of chapter 7's tight Newton run, and 2 iterations a step miss by 65 %
/// (tests/chapter_08/test_quasi_newton_step.cpp); on chapter 7's cut liver at 10k tets, 4
/// iterations stay within 0.72 % (bench/bench_real_time.cpp).
class QuasiNewtonNewmark {
public:
  QuasiNewtonNewmark(double dt, const LinearMaterial& material, QuasiNewtonNewmarkSettings settings);

  /// The body to step (first call, or a cut changed it). The factor of A's standard block is
  /// kept if that block is unchanged; the enrichments' rows are factorised anew.
  /// @throws std::invalid_argument if a node is held in some components only, or the mass is
  ///         not the same in x, y and z
  void set_body(QuasiNewtonBody body);

  /// The state at t0 from u0 and v0 with the acceleration that satisfies the equations there.
  DynamicState initial_state(const Eigen::VectorXd& u0, const Eigen::VectorXd& v0, double t0);
  /// kinetic 1/2 v^T M v and W(u) of the state.
  EnergyAccount start_account(const DynamicState& state);
  /// One step of dt.
  QuasiNewtonStepReport step(DynamicState& state);
  /// Books the step: the end state's energies, the step's works.
  void add_step(EnergyAccount& account, const DynamicState& state, const QuasiNewtonStepReport& report);

  /// W(u), f_int(u) and the pieces' rotations, remembered for the last u.
  double elastic_energy(const Eigen::VectorXd& u);
  /// How often A's standard block was factorised (1 unless a cut changed it).
  int factorisations() const { return factorisations_; }
  /// The matrix A on the free DOF nodes, standard then enriched (for tests).
  Eigen::SparseMatrix<double> step_matrix() const;
  /// The free DOF nodes in A's order.
  const std::vector<int>& free_nodes() const { return free_nodes_; }
  /// Solves A X = B (rows: free_nodes()), in place.
  void solve_step_matrix(Eigen::MatrixXd& B) { factor_->solve(B); }
  /// The trailing (enrichment) columns the last set_body found unchanged (GrowingCholesky).
  Eigen::Index kept_enrichment_columns() const { return factor_->kept_columns(); }

private:
  // E_n(u) (8.4), up to a constant, and its gradient on all DOFs.
  double step_energy(const Eigen::VectorXd& u, Eigen::VectorXd& gradient, QuasiNewtonStepReport& report);
  // The step's works and the rest of its energy balance were it to end at x, the last point
  // evaluated (kinetic_n, W_n: the energies at its start).
  StepEnergy step_balance(const DynamicState& state, double kinetic_n, double W_n, const Eigen::VectorXd& x,
                          const Eigen::VectorXd& v_tilde, QuasiNewtonStepReport& report);
  // -H g, L-BFGS's direction (or A^{-1}'s where the pairs give no descent).
  Eigen::MatrixXd descent_direction(const Eigen::MatrixXd& g, QuasiNewtonStepReport& report);
  // A X = B in place (the factor's solve), timed into the report.
  void solve(Eigen::MatrixXd& B, QuasiNewtonStepReport& report);
  void remember(const Eigen::VectorXd& u, double W); // W at u; last_rotations_ hold u's
  Eigen::MatrixXd gather(const Eigen::VectorXd& full) const; // free DOF nodes x 3
  void scatter_add(const Eigen::MatrixXd& free, Eigen::VectorXd& full) const;

  double dt_;
  LinearMaterial material_;
  QuasiNewtonNewmarkSettings settings_;
  QuasiNewtonBody body_;
  std::vector<int> free_nodes_;
  Eigen::VectorXd free_mask_;      // 1 on the free DOFs, 0 on the held ones
  std::vector<int> free_position_;           // each DOF node's row in A, -1 if held
  double c_L_ = 0.0;                         // (1 + c_D) kappa: A = c_M M_s + c_L L
  std::vector<int> free_standard_nodes_;     // the mesh's free nodes when A's factor was made ...
  Eigen::SparseMatrix<double> standard_mass_; // ... and their block of M_s
  std::unique_ptr<GrowingCholesky> factor_;
  int factorisations_ = 0;
  double c_M_ = 0.0, c_D_ = 0.0;
  // The step's constants: u~, b = f - alpha M v~, the pieces' gradient sums of the damping's
  // reference u^ (step()), the rotations of u_n.
  Eigen::VectorXd u_tilde_, b_;
  std::vector<Eigen::Matrix3d> damping_reference_sums_;
  std::vector<Eigen::Matrix3d> rotations_n_;
  std::deque<std::pair<Eigen::MatrixXd, Eigen::MatrixXd>> pairs_; // L-BFGS's (s, y), newest last
  // The last evaluation of the body.
  Eigen::VectorXd last_u_;
  std::vector<Eigen::Matrix3d> last_rotations_;
  double last_W_ = 0.0;
  bool last_valid_ = false;
};

} // namespace kerf
