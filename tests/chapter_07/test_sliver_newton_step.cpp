// Newton's step where a cut leaves a sliver (nonlinear_newmark.hpp, RotationUpdate::newton). The
// phantom node of a piece of 8 % of its tet is held by that piece alone and carries a sliver of
// its mass; squeezed, the consistent tangent's twists are negative and make the step's matrix
// indefinite, as in chapter 7's demo, whose Newton run with CHOLMOD stopped there at step 158.
// The iteration then solves with the frozen step's matrix and the step still converges to its
// tolerance; where even that matrix is not positive definite, the error says which matrix, which
// solver, and what can make it so.
#include "chapter_06/clamped_body.hpp"
#include "dynamics/cut_body.hpp"
#include "kerf/dynamics/lumped_mass.hpp"
#include "kerf/dynamics/nonlinear_newmark.hpp"
#include "kerf/fem/tet_shape_functions.hpp"
#include "kerf/solve/linear_solver.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <memory>
#include <string>
#include <vector>

namespace {

// The demo's tissue, step and damping (examples/07_liver_cut.json).
const kerf::LinearMaterial tissue{4000.0, 0.45, 1060.0};
constexpr double dt = 0.01, rayleigh_alpha = 2.0, rayleigh_beta = 0.01;

// The smallest eigenvalue of the 3 x 3 block of node d in M + gamma dt C + beta dt^2 K (the
// step's matrix where only node d is free), with C = alpha M + beta_R K_R(u), average acceleration.
double step_matrix_smallest(const Eigen::SparseMatrix<double>& M, const Eigen::SparseMatrix<double>& K_R,
                            const Eigen::SparseMatrix<double>& K, int d) {
  const Eigen::Matrix3d block = (1.0 + 0.5 * dt * rayleigh_alpha) * Eigen::Matrix3d(M.block(3 * d, 3 * d, 3, 3)) +
                                0.5 * dt * rayleigh_beta * Eigen::Matrix3d(K_R.block(3 * d, 3 * d, 3, 3)) +
                                0.25 * dt * dt * Eigen::Matrix3d(K.block(3 * d, 3 * d, 3, 3));
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(block).eigenvalues()[0];
}

} // namespace

TEST_CASE("a squeezed sliver's phantom node: Newton falls back to the frozen step's matrix once and still converges") {
  // A tet of the demo's size (legs of 1 cm: 1.7e-7 m^3, the demo's tets 1.6e-7), cut at
  // z = 0.57 L: the piece at node 3 is 0.43^3 = 7.95 % of it (the demo's sliver: 8.0 %).
  const double L = 0.01;
  kerf::TetMesh mesh = cut_body::unit_tet();
  mesh.nodes *= L;
  const kerf::TriangleSurface plane = cut_body::plane_surface({0, 0, 1}, 0.57 * L, {0.2 * L, 0.2 * L, 0.57 * L}, 2 * L);
  const cut_body::CutBody body(mesh, {plane}, tissue);
  REQUIRE(body.model.num_integrated_pieces(0) == 2);
  const int sliver = body.model.phantom_node(0, 0, 3) == 3 ? 0 : 1;
  const double tet_volume = L * L * L / 6;
  REQUIRE(body.model.integrated_volume(0, sliver) == kerf_test::relative(0.43 * 0.43 * 0.43 * tet_volume, 1e-12));
  // Node 0's phantom on the sliver: only the sliver holds it. Every other DOF node is held still.
  const int phantom = body.model.phantom_node(0, sliver, 0);
  REQUIRE(phantom >= body.mesh.num_nodes());
  std::vector<int> held;
  for (int d = 0; d < body.model.num_dof_nodes(); ++d)
    if (d != phantom) held.push_back(d);

  const Eigen::Index size = 3 * body.model.num_dof_nodes();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(size);
  const kerf::DofMap all_free = kerf::make_dof_map(body.model.num_dof_nodes(), {});
  auto assembler = std::make_shared<kerf::SparseAssembler>(body.model.assembly_slots(), all_free);
  kerf::NonlinearDynamicSystem system;
  system.M = kerf::lump_cut_xfem_mass(body.model, tissue.density, kerf::LumpingScheme::bernstein, cut_body::subtets);
  system.rayleigh_alpha = rayleigh_alpha;
  system.rayleigh_beta = rayleigh_beta;
  system.dofs = kerf::make_dof_map(body.model.num_dof_nodes(), {{held, {0, 0, 0}}});
  system.motion = [zero](double) { return kerf::PrescribedMotion{zero, zero, zero}; };
  system.internal_force = cut_body::corotated_force(body.model, assembler);
  system.elastic_energy = [&](const Eigen::VectorXd& u) { return body.model.energy(u, true); };
  // Its Bernstein mass rho int L_0 over the sliver, a tet whose corners have L_0 = 0, 0, 0 and
  // 1 - 0.57: rho V_sliver 0.43 / 4, a tenth of the sliver's mass (1.5e-6 kg).
  CHECK(system.M.coeff(3 * phantom, 3 * phantom) ==
        kerf_test::relative(tissue.density * body.model.integrated_volume(0, sliver) * 0.43 / 4, 1e-12));

  // The phantom node pushed 0.6 L / 3 along (1, 1, 1), towards the face across from node 0
  // (det F = 1 - 0.6 = 0.4; the demo's sliver was at 0.37), and 0.1 L aside, so that its
  // rotation turns; held there by a force that balances the piece's, which lets go after t = 0.
  Eigen::VectorXd u0 = zero;
  u0.segment<3>(3 * phantom) = 0.2 * L * Eigen::Vector3d(1, 1, 1) + 0.1 * L * Eigen::Vector3d(1, -1, 0).normalized();
  Eigen::VectorXd f_hold;
  const Eigen::SparseMatrix<double>* K = nullptr;
  system.internal_force(u0, kerf::CorotationalTangent::warped, f_hold, &K);
  const Eigen::SparseMatrix<double> K_warped = *K; // a copy: the next call reassembles into the same matrix
  system.internal_force(u0, kerf::CorotationalTangent::consistent, f_hold, &K);
  const Eigen::SparseMatrix<double> K_consistent = *K;
  system.load = [f_hold](double t) {
    return t < 0.5 * dt ? f_hold : Eigen::VectorXd(Eigen::VectorXd::Zero(f_hold.size()));
  };
  // Node 0 is at the origin: the edge matrix is the other nodes' positions.
  const Eigen::Matrix3d edges = mesh.nodes.bottomRows(3).transpose();
  const Eigen::Matrix<double, 4, 3> G = kerf::tet4_shape_gradients() * edges.inverse();
  const auto det_F = [&](const Eigen::VectorXd& u) {
    return (Eigen::Matrix3d::Identity() + body.model.phantom_displacements(u, 0, sliver).transpose() * G).determinant();
  };
  REQUIRE(det_F(u0) == kerf_test::relative(0.4, 1e-12));
  // The first solve's matrix: the state at rest (a = 0, v = 0) is the predictor. With the
  // consistent tangent it is indefinite, with the warped one positive definite (measured
  // -1.5e-5 and +4.3e-5 kg, the mass alone 1.5e-6; the demo's at step 158: -7.9e-6 and +5.3e-8).
  CHECK(step_matrix_smallest(system.M, K_warped, K_consistent, phantom) < -1e-5);
  CHECK(step_matrix_smallest(system.M, K_warped, K_warped, phantom) > 1e-5);

  for (const std::string& solver : {std::string("cholmod"), std::string("ldlt")}) {
    CAPTURE(solver);
    kerf::NonlinearNewmarkSettings settings;
    settings.update = kerf::RotationUpdate::newton;
    settings.tolerance = 1e-8;
    settings.solver.type = solver;
    kerf::NonlinearNewmarkIntegrator integrator(system, dt, settings);
    kerf::DynamicState state = integrator.initial_state(u0, zero, 0.0);
    REQUIRE(state.a.norm() <= 1e-9 * f_hold.norm() / system.M.coeff(3 * phantom, 3 * phantom)); // held: at rest
    const kerf::DynamicState start = state;

    const kerf::NonlinearStepReport first = integrator.step(state);
    CHECK(first.warped_fallbacks == 1); // the first iteration only: then the consistent tangent again
    CHECK(first.converged);
    CHECK(first.iterations <= 6); // measured 5 (to 9.7e-10): one fallback, then the consistent tangent
    // The step's equations at its end, from the system's own functions: the residual
    // f - M a - C v - f_int on the free DOFs within the tolerance of the step's reference force,
    // |f_int(u_0)| (the first residual; the load and M a_0 are zero there).
    Eigen::VectorXd f_int;
    system.internal_force(state.u, kerf::CorotationalTangent::warped, f_int, nullptr);
    const Eigen::VectorXd C_v = rayleigh_alpha * (system.M * state.v) + rayleigh_beta * (K_warped * state.v);
    const Eigen::VectorXd residual = system.load(dt) - system.M * state.a - C_v - f_int;
    CHECK(residual.segment<3>(3 * phantom).norm() <= 1e-8 * f_hold.segment<3>(3 * phantom).norm());
    CHECK((state.u - start.u).segment<3>(3 * phantom).norm() > 0.1 * L); // it sprang back (measured 0.21 L)

    // Released, the sliver relaxes to its rest shape, Newton converging in every step.
    for (int n = 0; n < 9; ++n) {
      const kerf::NonlinearStepReport step = integrator.step(state);
      CHECK(step.converged);
    }
    CHECK(std::abs(det_F(state.u) - 1.0) < 0.01); // measured 0.99997
  }
}

TEST_CASE("a step whose matrix stays indefinite with the warped tangent says which matrix, which solver, and why") {
  // One free node, a sliver of mass and a stiffness that is negative whatever tangent is asked
  // for: both matrices are c_M m I - (gamma dt beta_R + beta dt^2) k I < 0.
  const Eigen::SparseMatrix<double> M = Eigen::MatrixXd(1e-6 * Eigen::MatrixXd::Identity(3, 3)).sparseView();
  const Eigen::SparseMatrix<double> K = Eigen::MatrixXd(-10.0 * Eigen::MatrixXd::Identity(3, 3)).sparseView();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(3), push = Eigen::Vector3d(1e-3, 0, 0);
  kerf::NonlinearDynamicSystem system;
  system.M = M;
  system.rayleigh_alpha = rayleigh_alpha;
  system.rayleigh_beta = rayleigh_beta;
  system.dofs = kerf::make_dof_map(1, {});
  system.load = [push](double) { return push; };
  system.motion = [zero](double) { return kerf::PrescribedMotion{zero, zero, zero}; };
  system.internal_force = clamped_body::linear_force(K);
  system.elastic_energy = [&K](const Eigen::VectorXd& u) { return 0.5 * u.dot(K * u); };
  for (const kerf::RotationUpdate update : {kerf::RotationUpdate::newton, kerf::RotationUpdate::frozen}) {
    const bool newton = update == kerf::RotationUpdate::newton;
    CAPTURE(newton);
    kerf::NonlinearNewmarkSettings settings;
    settings.update = update;
    settings.solver.type = "cholmod";
    kerf::NonlinearNewmarkIntegrator integrator(system, dt, settings);
    kerf::DynamicState state = integrator.initial_state(zero, zero, 0.0);
    std::string message;
    try {
      integrator.step(state);
    } catch (const kerf::NotPositiveDefinite& error) {
      message = error.what();
    }
    CAPTURE(message);
    CHECK(message.find('\n') == std::string::npos); // one line
    CHECK(message.find(newton ? "Newton iteration 1: the step's matrix" : "the frozen step's matrix") == 0);
    if (newton) CHECK(message.find("with the consistent tangent K and with the warped K_R") != std::string::npos);
    CHECK(message.find("on 3 free DOFs is not positive definite (solver cholmod)") != std::string::npos);
    CHECK(message.find("a free DOF has no mass or an element's stiffness is indefinite") != std::string::npos);
    CHECK(message.find("Dirichlet") == std::string::npos); // a mass holds every DOF of a step: not the static message
  }
}
