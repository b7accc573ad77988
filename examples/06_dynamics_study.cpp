/* Kerf, chapter 6 study: the uncut clamped beam in time. Its natural frequencies against
   CalculiX, Newmark's period elongation against dt, and where the energy goes under average
   acceleration (with and without Rayleigh damping) and under backward Euler.

   Build:   cmake --preset release && cmake --build --preset release --target 06_dynamics_study

   Sample runs:
     06_dynamics_study --quick --out output/dynamics_study_quick
     06_dynamics_study --out figures/06_newmark
     06_dynamics_study --only period --out figures/06_newmark       (one part: modes, period, energy)

   Description: chapter 1's beam, 0.03 x 0.06 x 0.2 m, Tet10 on 3 x 6 x 20 cells (--quick: 1 x 2
   x 6), E = 300 kPa, nu = 0.35, rho = 1070 kg/m^3, clamped at z = 0, consistent mass; gravity
   9.81 m/s^2 along +x applied suddenly at t = 0 on the beam at rest:

        z = 0.2 +-----+
                |     |   <- gravity +x, from t = 0
                |     |
                |     |      the beam swings about its static deflection,
                |     |      mostly in its first mode (bending about y)
          z = 0 +=====+   clamped

   Three parts, files in --out:
     modes    modes_frequencies.csv: the six lowest eigenvalues omega^2 and frequencies by
              shift-invert subspace iteration (dynamics/eigen_modes.hpp) and by CalculiX
              *FREQUENCY on the same mesh (NaN without KERF_CCX);
     period   period_elongation.csv: for omega_1 dt from 0.05 to 3, the period of the first mode
              under average acceleration Newmark, measured from the run (the modal coordinate
              q_1 = phi_1^T M u, by a least-squares fit of q_{n+1} + q_{n-1} = 2 cos(theta) q_n
              about the static value; the tip's x displacement, by its upward crossings of the
              static value), against the closed form T_num / T = omega dt / (2 atan(omega dt / 2));
              period_history.csv: q_1 / q_s and the tip displacement over time at two steps;
     energy   energy_time.csv: kinetic, elastic, external work, damping and numerical dissipation,
              and the balance kinetic + elastic + dissipated - external work (energy_account.hpp)
              over 10 first-mode periods at dt = T_1 / 40, for undamped Newmark, Newmark with
              Rayleigh damping (xi = 0.05 at modes 1 and 2), and backward Euler;
              energy_dissipation.csv: the energy mode 1 keeps per step in free vibration under
              backward Euler against omega dt, measured and the closed form 1 / (1 + omega^2 dt^2).
   --quick runs every part on the coarse mesh with few steps; it is a test.

   Read chapter 6 first. */

#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/dynamics/backward_euler.hpp"
#include "kerf/dynamics/eigen_modes.hpp"
#include "kerf/dynamics/energy_account.hpp"
#include "kerf/dynamics/linear_dynamic_system.hpp"
#include "kerf/dynamics/newmark.hpp"
#include "kerf/dynamics/rayleigh_damping.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/io/calculix_deck.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"
#include "kerf/quadrature/gauss_piece_rules.hpp"
#include "kerf/xfem/cut_xfem_mass.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"
#include "kerf/xfem/surface_enrichment.hpp"
#include "measure.hpp" // bench/measure.hpp: the command line shared with the benchmarks

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

namespace dynamics_study {

const double not_a_number = std::numeric_limits<double>::quiet_NaN();
const kerf::LinearMaterial material{300e3, 0.35, 1070.0};
const Eigen::Vector3d gravity(9.81, 0.0, 0.0);
const double pi = std::numbers::pi;

kerf::PieceQuadratureRule subtets(const Eigen::Matrix<double, 4, 3>&, const kerf::TetPieces& pieces, int piece, int degree) {
  return kerf::subtet_rule(pieces, piece, degree);
}

/// The uncut beam as a linear dynamic system, with everything its model refers to.
struct Beam {
  kerf::TetMesh mesh;
  kerf::CutSurfaces cuts{{}};
  kerf::MeshPieces pieces;
  kerf::SurfaceEnrichment enrichment;
  kerf::CutXfemModel model;
  kerf::LinearDynamicSystem system;
  std::vector<int> clamped;
  int tip_dof = -1; // u_x of the node at (0.03, 0.06, 0.2)

  explicit Beam(const Eigen::Vector3i& cells)
      : mesh(kerf::tet10_from_tet4(kerf::make_box_mesh({0, 0, 0}, {0.03, 0.06, 0.2}, cells))),
        pieces(kerf::cut_mesh_into_pieces(mesh, cuts)), enrichment(kerf::make_surface_enrichment(mesh, pieces)),
        model(mesh, material, pieces, enrichment, subtets) {
    for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) {
      if (mesh.nodes(v, 2) == 0.0) clamped.push_back(static_cast<int>(v));
      if ((mesh.nodes.row(v) - Eigen::RowVector3d(0.03, 0.06, 0.2)).norm() < 1e-12) tip_dof = 3 * static_cast<int>(v);
    }
    system.M = kerf::assemble_cut_xfem_mass(model, material.density, subtets);
    const kerf::DofMap all_free = kerf::make_dof_map(model.num_dof_nodes(), {});
    kerf::SparseAssembler assembler(model.assembly_slots(), all_free);
    Eigen::VectorXd unused = Eigen::VectorXd::Zero(all_free.num_free);
    model.assemble_linear_stiffness(assembler, unused);
    system.K = assembler.matrix();
    system.C = Eigen::SparseMatrix<double>(system.M.rows(), system.M.cols());
    system.dofs = kerf::make_dof_map(mesh.num_nodes(), {{clamped, Eigen::Vector3d::Zero()}});
    set_gravity(true);
  }
  void set_gravity(bool on) {
    const Eigen::VectorXd f = on ? model.gravity_load(material.density, gravity) : Eigen::VectorXd::Zero(system.M.rows()).eval();
    system.load = [f](double) { return f; };
  }
  Eigen::VectorXd zero() const { return Eigen::VectorXd::Zero(system.M.rows()); }
};

/// The upward crossings of a sampled signal through `level`, by linear interpolation (times).
std::vector<double> upward_crossings(const std::vector<double>& t, const std::vector<double>& y, double level) {
  std::vector<double> crossings;
  for (std::size_t n = 1; n < y.size(); ++n)
    if (y[n - 1] < level && y[n] >= level) crossings.push_back(t[n - 1] + (level - y[n - 1]) / (y[n] - y[n - 1]) * (t[n] - t[n - 1]));
  return crossings;
}

/// The mean spacing of the crossings (NaN with fewer than two).
double mean_period(const std::vector<double>& crossings) {
  if (crossings.size() < 2) return not_a_number;
  return (crossings.back() - crossings.front()) / double(crossings.size() - 1);
}

/// theta of y_{n+1} + y_{n-1} = 2 cos(theta) y_n by least squares: exact for one sampled
/// sinusoid at any number of samples per period.
double phase_per_step(const std::vector<double>& y) {
  double num = 0.0, den = 0.0;
  for (std::size_t n = 1; n + 1 < y.size(); ++n) num += y[n] * (y[n + 1] + y[n - 1]), den += 2.0 * y[n] * y[n];
  return std::acos(std::clamp(num / den, -1.0, 1.0));
}

void run_modes(const Beam& beam, bool quick, const std::filesystem::path& out) {
  const kerf::ReducedDynamicSystem reduced(beam.system);
  const int count = 6;
  const kerf::EigenModes modes = kerf::lowest_eigenmodes(reduced.K_ff(), reduced.M_ff(), count);
  std::vector<double> ccx_lambda(count, not_a_number);
  const std::string ccx = KERF_CCX;
  if (!ccx.empty()) {
    const std::filesystem::path folder = out / "modes_calculix";
    std::filesystem::create_directories(folder);
    kerf::CalculixJob job;
    job.material = material;
    job.dirichlet = {{beam.clamped, Eigen::Vector3d::Zero()}};
    job.procedure = kerf::CalculixProcedure::frequency;
    job.frequencies = count;
    kerf::write_calculix_deck(folder / "beam_frequency.inp", beam.mesh, job);
    kerf::run_calculix(ccx, folder, "beam_frequency");
    ccx_lambda = kerf::read_calculix_eigenvalues(folder / "beam_frequency.dat");
    std::filesystem::remove_all(folder);
  }
  std::ofstream csv(out / "modes_frequencies.csv");
  csv.precision(10);
  csv << "mode,lambda_kerf,f_kerf_hz,lambda_calculix,f_calculix_hz,relative_difference\n";
  std::printf("modes (%s mesh, %d subspace iterations%s):\n", quick ? "1x2x6" : "3x6x20", modes.iterations,
              modes.converged ? "" : ", NOT converged");
  for (int k = 0; k < count; ++k) {
    const double rel = (ccx_lambda[k] - modes.lambda[k]) / ccx_lambda[k];
    csv << k + 1 << ',' << modes.lambda[k] << ',' << std::sqrt(modes.lambda[k]) / (2 * pi) << ',' << ccx_lambda[k] << ','
        << std::sqrt(ccx_lambda[k]) / (2 * pi) << ',' << rel << '\n';
    std::printf("  mode %d: f = %.6f Hz (Kerf), %.6f Hz (CalculiX), omega^2 relative difference %.3e\n", k + 1,
                std::sqrt(modes.lambda[k]) / (2 * pi), std::sqrt(ccx_lambda[k]) / (2 * pi), rel);
  }
}

void run_period(const Beam& beam, bool quick, const std::filesystem::path& out) {
  const kerf::ReducedDynamicSystem reduced(beam.system);
  const kerf::EigenModes modes = kerf::lowest_eigenmodes(reduced.K_ff(), reduced.M_ff(), 1, 0.0, 1e-13);
  const double omega = std::sqrt(modes.lambda[0]), period = 2 * pi / omega;
  const Eigen::VectorXd phi = modes.phi.col(0);
  const double q_static = phi.dot(reduced.free_load(0.0)) / modes.lambda[0];
  const Eigen::VectorXd u_static = reduced.expand(kerf::solve_once(reduced.K_ff(), reduced.free_load(0.0), {}), true);
  const double tip_static = u_static[beam.tip_dof];
  std::printf("period: omega_1 = %.6f rad/s, T_1 = %.6f s; static tip u_x = %.6e m, q_s = %.6e\n", omega, period, tip_static, q_static);

  std::ofstream csv(out / "period_elongation.csv"), history(out / "period_history.csv");
  csv.precision(10);
  history.precision(10);
  csv << "omega_dt,dt,steps,T_exact,T_modal,T_tip,ratio_modal,ratio_tip,ratio_closed_form\n";
  history << "omega_dt,t,q_over_qs,closed_form_q_over_qs,tip_ux,tip_static\n";
  const std::vector<double> omega_dts = quick ? std::vector<double>{0.2, 1.0, 3.0}
                                              : std::vector<double>{0.05, 0.1, 0.2, 0.3, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0};
  for (const double omega_dt : omega_dts) {
    const double dt = omega_dt / omega;
    const double closed = omega_dt / (2.0 * std::atan(omega_dt / 2.0));
    const int steps = static_cast<int>(std::ceil((quick ? 2.0 : 5.0) * period * closed / dt)) + 2;
    kerf::NewmarkIntegrator newmark(beam.system, dt);
    kerf::DynamicState state = kerf::consistent_initial_state(reduced, beam.zero(), beam.zero(), 0.0, {});
    std::vector<double> t{0.0}, q{phi.dot(reduced.M_ff() * reduced.restrict_to_free(state.u)) - q_static}, tip{state.u[beam.tip_dof]};
    for (int n = 1; n <= steps; ++n) {
      newmark.step(state);
      t.push_back(state.t);
      q.push_back(phi.dot(reduced.M_ff() * reduced.restrict_to_free(state.u)) - q_static);
      tip.push_back(state.u[beam.tip_dof]);
    }
    const double T_modal = 2 * pi * dt / phase_per_step(q);
    const double T_tip = mean_period(upward_crossings(t, tip, tip_static));
    csv << omega_dt << ',' << dt << ',' << steps << ',' << period << ',' << T_modal << ',' << T_tip << ',' << T_modal / period << ','
        << T_tip / period << ',' << closed << '\n';
    std::printf("  omega dt = %5.2f (%5d steps): T_num / T = %.8f (mode 1), %.6f (tip crossings), closed form %.8f\n", omega_dt, steps,
                T_modal / period, T_tip / period, closed);
    if (omega_dt == 0.2 || omega_dt == 1.0)
      for (std::size_t n = 0; n < t.size(); ++n)
        history << omega_dt << ',' << t[n] << ',' << 1.0 + q[n] / q_static << ','
                << 1.0 - std::cos(double(n) * 2.0 * std::atan(omega_dt / 2.0)) << ',' << tip[n] << ',' << tip_static << '\n';
  }
}

void run_energy(Beam& beam, bool quick, const std::filesystem::path& out) {
  const kerf::EigenModes modes = [&] {
    const kerf::ReducedDynamicSystem reduced(beam.system);
    return kerf::lowest_eigenmodes(reduced.K_ff(), reduced.M_ff(), 2, 0.0, 1e-13);
  }();
  const double omega_1 = std::sqrt(modes.lambda[0]), omega_2 = std::sqrt(modes.lambda[1]);
  const double period = 2 * pi / omega_1, dt = period / 40.0;
  const int steps = quick ? 80 : 400;
  const double xi = 0.05, alpha = 2 * xi * omega_1 * omega_2 / (omega_1 + omega_2), beta = 2 * xi / (omega_1 + omega_2);
  std::printf("energy: dt = T_1 / 40 = %.6e s, %d steps; Rayleigh alpha = %.6e 1/s, beta = %.6e s (xi = %.2f at modes 1, 2)\n", dt, steps,
              alpha, beta, xi);

  std::ofstream csv(out / "energy_time.csv");
  csv.precision(12);
  csv << "run,step,t,kinetic,elastic,external_work,damping,numerical,balance_drift\n";
  const Eigen::SparseMatrix<double> no_damping(beam.system.M.rows(), beam.system.M.cols());
  for (const std::string run : {"newmark", "newmark_rayleigh", "backward_euler"}) {
    beam.system.C = run == "newmark_rayleigh" ? kerf::rayleigh_damping(beam.system.M, beam.system.K, alpha, beta) : no_damping;
    const kerf::ReducedDynamicSystem reduced(beam.system);
    kerf::DynamicState state = kerf::consistent_initial_state(reduced, beam.zero(), beam.zero(), 0.0, {});
    kerf::EnergyAccount account = kerf::start_energy_account(beam.system, state);
    const double start = account.balance();
    double worst = 0.0, largest = 0.0;
    const auto write = [&](int n) {
      csv << run << ',' << n << ',' << state.t << ',' << account.kinetic << ',' << account.elastic << ',' << account.external_work << ','
          << account.damping << ',' << account.numerical << ',' << account.balance() - start << '\n';
      worst = std::max(worst, std::abs(account.balance() - start));
      largest = std::max(largest, std::abs(account.external_work));
    };
    write(0);
    if (run == "backward_euler") {
      kerf::BackwardEulerIntegrator euler(beam.system, dt);
      for (int n = 1; n <= steps; ++n) kerf::add_step(account, beam.system, state, euler.step(state)), write(n);
    } else {
      kerf::NewmarkIntegrator newmark(beam.system, dt);
      for (int n = 1; n <= steps; ++n) kerf::add_step(account, beam.system, state, newmark.step(state)), write(n);
    }
    std::printf("  %-16s: at the end kinetic %.4e, elastic %.4e, external work %.4e, damping %.4e, numerical %.4e J; "
                "largest |balance drift| %.2e J = %.2e of the external work\n",
                run.c_str(), account.kinetic, account.elastic, account.external_work, account.damping, account.numerical, worst,
                worst / largest);
  }
  beam.system.C = no_damping;

  // Backward Euler's numerical dissipation per step, mode 1 in free vibration.
  beam.set_gravity(false);
  const kerf::ReducedDynamicSystem reduced(beam.system);
  std::ofstream dissipation(out / "energy_dissipation.csv");
  dissipation.precision(12);
  dissipation << "omega_dt,dt,steps,kept_per_step_measured,kept_per_step_closed_form,spectral_radius_closed_form\n";
  const std::vector<double> omega_dts = quick ? std::vector<double>{0.1, 1.0} : std::vector<double>{0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1, 2, 5, 10};
  std::printf("  backward Euler, mode 1 free vibration:\n");
  for (const double omega_dt : omega_dts) {
    const int n_steps = 10;
    kerf::BackwardEulerIntegrator euler(beam.system, omega_dt / omega_1);
    const Eigen::VectorXd u0 = reduced.expand(1e-3 * modes.phi.col(0), false);
    kerf::DynamicState state = kerf::consistent_initial_state(reduced, u0, beam.zero(), 0.0, {});
    const double e0 = kerf::kinetic_energy(beam.system, state) + kerf::elastic_energy(beam.system, state);
    for (int n = 0; n < n_steps; ++n) euler.step(state);
    const double e1 = kerf::kinetic_energy(beam.system, state) + kerf::elastic_energy(beam.system, state);
    const double measured = std::pow(e1 / e0, 1.0 / n_steps), closed = 1.0 / (1.0 + omega_dt * omega_dt);
    dissipation << omega_dt << ',' << omega_dt / omega_1 << ',' << n_steps << ',' << measured << ',' << closed << ',' << std::sqrt(closed)
                << '\n';
    std::printf("    omega dt = %5.2f: energy kept per step %.12f (closed form %.12f)\n", omega_dt, measured, closed);
  }
  beam.set_gravity(true);
}

} // namespace dynamics_study

int main(int argc, char** argv) {
  const auto options = kerf_measure::parse_run_options(argc, argv, "06_dynamics_study [--quick] [--out DIR] [--only modes,period,energy]",
                                                       "output/dynamics_study", {"modes", "period", "energy"});
  if (!options) return 2;
  try {
    namespace ds = dynamics_study;
    std::filesystem::create_directories(options->out);
    std::cout << "Kerf chapter 6 dynamics study" << (options->quick ? " (quick)" : "") << " on " << kerf_measure::cpu_model() << ", "
              << kerf_measure::now_text() << "\n";
    ds::Beam beam(options->quick ? Eigen::Vector3i(1, 2, 6) : Eigen::Vector3i(3, 6, 20));
    if (options->runs("modes")) ds::run_modes(beam, options->quick, options->out);
    if (options->runs("period")) ds::run_period(beam, options->quick, options->out);
    if (options->runs("energy")) ds::run_energy(beam, options->quick, options->out);
  } catch (const std::exception& error) {
    std::cerr << "06_dynamics_study: " << error.what() << '\n';
    return 1;
  }
  return 0;
}
