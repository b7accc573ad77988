// The nonlinear Newmark step (nonlinear_newmark.hpp) on a linear body with still clamps is the
// dynamics area's linear Newmark: the same states to round-off, both rotation updates, and an
// energy account whose rest (the "numerical" part) is round-off, as newmark.hpp's closed form
// says for the average acceleration rule, with Rayleigh damping on.
#include "chapter_06/clamped_body.hpp"
#include "dynamics/cut_body.hpp"
#include "kerf/dynamics/newmark.hpp"
#include "kerf/dynamics/nonlinear_newmark.hpp"
#include "kerf/dynamics/rayleigh_damping.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/scene/scene_prescribed_motion.hpp"
#include "kerf/xfem/cut_xfem_mass.hpp"

#include <doctest/doctest.h>
#include <stdexcept>

namespace {

const kerf::LinearMaterial material{3000.0, 0.3, 1000.0};

} // namespace

TEST_CASE("on a linear cut body with still clamps the nonlinear Newmark step is the linear one, and its account balances") {
  const cut_body::CutBody body(kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {2, 2, 3}),
                               {cut_body::plane_surface({0.1, 0, 1}, 0.62, {0.5, 0.5, 0.5}, 0.7)}, material);
  REQUIRE(body.enrichment.num_enrichments() > 0);
  const std::vector<int> clamped = clamped_body::nodes_at_z0(body.mesh);
  const kerf::DofMap dofs = kerf::make_cut_xfem_dof_map(body.model, {{clamped, {0, 0, 0}}});
  const Eigen::SparseMatrix<double> M = kerf::assemble_cut_xfem_mass(body.model, material.density, cut_body::subtets);
  const Eigen::SparseMatrix<double> K = body.stiffness();
  const Eigen::VectorXd f = body.model.gravity_load(material.density, {9.81, 0, -3});
  const double alpha = 0.5, beta = 2e-3, dt = 0.02;

  kerf::LinearDynamicSystem linear{M, kerf::rayleigh_damping(M, K, alpha, beta), K, dofs, [f](double) { return f; }};
  kerf::NewmarkIntegrator reference(linear, dt);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(f.size());
  kerf::DynamicState expected = kerf::consistent_initial_state(reference.reduced(), zero, zero, 0.0, {});

  kerf::NonlinearDynamicSystem system;
  system.M = M;
  system.rayleigh_alpha = alpha;
  system.rayleigh_beta = beta;
  system.dofs = dofs;
  system.load = [f](double) { return f; };
  system.motion = [zero](double) { return kerf::PrescribedMotion{zero, zero, zero}; };
  system.internal_force = clamped_body::linear_force(K);
  system.elastic_energy = [&K](const Eigen::VectorXd& u) { return 0.5 * u.dot(K * u); };

  for (const kerf::RotationUpdate update : {kerf::RotationUpdate::frozen, kerf::RotationUpdate::checked, kerf::RotationUpdate::newton}) {
    CAPTURE(update == kerf::RotationUpdate::frozen ? "frozen" : update == kerf::RotationUpdate::checked ? "checked" : "newton");
    kerf::NonlinearNewmarkSettings settings;
    settings.update = update;
    settings.tolerance = 1e-10;
    kerf::NonlinearNewmarkIntegrator integrator(system, dt, settings);
    kerf::DynamicState state = integrator.initial_state(zero, zero, 0.0);
    kerf::DynamicState linear_state = expected;
    kerf::EnergyAccount account = integrator.start_account(state);
    double largest = 0.0, numerical = 0.0;
    for (int n = 0; n < 30; ++n) {
      const kerf::NonlinearStepReport step = integrator.step(state);
      integrator.add_step(account, state, step);
      reference.step(linear_state);
      largest = std::max(largest, account.kinetic + account.elastic);
      numerical = std::max(numerical, std::abs(account.numerical));
      CHECK(step.iterations == 1); // a linear body: one solve, frozen or Newton
      CHECK(step.converged);
    }
    // Two implementations of the same recurrence with different round-off (the nonlinear one
    // solves for increments): 1e-10 of the motion, against ~1e-13 of it expected.
    CHECK((state.u - linear_state.u).norm() <= 1e-10 * linear_state.u.norm());
    CHECK((state.v - linear_state.v).norm() <= 1e-10 * linear_state.v.norm());
    // Average acceleration: the closed-form numerical dissipation is zero (newmark.hpp), so the
    // rest of the balance is the round-off of 30 steps' energies (~1e-13 of them): 1e-10.
    CHECK(numerical <= 1e-10 * largest);
    CHECK(account.damping > 1e-3 * largest); // Rayleigh damping did dissipate something
  }
}

TEST_CASE("with a clamp moved along the smooth ramp, the energy account's rest shrinks like dt^2") {
  // The clamp's motion is exact, not Newmark's updates of its own acceleration, so the account's
  // rest (numerical) is not zero: the trapezoidal work of the reactions against the motion's
  // true displacement leaves an O(dt^3) error per step, O(dt^2) over the ramp [derived]. If the
  // reactions' work were missing or wrong, the rest would be of the size of the work itself and
  // would not shrink with dt. Linear forces, no damping, average acceleration: nothing else
  // leaves a rest (the first test case).
  const cut_body::CutBody body(kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {2, 2, 3}),
                               {cut_body::plane_surface({0.1, 0, 1}, 0.62, {0.5, 0.5, 0.5}, 0.7)}, material);
  const std::vector<int> clamped = clamped_body::nodes_at_z0(body.mesh);
  const kerf::DofMap dofs = kerf::make_cut_xfem_dof_map(body.model, {{clamped, {0, 0, 0}}});
  const Eigen::SparseMatrix<double> K = body.stiffness();
  const Eigen::Index size = K.rows();
  const double T = 0.5, push = 0.1; // the clamp moves 0.1 m along x over 0.5 s
  kerf::NonlinearDynamicSystem system;
  system.M = kerf::assemble_cut_xfem_mass(body.model, material.density, cut_body::subtets);
  system.dofs = dofs;
  system.load = [size](double) { return Eigen::VectorXd::Zero(size); };
  system.motion = [&](double t) {
    const kerf::SmoothRamp ramp = kerf::smooth_ramp(t / T);
    kerf::PrescribedMotion m{Eigen::VectorXd::Zero(size), Eigen::VectorXd::Zero(size), Eigen::VectorXd::Zero(size)};
    for (const int i : clamped) {
      m.u[3 * i] = push * ramp.s;
      m.v[3 * i] = push * ramp.ds / T;
      m.a[3 * i] = push * ramp.dds / (T * T);
    }
    return m;
  };
  system.internal_force = clamped_body::linear_force(K);
  system.elastic_energy = [&K](const Eigen::VectorXd& u) { return 0.5 * u.dot(K * u); };
  std::vector<double> rest, work;
  for (const int steps : {25, 50, 100}) {
    kerf::NonlinearNewmarkIntegrator integrator(system, T / steps, {});
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(size);
    kerf::DynamicState state = integrator.initial_state(zero, zero, 0.0);
    kerf::EnergyAccount account = integrator.start_account(state);
    for (int n = 0; n < steps; ++n) integrator.add_step(account, state, integrator.step(state));
    rest.push_back(std::abs(account.numerical));
    work.push_back(account.external_work);
    MESSAGE(steps << " steps: work " << account.external_work << " J, rest " << account.numerical << " J");
  }
  CHECK(work.back() > 0.0);
  // Halving dt divides the rest by about 4 (at least 3, for the asymptotic range's slack), and
  // the rest is a small part of the work.
  CHECK(rest[0] / rest[1] >= 3.0);
  CHECK(rest[1] / rest[2] >= 3.0);
  CHECK(rest[2] <= 1e-2 * work.back());
}

// The cut box of the first test case under gravity, with Rayleigh damping and still clamps at
// z = 0, linear: the system the last two test cases step.
struct DampedCutBody {
  cut_body::CutBody body{kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {2, 2, 3}),
                         {cut_body::plane_surface({0.1, 0, 1}, 0.62, {0.5, 0.5, 0.5}, 0.7)},
                         material};
  Eigen::SparseMatrix<double> K = body.stiffness();
  kerf::NonlinearDynamicSystem system;
  DampedCutBody() {
    const std::vector<int> clamped = clamped_body::nodes_at_z0(body.mesh);
    system.M = kerf::assemble_cut_xfem_mass(body.model, material.density, cut_body::subtets);
    system.rayleigh_alpha = 0.5;
    system.rayleigh_beta = 2e-3;
    system.dofs = kerf::make_cut_xfem_dof_map(body.model, {{clamped, {0, 0, 0}}});
    const Eigen::VectorXd f = body.model.gravity_load(material.density, {9.81, 0, -3});
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(f.size());
    system.load = [f](double) { return f; };
    system.motion = [zero](double) { return kerf::PrescribedMotion{zero, zero, zero}; };
    system.internal_force = clamped_body::linear_force(K);
    system.elastic_energy = [this](const Eigen::VectorXd& u) { return 0.5 * u.dot(K * u); };
  }
  DampedCutBody(const DampedCutBody&) = delete; // the system's functions read this K
  DampedCutBody& operator=(const DampedCutBody&) = delete;
};

TEST_CASE("a step opened and closed by hand balances its account; an open step cannot be booked or closed twice") {
  // Chapter 7 closes each step with the energies of the model the next step starts on (open_step,
  // then close_step). Closed by the same integrator, the account of a linear body under the
  // average acceleration rule balances to round-off (newmark.hpp's closed form, as in the first
  // test case); a report booked before it is closed, or closed twice, is refused.
  const DampedCutBody damped;
  const kerf::NonlinearDynamicSystem& system = damped.system;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(system.M.rows());

  kerf::NonlinearNewmarkIntegrator integrator(system, 0.02, {});
  kerf::DynamicState state = integrator.initial_state(zero, zero, 0.0);
  kerf::EnergyAccount account = integrator.start_account(state);
  double largest = 0.0;
  for (int n = 0; n < 30; ++n) {
    kerf::NonlinearStepReport report = integrator.open_step(state);
    CHECK(report.awaiting_end_energies);
    CHECK_THROWS_AS(integrator.add_step(account, state, report), std::logic_error);
    integrator.close_step(report, state);
    CHECK_FALSE(report.awaiting_end_energies);
    CHECK_THROWS_AS(integrator.close_step(report, state), std::logic_error);
    integrator.add_step(account, state, report);
    largest = std::max(largest, account.kinetic + account.elastic);
  }
  CHECK(largest > 0.0);
  CHECK(account.damping > 1e-3 * largest);
  // The rest of the balance is round-off (~1e-13 of the energies), as in the first test case;
  // without the end's energies it would be of the size of the energies themselves.
  CHECK(std::abs(account.numerical) <= 1e-10 * largest);
}

TEST_CASE("the step does not depend on the order in which the DofMap numbers its free DOFs") {
  // make_dof_map numbers the free DOFs in the order of the DOFs, so the step matrix's merged
  // columns (nonlinear_newmark.cpp) come out sorted; a DofMap numbered another way needs each
  // column sorted. Both must give the same steps: here the free DOFs numbered backwards, against
  // make_dof_map's, on the linear cut body with damping.
  const DampedCutBody damped;
  const kerf::NonlinearDynamicSystem& system = damped.system;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(system.M.rows());
  kerf::NonlinearDynamicSystem backwards = system;
  for (int& i : backwards.dofs.free_index)
    if (i >= 0) i = system.dofs.num_free - 1 - i;

  kerf::NonlinearNewmarkIntegrator in_order(system, 0.02, {}), reversed(backwards, 0.02, {});
  kerf::DynamicState state = in_order.initial_state(zero, zero, 0.0), state_reversed = reversed.initial_state(zero, zero, 0.0);
  for (int n = 0; n < 10; ++n) {
    in_order.step(state);
    reversed.step(state_reversed);
  }
  REQUIRE(state.u.norm() > 0.0);
  // The same equations solved by a direct solver on a permuted matrix: round-off apart.
  CHECK((state_reversed.u - state.u).norm() <= 1e-10 * state.u.norm());
  CHECK((state_reversed.a - state.a).norm() <= 1e-10 * state.a.norm());
}

TEST_CASE("a free DOF without mass: the start's acceleration is refused, naming the mass matrix") {
  // Two nodes' worth of DOFs, one free DOF with no mass: M_ff is singular, and the start's
  // a = M_ff^-1 (f - f_int)_f does not exist. The message must say so, not speak of stiffness.
  const Eigen::Index size = 6;
  Eigen::SparseMatrix<double> M(size, size), K(size, size);
  for (Eigen::Index i = 0; i < size; ++i) {
    M.insert(i, i) = i == 4 ? 0.0 : 1.0;
    K.insert(i, i) = 10.0;
  }
  M.makeCompressed();
  K.makeCompressed();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(size);
  kerf::NonlinearDynamicSystem system;
  system.M = M;
  system.dofs = kerf::make_dof_map(2, {});
  system.load = [zero](double) { return zero; };
  system.motion = [zero](double) { return kerf::PrescribedMotion{zero, zero, zero}; };
  system.internal_force = clamped_body::linear_force(K);
  system.elastic_energy = [&K](const Eigen::VectorXd& u) { return 0.5 * u.dot(K * u); };
  for (const char* solver : {"ldlt", "cg-jacobi"}) {
    CAPTURE(solver);
    kerf::NonlinearNewmarkSettings settings;
    settings.solver.type = solver;
    kerf::NonlinearNewmarkIntegrator integrator(system, 0.01, settings);
    CHECK_THROWS_WITH_AS(integrator.initial_state(zero, zero, 0.0),
                         doctest::Contains("the mass matrix M_ff on 6 free DOFs is not positive definite"), kerf::NotPositiveDefinite);
  }
}

TEST_CASE("a scene's corotation names its rotation update; none named is the chapter's default") {
  for (const kerf::RotationUpdate update : {kerf::RotationUpdate::frozen, kerf::RotationUpdate::checked, kerf::RotationUpdate::newton}) {
    CHECK(kerf::rotation_update_named(kerf::rotation_update_name(update), kerf::RotationUpdate::frozen) == update);
    CHECK(kerf::rotation_update_named("", update) == update);
  }
  CHECK_THROWS_AS(kerf::rotation_update_named("lagged", kerf::RotationUpdate::frozen), std::invalid_argument);
}
