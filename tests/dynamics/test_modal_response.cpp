// The integrators on the clamped Tet10 beam of chapter 1 (0.03 x 0.06 x 0.2 m, E = 300 kPa,
// nu = 0.35, rho = 1070 kg/m^3, clamped at z = 0; coarse: 1 x 2 x 6 cells), seen through its
// first mode (dynamics/eigen_modes.hpp). With C = alpha M + beta K the modes decouple, and every
// scheme of this area is a linear map on each mode's (q, q'), so its discrete answer is known in
// closed form:
// - average acceleration Newmark is the trapezoidal rule on (q, q'), whose amplification
//   eigenvalues lambda = (1 + h mu / 2) / (1 - h mu / 2), mu = the mode's continuous eigenvalues,
//   have |lambda| = 1 undamped and the phase 2 atan(omega dt / 2) per step: the beam released
//   under suddenly applied gravity has q_1(t_n) = q_s (1 - cos(n theta)), theta = 2 atan(omega dt / 2),
//   so the period grows by T_num / T = omega dt / (2 atan(omega dt / 2)) (Hughes 2000, section 9.1);
// - with Rayleigh damping q_n = c_1 lambda_1^n + c_2 lambda_2^n, mu = -xi omega +- i omega sqrt(1 - xi^2);
// - backward Euler, lambda = 1 / (1 - h mu): an undamped mode loses the fraction
//   1 - 1 / (1 + omega^2 dt^2) of its energy every step.
#include "dynamics/cut_body.hpp"
#include "kerf/dynamics/backward_euler.hpp"
#include "kerf/dynamics/eigen_modes.hpp"
#include "kerf/dynamics/energy_account.hpp"
#include "kerf/dynamics/newmark.hpp"
#include "kerf/dynamics/rayleigh_damping.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"
#include "kerf/xfem/cut_xfem_mass.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

namespace {

const kerf::LinearMaterial beam_material{300e3, 0.35, 1070.0};
const Eigen::Vector3d gravity(9.81, 0.0, 0.0); // chapter 1's case 1

// The beam's system (C = 0, gravity from t = 0) and its lowest modes.
struct Beam {
  cut_body::CutBody body{kerf::tet10_from_tet4(kerf::make_box_mesh({0, 0, 0}, {0.03, 0.06, 0.2}, {1, 2, 6})), {}, beam_material};
  kerf::LinearDynamicSystem system;
  kerf::EigenModes modes;
  Beam() {
    system.M = kerf::assemble_cut_xfem_mass(body.model, beam_material.density, cut_body::subtets);
    system.K = body.stiffness();
    system.C = Eigen::SparseMatrix<double>(system.M.rows(), system.M.cols());
    std::vector<int> clamped;
    for (Eigen::Index v = 0; v < body.mesh.num_nodes(); ++v)
      if (body.mesh.nodes(v, 2) == 0.0) clamped.push_back(static_cast<int>(v));
    system.dofs = kerf::make_dof_map(body.mesh.num_nodes(), {{clamped, Eigen::Vector3d::Zero()}});
    const Eigen::VectorXd f = body.model.gravity_load(beam_material.density, gravity);
    system.load = [f](double) { return f; };
    const kerf::ReducedDynamicSystem reduced(system);
    // 1e-13 (near the round-off of a Ritz value): the Ritz vectors then carry about
    // sqrt(1e-13) = 3e-7 of the other modes.
    modes = kerf::lowest_eigenmodes(reduced.K_ff(), reduced.M_ff(), 2, 0.0, 1e-13);
  }
  double omega() const { return std::sqrt(modes.lambda[0]); }
  // q_1 = phi_1^T M u of a state (phi_1 M-orthonormal).
  double modal(const kerf::ReducedDynamicSystem& reduced, const Eigen::VectorXd& u) const {
    return modes.phi.col(0).dot(reduced.M_ff() * reduced.restrict_to_free(u));
  }
};

} // namespace

TEST_CASE("Newmark's average acceleration: the beam under sudden gravity follows q_s (1 - cos(n 2 atan(omega dt / 2))) in mode 1") {
  const Beam beam;
  REQUIRE(beam.modes.converged);
  const kerf::ReducedDynamicSystem reduced(beam.system);
  const double omega = beam.omega();
  const double q_static = beam.modes.phi.col(0).dot(reduced.free_load(0.0)) / beam.modes.lambda[0];
  for (const double omega_dt : {0.2, 1.0, 2.5}) {
    CAPTURE(omega_dt);
    const double dt = omega_dt / omega;
    const double theta = 2.0 * std::atan(omega_dt / 2.0);
    kerf::NewmarkIntegrator newmark(beam.system, dt);
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(beam.system.M.rows());
    kerf::DynamicState state = kerf::consistent_initial_state(reduced, zero, zero, 0.0, {});
    // Two numerical periods, at least 8 steps.
    const int steps = std::max(8, static_cast<int>(std::ceil(2.0 * 2.0 * std::numbers::pi / theta)));
    double worst = 0.0, worst_exact_phase = 0.0;
    for (int n = 1; n <= steps; ++n) {
      newmark.step(state);
      const double q = beam.modal(reduced, state.u);
      worst = std::max(worst, std::abs(q - q_static * (1.0 - std::cos(n * theta))));
      worst_exact_phase = std::max(worst_exact_phase, std::abs(q - q_static * (1.0 - std::cos(n * omega_dt))));
    }
    // The modal projection carries the Ritz vector's share of the other modes (at most 3e-7 by
    // the eigenvalue tolerance; measured 7e-13 to 4e-12 of q_s at the three steps): 1e-8 holds
    // any Ritz vector this accurate, and a wrong phase misses by 4e-2 or more (next check).
    CHECK(worst <= 1e-8 * std::abs(q_static));
    // And the test can tell: the exact phase n omega dt is far off (by 2 q_s sin of the drift).
    CHECK(worst_exact_phase > 1e-2 * std::abs(q_static));
  }
  // The period elongation this is, at omega dt = 1: 1 / (2 atan(1/2)) = 1.0783.
  CHECK(1.0 / (2.0 * std::atan(0.5)) == kerf_test::relative(1.078, 1e-3));
}

TEST_CASE("Newmark with Rayleigh damping: mode 1 decays as c1 lambda1^n + c2 lambda2^n, and the account's dissipation is the energy lost") {
  Beam beam;
  const double omega = beam.omega(), omega_2 = std::sqrt(beam.modes.lambda[1]);
  // xi = 0.05 at omega_1 and omega_2: alpha = 2 xi w1 w2 / (w1 + w2), beta = 2 xi / (w1 + w2).
  const double xi_target = 0.05, alpha = 2.0 * xi_target * omega * omega_2 / (omega + omega_2), beta = 2.0 * xi_target / (omega + omega_2);
  beam.system.C = kerf::rayleigh_damping(beam.system.M, beam.system.K, alpha, beta);
  beam.system.load = [n = beam.system.M.rows()](double) { return Eigen::VectorXd::Zero(n).eval(); };
  const kerf::ReducedDynamicSystem reduced(beam.system);
  const double xi = alpha / (2.0 * omega) + beta * omega / 2.0;
  CHECK(xi == kerf_test::relative(xi_target, 1e-12));
  const double dt = 0.5 / omega;
  // Free vibration from u0 = phi_1 (scaled to 1 mm at most), at rest.
  const Eigen::VectorXd phi = reduced.expand(beam.modes.phi.col(0), false);
  const double q0 = 1e-3 / phi.cwiseAbs().maxCoeff();
  kerf::NewmarkIntegrator newmark(beam.system, dt);
  kerf::DynamicState state = kerf::consistent_initial_state(reduced, q0 * phi, Eigen::VectorXd::Zero(phi.size()), 0.0, {});
  kerf::EnergyAccount account = kerf::start_energy_account(beam.system, state);
  const double start = account.balance();
  // mu_{1,2} = -xi omega +- i omega sqrt(1 - xi^2); lambda = (1 + dt mu / 2) / (1 - dt mu / 2);
  // (q, q') = c1 (1, mu1) + c2 (1, mu2) with q(0) = q0, q'(0) = 0.
  using complex = std::complex<double>;
  const complex mu1(-xi * omega, omega * std::sqrt(1.0 - xi * xi)), mu2 = std::conj(mu1);
  const complex lambda1 = (1.0 + dt * mu1 / 2.0) / (1.0 - dt * mu1 / 2.0), lambda2 = std::conj(lambda1);
  const complex c1 = q0 * mu2 / (mu2 - mu1), c2 = q0 - c1;
  double worst = 0.0, worst_balance = 0.0;
  for (int n = 1; n <= 60; ++n) {
    kerf::add_step(account, beam.system, state, newmark.step(state));
    const double q = beam.modal(reduced, state.u);
    worst = std::max(worst, std::abs(q - (c1 * std::pow(lambda1, n) + c2 * std::pow(lambda2, n)).real()));
    worst_balance = std::max(worst_balance, std::abs(account.balance() - start));
  }
  // Same modal projection argument as above (measured 8e-13): 1e-8 of the amplitude.
  CHECK(worst <= 1e-8 * q0);
  // The damping took what the motion lost (60 steps of omega dt = 0.5 at xi = 0.05 remove most of
  // it: exp(-2 xi omega t) = exp(-3) of the energy is left), and the account balances to round-off.
  CHECK(account.damping > 0.9 * start);
  CHECK(account.numerical == doctest::Approx(0.0).epsilon(1e-12).scale(start));
  // Round-off: 60 steps of sums of energies ~ start, each a few ulps (measured 2e-12): 1e-10 of it.
  CHECK(worst_balance <= 1e-10 * start);
}

TEST_CASE("backward Euler: mode 1 free vibration loses 1 - 1 / (1 + omega^2 dt^2) of its energy every step") {
  Beam beam;
  beam.system.load = [n = beam.system.M.rows()](double) { return Eigen::VectorXd::Zero(n).eval(); };
  const kerf::ReducedDynamicSystem reduced(beam.system);
  const double omega = beam.omega();
  for (const double omega_dt : {0.1, 0.5, 2.0}) {
    CAPTURE(omega_dt);
    const double dt = omega_dt / omega;
    const Eigen::VectorXd phi = reduced.expand(beam.modes.phi.col(0), false);
    kerf::BackwardEulerIntegrator euler(beam.system, dt);
    kerf::DynamicState state = kerf::consistent_initial_state(reduced, 1e-3 * phi, Eigen::VectorXd::Zero(phi.size()), 0.0, {});
    kerf::EnergyAccount account = kerf::start_energy_account(beam.system, state);
    const double start = account.kinetic + account.elastic;
    const int steps = 10;
    for (int n = 0; n < steps; ++n) kerf::add_step(account, beam.system, state, euler.step(state));
    const double expected = start * std::pow(1.0 + omega_dt * omega_dt, -steps);
    // The other modes' 3e-7 share of the vector carries 1e-13 of the energy: 1e-9 is loose.
    CHECK(account.kinetic + account.elastic == kerf_test::relative(expected, 1e-9));
    // The account books the loss as numerical dissipation, to round-off.
    CHECK(account.numerical == kerf_test::relative(start - expected, 1e-9));
  }
}

TEST_CASE("lowest_eigenmodes on spring chains: lambda_k = 4 sin^2(k pi / (2 (n + 1))) fixed-fixed, 4 sin^2(k pi / (2 n)) free") {
  // n unit masses joined by unit springs: K = tridiag(-1, 2, -1) with both ends held (fixed-fixed),
  // or with 1 in the two corners (free-free, a rigid mode at lambda = 0, which needs a shift
  // below 0); M = I. The closed forms are the discrete sine and cosine modes.
  const int n = 60, count = 5;
  std::vector<Eigen::Triplet<double>> fixed, free, identity;
  for (int i = 0; i < n; ++i) {
    fixed.emplace_back(i, i, 2.0);
    free.emplace_back(i, i, (i == 0 || i == n - 1) ? 1.0 : 2.0);
    identity.emplace_back(i, i, 1.0);
    if (i + 1 < n)
      for (auto* list : {&fixed, &free}) list->emplace_back(i, i + 1, -1.0), list->emplace_back(i + 1, i, -1.0);
  }
  Eigen::SparseMatrix<double> K_fixed(n, n), K_free(n, n), M(n, n);
  K_fixed.setFromTriplets(fixed.begin(), fixed.end());
  K_free.setFromTriplets(free.begin(), free.end());
  M.setFromTriplets(identity.begin(), identity.end());
  const kerf::EigenModes fixed_modes = kerf::lowest_eigenmodes(K_fixed, M, count);
  const kerf::EigenModes free_modes = kerf::lowest_eigenmodes(K_free, M, count, -0.01);
  REQUIRE(fixed_modes.converged);
  REQUIRE(free_modes.converged);
  for (int k = 0; k < count; ++k) {
    // Converged to 1e-12 relative; the closed form is evaluated to round-off.
    CHECK(fixed_modes.lambda[k] == kerf_test::relative(4.0 * std::pow(std::sin((k + 1) * std::numbers::pi / (2.0 * (n + 1))), 2), 1e-10));
    if (k == 0) CHECK(std::abs(free_modes.lambda[0]) < 1e-12);
    else CHECK(free_modes.lambda[k] == kerf_test::relative(4.0 * std::pow(std::sin(k * std::numbers::pi / (2.0 * n)), 2), 1e-10));
  }
  CHECK_THROWS_AS(kerf::lowest_eigenmodes(K_fixed, M, 0), std::invalid_argument);
  CHECK_THROWS_AS(kerf::lowest_eigenmodes(K_fixed, M, n + 1), std::invalid_argument);
  CHECK_THROWS_AS(kerf::lowest_eigenmodes(K_fixed, Eigen::SparseMatrix<double>(n - 1, n - 1), 1), std::invalid_argument);
}
