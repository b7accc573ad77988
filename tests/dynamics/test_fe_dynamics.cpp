// The integrators on finite-element bodies: a clamped Tet4 bar keeps its energy exactly under
// the average acceleration rule; every integrator's energy account balances to round-off with
// damping, a time-varying load and a prescribed displacement; the central difference is stable
// just below 2 / omega_max and grows by its closed-form factor just above, and refuses such a
// step; a free body falls as g t^2 / 2 exactly under Newmark, and as g dt^2 n (n + 1) / 2 under
// backward Euler; the freed part of a clamped cut block falls as g t^2 / 2 with the piece-wise
// lumped mass and does not with eqs. 81-82.
#include "dynamics/cut_body.hpp"
#include "kerf/dynamics/backward_euler.hpp"
#include "kerf/dynamics/central_difference.hpp"
#include "kerf/dynamics/critical_time_step.hpp"
#include "kerf/dynamics/energy_account.hpp"
#include "kerf/dynamics/lumped_mass.hpp"
#include "kerf/dynamics/newmark.hpp"
#include "kerf/dynamics/rayleigh_damping.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/xfem/cut_xfem_mass.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace {

const kerf::LinearMaterial material{1000.0, 0.3, 1100.0};
const double rho = material.density;

std::vector<int> nodes_where(const kerf::TetMesh& mesh, const std::function<bool(const Eigen::Vector3d&)>& keep) {
  std::vector<int> nodes;
  for (Eigen::Index i = 0; i < mesh.num_nodes(); ++i)
    if (keep(mesh.nodes.row(i).transpose())) nodes.push_back(static_cast<int>(i));
  return nodes;
}

// A Tet4 bar [0,1] x [0,0.1] x [0,0.1], 8 x 1 x 1 cells, uncut, clamped at x = 0.
struct Bar {
  cut_body::CutBody body{kerf::make_box_mesh({0, 0, 0}, {1, 0.1, 0.1}, {8, 1, 1}), {}, material};
  std::vector<int> clamped = nodes_where(body.mesh, [](const Eigen::Vector3d& x) { return x.x() == 0.0; });

  kerf::LinearDynamicSystem system(bool lumped, const Eigen::Vector3d& clamp_displacement = Eigen::Vector3d::Zero()) const {
    kerf::LinearDynamicSystem s;
    s.M = lumped ? kerf::lump_cut_xfem_mass(body.model, rho, kerf::LumpingScheme::virtual_tet, cut_body::subtets)
                 : kerf::assemble_cut_xfem_mass(body.model, rho, cut_body::subtets);
    s.K = body.stiffness();
    s.C = Eigen::SparseMatrix<double>(s.M.rows(), s.M.cols());
    s.dofs = kerf::make_dof_map(body.mesh.num_nodes(), {{clamped, clamp_displacement}});
    s.load = [n = s.M.rows()](double) { return Eigen::VectorXd::Zero(n).eval(); };
    return s;
  }
  // A smooth initial bend: u_z = 0.01 x^2.
  Eigen::VectorXd bend() const {
    Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * body.mesh.num_nodes());
    for (Eigen::Index i = 0; i < body.mesh.num_nodes(); ++i) u[3 * i + 2] = 0.01 * std::pow(body.mesh.nodes(i, 0), 2);
    return u;
  }
};

// Runs `steps` steps and returns the largest |balance - balance at the start| and the largest energy seen.
template <class Integrator>
std::pair<double, double> balance_drift(Integrator& integrator, const kerf::LinearDynamicSystem& system, kerf::DynamicState state,
                                        int steps, kerf::EnergyAccount* final_account = nullptr) {
  kerf::EnergyAccount account = kerf::start_energy_account(system, state);
  const double start = account.balance();
  double drift = 0.0, largest = start;
  for (int n = 0; n < steps; ++n) {
    kerf::add_step(account, system, state, integrator.step(state));
    drift = std::max(drift, std::abs(account.balance() - start));
    largest = std::max({largest, account.kinetic + account.elastic, std::abs(account.external_work)});
  }
  if (final_account) *final_account = account;
  return {drift, largest};
}

} // namespace

TEST_CASE("the average acceleration rule keeps a vibrating Tet4 bar's energy to round-off") {
  const Bar bar;
  const kerf::LinearDynamicSystem system = bar.system(false);
  const double dt = 0.01;
  kerf::NewmarkIntegrator newmark(system, dt);
  const kerf::DynamicState state = kerf::consistent_initial_state(newmark.reduced(), bar.bend(), Eigen::VectorXd::Zero(system.M.rows()), 0.0, {});
  kerf::EnergyAccount account;
  const auto [drift, largest] = balance_drift(newmark, system, state, 500, &account);
  // The energy moves between kinetic and elastic (checked: the kinetic part is not negligible),
  // and the sum stays put; the solves' round-off, ~1e-15 relative a step, is all that moves it.
  CHECK(account.kinetic > 1e-3 * largest);
  CHECK(drift <= 1e-12 * largest);
  CHECK(account.numerical == 0.0);
  MESSAGE("bar, average acceleration: energy drift " << drift / largest << " of the energy over 500 steps");
}

TEST_CASE("with Rayleigh damping, a load in time and a prescribed displacement, every integrator's energy account balances") {
  const Bar bar;
  kerf::LinearDynamicSystem system = bar.system(true, Eigen::Vector3d(0.0, 0.0, 0.005));
  system.C = kerf::rayleigh_damping(system.M, system.K, 0.5, 1e-3);
  const Eigen::VectorXd tip = [&] {
    Eigen::VectorXd f = Eigen::VectorXd::Zero(system.M.rows());
    for (const int i : nodes_where(bar.body.mesh, [](const Eigen::Vector3d& x) { return x.x() == 1.0; })) f[3 * i + 2] = 1e-3;
    return f;
  }();
  system.load = [tip](double t) { return (std::sin(3.0 * t) * tip).eval(); };
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(system.M.rows());
  const kerf::ReducedDynamicSystem reduced(system);
  const kerf::DynamicState start = kerf::consistent_initial_state(reduced, bar.bend(), zero, 0.0, {});
  const kerf::LargestEigenvalue top = kerf::largest_eigenvalue(reduced.M_ff(), reduced.K_ff());
  const double dt = 0.5 * kerf::central_difference_critical_step(top.lambda);

  kerf::NewmarkIntegrator average(system, dt);
  kerf::NewmarkIntegrator dissipative(system, dt, {0.3025, 0.6}); // gamma = 0.6, beta = (gamma + 1/2)^2 / 4
  kerf::BackwardEulerIntegrator euler(system, dt);
  kerf::CentralDifferenceIntegrator central(system, dt);
  kerf::EnergyAccount a1, a2, a3, a4;
  const auto [d1, e1] = balance_drift(average, system, start, 400, &a1);
  const auto [d2, e2] = balance_drift(dissipative, system, start, 400, &a2);
  const auto [d3, e3] = balance_drift(euler, system, start, 400, &a3);
  const auto [d4, e4] = balance_drift(central, system, start, 400, &a4);
  // Each term is computed on its own (StepEnergy's closed forms); the balance drifts by the
  // round-off of 400 steps of sums over ~100 DOFs.
  CHECK(d1 <= 1e-11 * e1);
  CHECK(d2 <= 1e-11 * e2);
  CHECK(d3 <= 1e-11 * e3);
  CHECK(d4 <= 1e-11 * e4);
  // ... and no term is idle: the load worked, the damping and (but for the trapezoidal rule)
  // the integrators dissipated.
  for (const kerf::EnergyAccount* a : {&a1, &a2, &a3, &a4}) {
    CHECK(std::abs(a->external_work) > 1e-3 * e1);
    CHECK(a->damping > 1e-3 * e1);
  }
  CHECK(a1.numerical == 0.0);
  CHECK(a2.numerical > 1e-4 * e2);
  CHECK(a3.numerical > 1e-4 * e3);
  MESSAGE("energy balance drift / largest energy: average " << d1 / e1 << ", gamma 0.6 " << d2 / e2 << ", backward Euler "
                                                            << d3 / e3 << ", central difference " << d4 / e4);
}

TEST_CASE("the central difference is stable just below 2 / omega_max, grows by its closed-form factor above, and refuses such a step") {
  const Bar bar;
  const kerf::LinearDynamicSystem system = bar.system(true);
  const kerf::ReducedDynamicSystem reduced(system);
  // omega_max^2 by a dense generalised eigensolver, the reference for the power iteration.
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> dense(Eigen::MatrixXd(reduced.K_ff()), Eigen::MatrixXd(reduced.M_ff()));
  const double lambda = dense.eigenvalues().maxCoeff();
  const kerf::LargestEigenvalue top = kerf::largest_eigenvalue(reduced.M_ff(), reduced.K_ff());
  CHECK(top.converged);
  CHECK(top.lambda <= lambda * (1.0 + 1e-14)); // a Rayleigh quotient never exceeds it
  CHECK(top.lambda == kerf_test::relative(lambda, 1e-9));
  const double critical = 2.0 / std::sqrt(lambda);
  MESSAGE("omega_max^2 = " << lambda << " /s^2, power iteration " << top.lambda << " in " << top.iterations << " iterations, dt_crit = " << critical << " s");

  std::mt19937 random(3);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::VectorXd u0(system.M.rows());
  for (Eigen::Index i = 0; i < u0.size(); ++i) u0[i] = 1e-3 * uniform(random);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(u0.size());
  const auto M_norm = [&](const Eigen::VectorXd& u) { return std::sqrt(u.dot(system.M * u)); };

  // Below: from rest every mode runs as u_0 cos(n theta) exactly (u_1 = u_0 (1 - omega^2 dt^2 / 2)),
  // so the M-norm of u never exceeds its start.
  {
    kerf::CentralDifferenceIntegrator central(system, 0.99 * critical);
    CHECK(central.critical_step() == kerf_test::relative(critical, 1e-9));
    kerf::DynamicState state = kerf::consistent_initial_state(reduced, u0, zero, 0.0, {});
    const double start = M_norm(state.u);
    double largest = 0.0;
    for (int n = 0; n < 3000; ++n) {
      central.step(state);
      largest = std::max(largest, M_norm(state.u));
    }
    CHECK(largest <= start * (1.0 + 1e-9));
    MESSAGE("dt = 0.99 dt_crit: largest |u|_M / |u_0|_M over 3000 steps = " << largest / start);
  }
  // Above: refused, and when forced the top mode grows by |z| = (b + sqrt(b^2 - 4)) / 2,
  // b = omega^2 dt^2 - 2, every step.
  const double dt = 1.01 * critical;
  CHECK_THROWS_AS(kerf::CentralDifferenceIntegrator(system, dt), std::invalid_argument);
  kerf::CentralDifferenceIntegrator central(system, dt, true);
  kerf::DynamicState state = kerf::consistent_initial_state(reduced, u0, zero, 0.0, {});
  for (int n = 0; n < 300; ++n) central.step(state);
  const double before = M_norm(state.u);
  for (int n = 0; n < 10; ++n) central.step(state);
  const double growth = std::pow(M_norm(state.u) / before, 0.1);
  const double b = lambda * dt * dt - 2.0;
  CHECK(growth == kerf_test::relative((b + std::sqrt(b * b - 4.0)) / 2.0, 1e-9));
  MESSAGE("dt = 1.01 dt_crit: growth per step " << growth << ", closed form " << (b + std::sqrt(b * b - 4.0)) / 2.0);
}

TEST_CASE("a free body falls as g t^2 / 2 exactly with Newmark, and as g dt^2 n (n + 1) / 2 with backward Euler") {
  const cut_body::CutBody body(kerf::make_box_mesh({0, 0, 0}, {1, 0.5, 0.5}, {2, 1, 1}), {}, material);
  const Eigen::Vector3d g(0.0, 0.0, -9.81);
  kerf::LinearDynamicSystem system;
  system.M = kerf::assemble_cut_xfem_mass(body.model, rho, cut_body::subtets);
  system.K = body.stiffness();
  system.C = Eigen::SparseMatrix<double>(system.M.rows(), system.M.cols());
  system.dofs = kerf::make_dof_map(body.mesh.num_nodes(), {});
  const Eigen::VectorXd f = body.model.gravity_load(rho, g);
  system.load = [f](double) { return f; };
  const double dt = 0.01;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(f.size());
  const Eigen::VectorXd ones = body.piecewise_field([](const Eigen::Vector3d&) { return 1; },
                                                    [&](const Eigen::Vector3d&, int) { return g; }); // g at every node
  kerf::NewmarkIntegrator newmark(system, dt);
  kerf::BackwardEulerIntegrator euler(system, dt);
  kerf::DynamicState a = kerf::consistent_initial_state(newmark.reduced(), zero, zero, 0.0, {});
  kerf::DynamicState b = a;
  double worst_newmark = 0.0, worst_euler = 0.0;
  for (int n = 1; n <= 50; ++n) {
    newmark.step(a);
    euler.step(b);
    const double t = n * dt;
    worst_newmark = std::max(worst_newmark, (a.u - 0.5 * t * t * ones).lpNorm<Eigen::Infinity>() / (0.5 * t * t * g.norm()));
    const double euler_drop = 0.5 * dt * dt * n * (n + 1);
    worst_euler = std::max(worst_euler, (b.u - euler_drop * ones).lpNorm<Eigen::Infinity>() / (euler_drop * g.norm()));
  }
  CHECK(worst_newmark <= 1e-12);
  CHECK(worst_euler <= 1e-12);
  MESSAGE("free fall: Newmark's worst relative error against g t^2 / 2 " << worst_newmark << ", backward Euler's against g dt^2 n(n+1)/2 " << worst_euler);
}

TEST_CASE("the freed part of a clamped cut block falls as g t^2 / 2 with the virtual-tet mass, and not with eqs. 81-82") {
  // The unit cube of 2 x 2 x 2 cells cut clean through at z = 0.62 + 0.1 x (in the upper layer
  // of cells, so that the clamp holds no node of the part above), clamped at z = 0: the part
  // above the cut is held by nothing and falls; the part below swings on the clamp.
  const cut_body::CutBody body(kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {2, 2, 2}),
                               {cut_body::plane_surface({-0.1, 0, 1}, 0.62, {0.5, 0.5, 0.5}, 3.0)}, material);
  const auto side = [](const Eigen::Vector3d& x) { return x.z() - 0.1 * x.x() < 0.62 ? -1 : 1; };
  const Eigen::Vector3d g(0.0, 0.0, -9.81);
  const double dt = 0.02;
  const int steps = 20;
  for (const kerf::LumpingScheme scheme : {kerf::LumpingScheme::virtual_tet, kerf::LumpingScheme::schoch_eq_81_82}) {
    CAPTURE(std::string(scheme == kerf::LumpingScheme::virtual_tet ? "virtual_tet" : "schoch_eq_81_82"));
    const kerf::DynamicState state = cut_body::newmark_from_rest(
        kerf::lump_cut_xfem_mass(body.model, rho, scheme, cut_body::subtets), body.stiffness(),
        kerf::make_cut_xfem_dof_map(body.model, {{nodes_where(body.mesh, [](const Eigen::Vector3d& x) { return x.z() == 0.0; }), {0, 0, 0}}}),
        kerf::lumped_gravity_load(body.model, rho, g, scheme, cut_body::subtets), dt, steps);
    const double drop = 0.5 * g.z() * state.t * state.t;
    // The phantom values u_i + a_k of the part above, node by node, against the free fall.
    double worst = 0.0;
    for (Eigen::Index t = 0; t < body.mesh.num_tets(); ++t)
      for (int p = 0; p < body.num_integrated_pieces(t); ++p) {
        if (side(body.piece_centroid(t, p)) < 0) continue;
        for (int a = 0; a < 4; ++a) {
          const int i = body.mesh.tets(t, a), k = body.model.phantom_node(t, p, a);
          Eigen::Vector3d value = state.u.segment<3>(3 * i);
          if (k != i) value += state.u.segment<3>(3 * k);
          worst = std::max(worst, (value - Eigen::Vector3d(0, 0, drop)).norm() / std::abs(drop));
        }
      }
    if (scheme == kerf::LumpingScheme::virtual_tet) CHECK(worst <= 1e-10);
    else CHECK(worst > 0.1);
    MESSAGE("freed part after " << steps << " steps: worst relative deviation from g t^2 / 2 = " << worst);
  }
}
