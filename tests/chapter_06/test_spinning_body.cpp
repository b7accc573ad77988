// A free body that turns a good part of a radian in every step: the frozen step (rotations of the
// step's start) against the checked one (nonlinear_newmark.hpp, RotationUpdate::checked).
//
// A free corotated cube spinning about an axis through its centre, no load, no damping: what it
// holds, kinetic plus elastic energy, is its start value for all time (the exact motion
// conserves it). The frozen step takes f_int(u) ~ f_int(u_n) + K_R(u_n) (u - u_n): a rotation
// by an angle theta in the step moves the body along (R(theta) - I) x, whose part
// (1 - cos theta) n x (n x x) is no rotation of K_R's and which K_R resists as if it were strain.
// That force does work the exact motion does not, a fraction of order theta^2 of the rotational
// energy in every step, and a spinning piece's energy drifts. The checked step assembles f_int at
// the step's end and solves again with the rotations of its iterate until its residual is within
// the tolerance: Newton's equations with the warped tangent, whose solution the average
// acceleration rule keeps near the start energy.
#include "dynamics/cut_body.hpp"
#include "kerf/dynamics/nonlinear_newmark.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/xfem/cut_xfem_mass.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <vector>

namespace {

struct SpinRun {
  double drift = 0.0;           // largest |E(t) - E(0)| / E(0) along the run
  double turned = 0.0;          // the angle the body turned (rad), from a corner's position
  int solves = 0;               // linear solves of the run
  bool converged = true;        // every checked step met its tolerance
};

// The cube [0, 0.2]^3 in 2 x 2 x 2 cells of six tets, spinning at omega about the vertical axis
// through its centre, stepped `steps` times by dt.
SpinRun spin(kerf::RotationUpdate update, double omega, double dt, int steps) {
  const kerf::LinearMaterial material{1.0e5, 0.3, 1000.0};
  const cut_body::CutBody body(kerf::make_box_mesh({0, 0, 0}, {0.2, 0.2, 0.2}, {2, 2, 2}), {}, material);
  const Eigen::Index size = 3 * body.model.num_dof_nodes();
  auto assembler = std::make_shared<kerf::SparseAssembler>(body.model.assembly_slots(), kerf::make_dof_map(body.model.num_dof_nodes(), {}));
  kerf::NonlinearDynamicSystem system;
  system.M = kerf::assemble_cut_xfem_mass(body.model, material.density, cut_body::subtets);
  system.dofs = kerf::make_dof_map(body.model.num_dof_nodes(), {});
  system.load = [size](double) { return Eigen::VectorXd::Zero(size); };
  system.motion = [size](double) {
    return kerf::PrescribedMotion{Eigen::VectorXd::Zero(size), Eigen::VectorXd::Zero(size), Eigen::VectorXd::Zero(size)};
  };
  system.internal_force = cut_body::corotated_force(body.model, assembler);
  system.elastic_energy = [&](const Eigen::VectorXd& u) { return body.model.energy(u, true); };

  // v = omega e_z x (X - c) at every node: a rigid spin (the model's DOF nodes are the mesh's).
  const Eigen::Vector3d centre(0.1, 0.1, 0.1);
  Eigen::VectorXd v0(size);
  for (Eigen::Index i = 0; i < body.mesh.num_nodes(); ++i) {
    const Eigen::Vector3d r = body.mesh.nodes.row(i).transpose() - centre;
    v0.segment<3>(3 * i) = omega * Eigen::Vector3d(-r.y(), r.x(), 0.0);
  }
  kerf::NonlinearNewmarkSettings settings;
  settings.update = update;
  settings.tolerance = 1e-8;
  kerf::NonlinearNewmarkIntegrator integrator(system, dt, settings);
  kerf::DynamicState state = integrator.initial_state(Eigen::VectorXd::Zero(size), v0, 0.0);
  kerf::EnergyAccount account = integrator.start_account(state);
  const double start = account.kinetic + account.elastic;
  SpinRun run;
  double angle = 0.0;
  Eigen::Vector2d corner_before(-0.1, -0.1); // node 0 at the origin, relative to the axis
  for (int n = 0; n < steps; ++n) {
    const kerf::NonlinearStepReport report = integrator.step(state);
    integrator.add_step(account, state, report);
    run.solves += report.iterations;
    run.converged = run.converged && report.converged;
    const double held = account.kinetic + account.elastic;
    if (!std::isfinite(held)) {
      run.drift = INFINITY;
      break;
    }
    run.drift = std::max(run.drift, std::abs(held - start) / start);
    const Eigen::Vector2d corner = Eigen::Vector2d(-0.1, -0.1) + state.u.head<2>();
    angle += std::atan2(corner_before.x() * corner.y() - corner_before.y() * corner.x(), corner_before.dot(corner));
    corner_before = corner;
  }
  run.turned = angle;
  return run;
}

} // namespace

TEST_CASE("a body spinning 0.3 rad a step: the frozen step's energy bursts, the checked step's drift shrinks like dt^2") {
  // omega = 10 rad/s for T = 1.8 s (18 rad, nearly three turns) in steps of 30, 15 and 7.5 ms:
  // 0.3, 0.15 and 0.075 rad a step. The centrifugal strain rho omega^2 L^2 / E is 4e-3: the body
  // hardly stretches, and what it holds is its kinetic energy 1/2 I omega^2 = 0.53 J, I = m L^2 / 6.
  const double omega = 10.0, T = 1.8;
  std::vector<double> drift, turned;
  for (const int steps : {60, 120, 240}) {
    CAPTURE(steps);
    const double dt = T / steps;
    const SpinRun frozen = spin(kerf::RotationUpdate::frozen, omega, dt, steps);
    const SpinRun checked = spin(kerf::RotationUpdate::checked, omega, dt, steps);
    const SpinRun newton = spin(kerf::RotationUpdate::newton, omega, dt, steps);
    MESSAGE(steps << " steps, largest energy drift: frozen " << frozen.drift << " (turned " << frozen.turned << " rad, "
                  << frozen.solves << " solves), checked " << checked.drift << " (turned " << checked.turned << " rad, "
                  << checked.solves << " solves), newton " << newton.drift << " (turned " << newton.turned << " rad, "
                  << newton.solves << " solves)");
    CHECK(checked.converged);
    CHECK(newton.converged);
    // Without damping the checked step and Newton's solve the same equations, one with the
    // warped tangent, the other with the consistent one: the same motion to their tolerance.
    CHECK(checked.turned == kerf_test::relative(newton.turned, 1e-6));
    CHECK(checked.drift == kerf_test::relative(newton.drift, 1e-3));
    drift.push_back(checked.drift);
    turned.push_back(checked.turned);
    if (steps == 60) CHECK(frozen.drift > 1e6); // measured 4e31: the lagged rotations feed the spin
  }
  // The average acceleration rule's energy error and phase error are O(dt^2): the drift and the
  // change of the angle turned fall by about 4 a halving.
  const double drift_rate = std::log2(drift[1] / drift[2]);
  const double angle_rate = std::log2(std::abs(turned[1] - turned[0]) / std::abs(turned[2] - turned[1]));
  MESSAGE("observed orders: energy drift " << std::log2(drift[0] / drift[1]) << ", " << drift_rate << "; angle " << angle_rate);
  // Measured 2.02, 1.88 (drift) and 1.87 (angle), still short of the asymptotic 2 at 0.15 rad a step;
  // 1.7 tells second order from the first order a lagged rotation would leave.
  CHECK(drift_rate > 1.7);
  CHECK(angle_rate > 1.7);
}
