/* Kerf, chapter 6 study: the validation experiments of the cut body in time. Schoch's falling
   slice (Fig. 4: linear XFEM's ghost forces against corotational XFEM), Koschier's hinged cubes
   (Fig. 10: XFEM against element duplication), the slab cut into slices and the block that
   unfolds (Figs. 11-12, the same comparison), frozen rotations against Newton per step, and the
   central difference pushed above its critical step.

   Build:   cmake --preset release && cmake --build --preset release --target 06_cut_dynamics_study

   Sample runs:
     06_cut_dynamics_study --quick --out output/cut_dynamics_study_quick
     06_cut_dynamics_study --out figures/06_newmark
     06_cut_dynamics_study --only hinge --out figures/06_newmark   (one part: slice, hinge, slab, unfold, rotations, explicit)

   Description, files in --out:
     slice      Schoch's beam 0.03 x 0.06 x 0.2 m (E = 300 kPa, nu = 0.35, rho = 1070 kg/m^3), Tet4
                on 3 x 6 x 20 cells (--quick 3 x 2 x 10), clamped at z = 0, gravity 9.81 m/s^2 along
                +x from t = 0, consistent mass, no damping. A cut at z = 0.175 through x in
                [-0.005, 0.025] leaves the top slice hanging by a strip 5 mm wide at x = 0.03:

                   z = 0.2 +------+      the slice, 25 mm thick, swings about the strip
                           |      |      (the hinge at x = 0.03) towards +x
                   0.175   ======-+ <- strip
                           |      |
                     z = 0 +======+ clamped

                Average acceleration Newmark, dt = 5 ms, 1 s, Newton per step, linear XFEM and
                corotational XFEM. slice_history.csv: the energies, the slice's rotation and the
                stretch of two of its edges (top edge along x, side edge along z) per step;
                numerical: the energy account's rest (energy_account.hpp), round-off here.
     hinge      Koschier's Fig. 10: the cube [0, 1]^3 of five tets hinged on its edge {x = 0, z = 1},
                gravity -z, E = 1e8 Pa (stiff: strain ~1e-4), nu = 0.3, rho = 1000, cut by x = c into a
                slice [0, c] that swings down to rest (Newmark gamma = 0.6, beta = 0.3025, Rayleigh
                alpha = 4 1/s, dt = 0.02 s, 20 s), by XFEM with the consistent mass ("xfem"), with
                the scenes' default lumped mass ("xfem_lumped", per-piece Bernstein), with the
                former default ("xfem_virtual_tet", each piece's weight at its tet's centroid), and
                by element duplication (each piece a full copy of its element,
                cut_dynamics_scenes.hpp). hinge.csv: the true centre of mass of the slice at rest,
                its horizontal offset from the hinge, and the offset the geometry predicts (the
                model's centre of weight under the hinge).
     slab       Koschier's Fig. 11 as Kerf reads it: a plate of 61 x 1 x 11 blocks of 1 cm (six Tet4
                a block) on the wall x = 0, gravity -z, E = 1e8 Pa, nu = 0.3, rho = 1000, cut along
                its length by z = 1.1, 2.7, 4.9, 7.6 cm into five slices 1.1 to 3.4 cm thick; Rayleigh
                alpha = 10 1/s, dt = 0.01 s, 4 s, Newton per step (to 1e-8), XFEM and duplication.
                slab.csv: each slice's model and true volume, its centre of mass's drop at rest,
                and Euler-Bernoulli's 0.6 rho g L^4 / (E t^2). --quick: 8 blocks long, 1 s.
     unfold     Koschier's Fig. 12 as Kerf reads it: the block [0, 1] x [0, 0.25] x [0, 1] on the
                hinge {x = 1/2, z = 1}, cut by z = 0.55 (x < 0.78) and z = 0.27 (x > 0.22) into a
                zig-zag that unfolds, E = 100 kPa, alpha = 2 1/s, dt = 0.02 s, 20 s (--quick 3.6 s
                of 0.06 s, not at rest). unfold.csv: the true and the model's centre of mass at rest
                from the hinge, the model's volume; unfold_history.csv: the true one every 5 steps.
     rotations  the demo's flap (chapters/06_newmark: Tet4 3 x 6 x 19, cut at z = 0.15, the default
                lumped mass, Rayleigh [3, 0.002]), 0.6 s, frozen rotations and Newton per step
                against a Newton run at dt = 0.625 ms (Newton to a relative residual of 1e-10):
                rotations.csv, the flap tip's largest error over the run, the linear solves and
                the milliseconds, against dt. A run whose step matrix Cholesky refuses (Newton's
                consistent tangent in a large step) is retried with LDL^T, and written as NaN
                if that fails too.
     explicit   the same flap, linear XFEM, the default lumped mass, central difference forced at
                0.9, 1.01 and 1.1 times the true critical step 2 / omega_max (omega_max by
                eigen_modes.hpp on M phi = mu K phi, mu = 1 / omega_max^2): explicit.csv, the energy
                every step, and explicit_growth.csv, its growth per step against the closed form
                |z|^2, z the top mode's amplification factor; beside it the program's estimate.
   --quick runs every part small and short; it is a test.

   Read chapter 6 first. */

#include "cut_dynamics_scenes.hpp"
#include "kerf/dynamics/central_difference.hpp"
#include "kerf/dynamics/critical_time_step.hpp"
#include "kerf/dynamics/eigen_modes.hpp"
#include "kerf/dynamics/energy_account.hpp"
#include "measure.hpp" // bench/measure.hpp: the command line shared with the benchmarks

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace cut_dynamics_study {

using cut_dynamics::beam_material;
using cut_dynamics::cube_material;
using cut_dynamics::node_at;
const double pi = std::numbers::pi;

kerf::NonlinearNewmarkSettings newton_settings() {
  kerf::NonlinearNewmarkSettings settings;
  settings.update = kerf::RotationUpdate::newton;
  settings.tolerance = 1e-10;
  return settings;
}

void run_slice(bool quick, const std::filesystem::path& out) {
  std::ofstream csv(out / "slice_history.csv");
  csv.precision(10);
  csv << "model,step,t,kinetic,elastic,external_work,numerical,rotation_deg,stretch_top,stretch_side\n";
  const double dt = 0.005;
  const int steps = quick ? 60 : 200;
  std::printf("slice: dt = %.3f s, %d steps, consistent mass, no damping, Newton per step\n", dt, steps);
  for (const bool corotated : {false, true}) {
    const auto body = cut_dynamics::schoch_beam(quick ? Eigen::Vector3i(3, 2, 10) : Eigen::Vector3i(3, 6, 20), quick ? 0.17 : 0.175, corotated);
    kerf::NonlinearNewmarkIntegrator integrator(body->system, dt, newton_settings());
    kerf::DynamicState state = integrator.initial_state(body->zero(), body->zero(), 0.0);
    kerf::EnergyAccount account = integrator.start_account(state);
    double largest_rotation = 0.0, largest_stretch = 0.0, largest_elastic = 0.0;
    const auto write = [&](int n) {
      const cut_dynamics::SliceShape shape = cut_dynamics::slice_shape(*body, state.u);
      const double rotation = shape.rotation_deg, stretch_top = shape.stretch_top, stretch_side = shape.stretch_side;
      csv << (corotated ? "corotational" : "linear") << ',' << n << ',' << state.t << ',' << account.kinetic << ',' << account.elastic << ','
          << account.external_work << ',' << account.numerical << ',' << rotation << ',' << stretch_top << ',' << stretch_side << '\n';
      largest_rotation = std::max(largest_rotation, rotation);
      largest_stretch = std::max({largest_stretch, std::abs(stretch_top), std::abs(stretch_side)});
      largest_elastic = std::max(largest_elastic, account.elastic);
    };
    write(0);
    for (int n = 1; n <= steps; ++n) {
      integrator.add_step(account, state, integrator.step(state));
      write(n);
    }
    std::printf("  %-12s: largest rotation %.2f deg, largest |edge stretch| %.4e, largest elastic energy %.4e J, "
                "final external work %.4e J\n",
                corotated ? "corotational" : "linear", largest_rotation, largest_stretch, largest_elastic, account.external_work);
  }
}

/// The horizontal offset from the hinge that the geometry predicts for a body whose model has its
/// centre of mass at `model_com` while its material's is at `true_com`: the model hangs with its
/// own centre of mass under the hinge (x = 0, z = 1), rotated about y by phi; that rotation moves
/// the material's centre of mass to a_x cos(phi) + a_z sin(phi), a = true_com - hinge.
double predicted_offset(const Eigen::Vector3d& true_com, const Eigen::Vector3d& model_com) {
  const double bx = model_com.x(), bz = model_com.z() - 1.0, ax = true_com.x(), az = true_com.z() - 1.0;
  const double phi = std::atan2(bx, -bz);
  return ax * std::cos(phi) + az * std::sin(phi);
}

// The centre of the slice's weight as the model has it, in the reference state: where the
// weights of its pieces act. Consistent and Bernstein masses put each piece's at its own centre
// of mass; the virtual tet at its tet's centroid; duplication gives every tet the slice touches
// its whole volume at its centroid.
Eigen::Vector3d slice_weight_centre(const cut_dynamics::CutDynamicBody& body, double c, const std::string& method) {
  if (method == "xfem" || method == "xfem_lumped")
    return body.centre_of_mass(body.zero(), [c](const Eigen::Vector3d& x) { return x.x() < c; });
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  double volume = 0.0;
  for (Eigen::Index t = 0; t < body.mesh.num_tets(); ++t) {
    const Eigen::Matrix<double, 4, 3> X = kerf::tet_corners(body.mesh, t);
    if (X.col(0).minCoeff() >= c) continue;
    double V = cut_dynamics::tet_volume(body.mesh, t);
    if (method == "xfem_virtual_tet" && X.col(0).maxCoeff() > c) {
      // The tet's piece x < c (its pieces are the two sides of the plane): its volume.
      const kerf::TetPieces& cut = body.pieces.tets[static_cast<std::size_t>(body.pieces.entry[static_cast<std::size_t>(t)])];
      V = 0.0;
      for (int p = 0; p < static_cast<int>(cut.pieces.size()); ++p) {
        const kerf::PieceQuadratureRule rule = kerf::subtet_rule(cut, p, 1);
        double w = 0.0, x = 0.0;
        for (std::size_t q = 0; q < rule.points.size(); ++q) w += rule.weights[q], x += rule.weights[q] * rule.points[q].x();
        if (x / w < c) V += w;
      }
    }
    moment += V * X.colwise().mean().transpose(), volume += V;
  }
  return moment / volume;
}

void run_hinge(bool quick, const std::filesystem::path& out) {
  std::ofstream csv(out / "hinge.csv");
  csv.precision(12);
  csv << "c,method,final_kinetic,com_x,com_y,com_z,predicted_com_x,rotation_deg\n";
  const double dt = 0.02, T = quick ? 8.0 : 20.0;
  const int steps = static_cast<int>(std::lround(T / dt));
  std::printf("hinge: five-tet cube, E = %.0e Pa, dt = %.2f s, %d steps, gamma = 0.6, Rayleigh alpha = 4 1/s\n", cube_material.young, dt,
              steps);
  const std::vector<double> cuts = quick ? std::vector<double>{0.3} : std::vector<double>{0.2, 0.35, 0.5, 0.65, 0.8};
  for (const double c : cuts)
    for (const std::string method : {"xfem", "xfem_lumped", "xfem_virtual_tet", "duplication"}) {
      const bool duplication = method == "duplication";
      const auto body = cut_dynamics::hinged_cube(c, cube_material, duplication ? cut_dynamics::duplication_rule : cut_dynamics::piece_rule);
      if (method == "xfem_lumped" || method == "xfem_virtual_tet")
        body->use_lumped_mass(method == "xfem_lumped" ? kerf::LumpingScheme::bernstein : kerf::LumpingScheme::virtual_tet, cube_material.density,
                              {0, 0, -9.81}, cut_dynamics::piece_rule);
      body->system.rayleigh_alpha = 4.0;
      kerf::NonlinearNewmarkSettings settings = newton_settings();
      settings.newmark = {0.3025, 0.6};
      kerf::NonlinearNewmarkIntegrator integrator(body->system, dt, settings);
      kerf::DynamicState state = integrator.initial_state(body->zero(), body->zero(), 0.0);
      for (int n = 0; n < steps; ++n) integrator.step(state);
      const auto on_slice = [c](const Eigen::Vector3d& x) { return x.x() < c; };
      const Eigen::Vector3d com = body->centre_of_mass(state.u, on_slice), com0 = body->centre_of_mass(body->zero(), on_slice);
      const double kinetic = 0.5 * state.v.dot(body->system.M * state.v);
      const Eigen::Vector3d d = com - Eigen::Vector3d(0, com.y(), 1), d0 = com0 - Eigen::Vector3d(0, com0.y(), 1);
      const double rotation = std::acos(std::clamp(d.normalized().dot(d0.normalized()), -1.0, 1.0)) * 180.0 / pi;
      const double predicted = predicted_offset(com0, slice_weight_centre(*body, c, method));
      csv << c << ',' << method << ',' << kinetic << ',' << com.x() << ',' << com.y() << ',' << com.z() << ',' << predicted << ',' << rotation
          << '\n';
      std::printf("  c = %.2f %-16s: slice centre of mass at rest x = %+.6e m from the hinge (geometry predicts %+.6e), "
                  "rotated %.2f deg, kinetic %.2e J\n",
                  c, method.c_str(), com.x(), predicted, rotation, kinetic);
    }
}

void run_slab(bool quick, const std::filesystem::path& out) {
  // Koschier: 61 x 11 x 1 blocks. Full: 61 x 1 x 11 blocks of 1 cm; --quick 8 x 1 x 11, 1 s.
  const int nx = quick ? 8 : 61, nz = 11;
  const double h = 0.01, L = nx * h, dt = 0.01, T = quick ? 1.0 : 4.0, alpha = 10.0;
  const int steps = static_cast<int>(std::lround(T / dt));
  // Five slices, thinnest at the bottom (so that the one that folds furthest folds away from the
  // rest): 1.1, 1.6, 2.2, 2.7 and 3.4 blocks thick, the cuts off the mesh's planes.
  const std::vector<double> cut_z{0.011, 0.027, 0.049, 0.076};
  std::vector<double> bounds{0.0};
  bounds.insert(bounds.end(), cut_z.begin(), cut_z.end());
  bounds.push_back(nz * h);
  std::ofstream csv(out / "slab.csv");
  csv.precision(10);
  csv << "method,slice,thickness,true_volume,model_volume,com_drop,beam_theory_drop,final_kinetic\n";
  std::printf("slab: %d x 1 x %d blocks of %.0f cm (%d Tet4), clamped at x = 0, E = %.0e Pa, dt = %.2f s, %d steps, gamma = 0.6, "
              "Rayleigh alpha = %.0f 1/s\n",
              nx, nz, h * 100, 6 * nx * nz, cube_material.young, dt, steps, alpha);
  for (const bool duplication : {false, true}) {
    const auto body =
        cut_dynamics::cut_slab(nx, nz, cut_z, cube_material, duplication ? cut_dynamics::duplication_rule : cut_dynamics::piece_rule);
    const kerf::DynamicState state = cut_dynamics::settle(*body, alpha, dt, steps, [](int, const kerf::DynamicState&) {});
    const double kinetic = 0.5 * state.v.dot(body->system.M * state.v);
    for (std::size_t k = 0; k + 1 < bounds.size(); ++k) {
      const double lo = bounds[k], hi = bounds[k + 1], thickness = hi - lo;
      const auto in_slice = [lo, hi](const Eigen::Vector3d& x) { return x.z() > lo && x.z() < hi; };
      const double drop = body->centre_of_mass(body->zero(), in_slice).z() - body->centre_of_mass(state.u, in_slice).z();
      // Euler-Bernoulli, a cantilever of thickness t under its weight rho g A: w(x) = q x^2 (6 L^2
      // - 4 L x + x^2) / (24 E I), whose mean over the length is q L^4 / (20 E I) = 0.6 rho g L^4 / (E t^2).
      const double beam = 0.6 * cube_material.density * 9.81 * std::pow(L, 4) / (cube_material.young * thickness * thickness);
      const double true_volume = cut_dynamics::model_volume(*body, in_slice, false), volume = cut_dynamics::model_volume(*body, in_slice, duplication);
      csv << (duplication ? "duplication" : "xfem") << ',' << k << ',' << thickness << ',' << true_volume << ',' << volume << ',' << drop << ','
          << beam << ',' << kinetic << '\n';
      std::printf("  %-11s slice %zu (%.1f mm): model volume / true %.3f, centre of mass drop at rest %.4e m (beam theory %.4e m)\n",
                  duplication ? "duplication" : "xfem", k, thickness * 1e3, volume / true_volume, drop, beam);
    }
    std::printf("  %-11s final kinetic energy %.2e J\n", duplication ? "duplication" : "xfem", kinetic);
  }
}

void run_unfold(bool quick, const std::filesystem::path& out) {
  const double dt = quick ? 0.06 : 0.02, T = quick ? 3.6 : 20.0, alpha = 2.0; // --quick: a few seconds, not at rest
  const int steps = static_cast<int>(std::lround(T / dt));
  const kerf::LinearMaterial soft{1e5, 0.3, 1000.0};
  std::ofstream csv(out / "unfold.csv"), history(out / "unfold_history.csv");
  csv.precision(12);
  history.precision(10);
  csv << "method,true_volume,model_volume,final_kinetic,com_x,com_z,com0_z,model_com_x\n";
  history << "method,step,t,com_x,com_z\n";
  std::printf("unfold: block 1 x 0.25 x 1 m on the hinge {x = 0.5, z = 1}, two cuts, E = %.0e Pa, dt = %.2f s, %d steps, gamma = 0.6, "
              "Rayleigh alpha = %.0f 1/s\n",
              soft.young, dt, steps, alpha);
  const auto all = [](const Eigen::Vector3d&) { return true; };
  for (const bool duplication : {false, true}) {
    const char* name = duplication ? "duplication" : "xfem";
    const kerf::PieceRuleFunction rule = duplication ? cut_dynamics::duplication_rule : cut_dynamics::piece_rule;
    const auto body = cut_dynamics::unfolding_block(soft, rule);
    const kerf::DynamicState state = cut_dynamics::settle(*body, alpha, dt, steps, [&](int n, const kerf::DynamicState& s) {
      if (n % 5) return;
      const Eigen::Vector3d com = body->centre_of_mass(s.u, all);
      history << name << ',' << n << ',' << s.t << ',' << com.x() - 0.5 << ',' << com.z() << '\n';
    });
    const double kinetic = 0.5 * state.v.dot(body->system.M * state.v);
    const Eigen::Vector3d com = body->centre_of_mass(state.u, all), com0 = body->centre_of_mass(body->zero(), all);
    const Eigen::Vector3d model_com = body->model_centre_of_mass(state.u, rule);
    const double true_volume = cut_dynamics::model_volume(*body, all, false), volume = cut_dynamics::model_volume(*body, all, duplication);
    csv << name << ',' << true_volume << ',' << volume << ',' << kinetic << ',' << com.x() - 0.5 << ',' << com.z() << ',' << com0.z() << ',' << model_com.x() - 0.5
        << '\n';
    std::printf("  %-11s: model volume / true %.4f, centre of mass at rest x = %+.6e m from the hinge (the model's %+.6e), "
                "z = %.6f m (from %.6f), kinetic %.2e J\n",
                name, volume / true_volume, com.x() - 0.5, model_com.x() - 0.5, com.z(), com0.z(), kinetic);
  }
}

/// The flap tip's displacement at every step of a run, with the solves and the time it took.
struct FlapRun {
  std::string solver;
  std::vector<Eigen::Vector3d> tip;
  long solves = 0;
  double ms = 0.0;
};

FlapRun run_flap(const cut_dynamics::CutDynamicBody& body, int tip, double dt, int steps, kerf::RotationUpdate update,
                 const std::string& solver) {
  kerf::NonlinearNewmarkSettings settings = newton_settings();
  settings.update = update;
  settings.solver.type = solver;
  FlapRun run;
  run.solver = solver;
  const auto start = std::chrono::steady_clock::now();
  kerf::NonlinearNewmarkIntegrator integrator(body.system, dt, settings);
  kerf::DynamicState state = integrator.initial_state(body.zero(), body.zero(), 0.0);
  run.tip.push_back(state.u.segment<3>(3 * tip));
  for (int n = 0; n < steps; ++n) {
    run.solves += integrator.step(state).iterations;
    run.tip.push_back(state.u.segment<3>(3 * tip));
  }
  run.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return run;
}

void run_rotations(bool quick, const std::filesystem::path& out) {
  const auto body = cut_dynamics::demo_flap(quick ? Eigen::Vector3i(3, 2, 6) : Eigen::Vector3i(3, 6, 19), true);
  const int tip = node_at(body->mesh, {0, 0.06, 0.2});
  const double T = quick ? 0.16 : 0.6, dt_reference = quick ? 0.0025 : 0.000625;
  const std::vector<double> dts = quick ? std::vector<double>{0.02, 0.01} : std::vector<double>{0.02, 0.01, 0.005, 0.0025};
  const FlapRun reference = run_flap(*body, tip, dt_reference, static_cast<int>(std::lround(T / dt_reference)), kerf::RotationUpdate::newton,
                                   "cholmod");
  double amplitude = 0.0;
  for (const Eigen::Vector3d& u : reference.tip) amplitude = std::max(amplitude, u.norm());
  std::printf("rotations: the demo flap over %.2f s; reference Newton at dt = %.3e s (%ld solves, %.0f ms), largest tip |u| %.4e m\n", T,
              dt_reference, reference.solves, reference.ms, amplitude);
  std::ofstream csv(out / "rotations.csv");
  csv.precision(10);
  csv << "update,solver,dt,steps,solves,ms,ms_per_step,tip_error_max,tip_error_relative\n";
  for (const double dt : dts)
    for (const kerf::RotationUpdate update : {kerf::RotationUpdate::frozen, kerf::RotationUpdate::newton}) {
      const int steps = static_cast<int>(std::lround(T / dt));
      // Newton's consistent tangent is not positive definite in a large step (its geometric
      // terms), and M + beta dt^2 K with it may lose definiteness: Cholesky then refuses, and
      // the run is done again with the LDL^T factorisation, which takes an indefinite matrix.
      // If that fails too, the row says so (NaN error).
      FlapRun run;
      const char* name = update == kerf::RotationUpdate::newton ? "newton" : "frozen";
      for (const std::string solver : {"cholmod", "ldlt"}) {
        try {
          run = run_flap(*body, tip, dt, steps, update, solver);
          break;
        } catch (const std::exception& error) {
          std::printf("  %-6s %-7s dt = %.4f s: failed: %s\n", name, solver.c_str(), dt, error.what());
          run = FlapRun{solver + " failed", {}, 0, 0.0};
        }
      }
      if (run.tip.empty()) {
        csv << name << ',' << run.solver << ',' << dt << ',' << steps << ",NaN,NaN,NaN,NaN,NaN\n";
        continue;
      }
      const int stride = static_cast<int>(std::lround(dt / dt_reference));
      double error = 0.0;
      for (int n = 0; n <= steps; ++n) error = std::max(error, (run.tip[n] - reference.tip[n * stride]).norm());
      csv << name << ',' << run.solver << ',' << dt << ',' << steps << ',' << run.solves << ',' << run.ms << ',' << run.ms / steps << ',' << error << ','
          << error / amplitude << '\n';
      std::printf("  %-6s %-7s dt = %.4f s: %4d steps, %5ld solves, %8.1f ms (%.2f ms/step), largest tip error %.4e m = %.3e of the swing\n",
                  name, run.solver.c_str(), dt, steps, run.solves, run.ms, run.ms / steps, error, error / amplitude);
    }
}

void run_explicit(bool quick, const std::filesystem::path& out) {
  const auto body = cut_dynamics::demo_flap(quick ? Eigen::Vector3i(3, 2, 6) : Eigen::Vector3i(3, 6, 19), false);
  kerf::LinearDynamicSystem linear;
  linear.M = body->system.M;
  linear.K = body->K;
  linear.C = Eigen::SparseMatrix<double>(linear.M.rows(), linear.M.cols());
  linear.dofs = body->system.dofs;
  linear.load = body->system.load;
  const kerf::ReducedDynamicSystem reduced(linear);
  // The true omega_max: the lowest mu of M phi = mu K phi is 1 / omega_max^2 (K is positive
  // definite: the clamp holds every piece, the flap through its strip).
  const kerf::EigenModes top = kerf::lowest_eigenmodes(reduced.M_ff(), reduced.K_ff(), 1, 0.0, 1e-13);
  const double omega_max = 1.0 / std::sqrt(top.lambda[0]), critical = 2.0 / omega_max;
  const double estimate = kerf::CentralDifferenceIntegrator(linear, critical, true).critical_step();
  std::printf("explicit: omega_max = %.6e rad/s (eigen_modes, %s), true critical step 2 / omega_max = %.9e s, "
              "the program's estimate %.9e s (relative difference %.2e)\n",
              omega_max, top.converged ? "converged" : "NOT converged", critical, estimate, (estimate - critical) / critical);
  std::ofstream csv(out / "explicit.csv"), growth(out / "explicit_growth.csv");
  csv.precision(12);
  growth.precision(12);
  csv << "factor,step,t,energy\n";
  growth << "factor,dt,critical_true,critical_estimate,growth_measured,growth_closed_form,steps\n";
  const int steps = 300; // cheap: the mass is diagonal; enough for 1.01 dt_crit to blow up from round-off
  for (const double factor : {0.9, 1.01, 1.1}) {
    const double dt = factor * critical;
    kerf::CentralDifferenceIntegrator integrator(linear, dt, true);
    kerf::DynamicState state = kerf::consistent_initial_state(reduced, body->zero(), body->zero(), 0.0, {});
    std::vector<double> energy{kerf::kinetic_energy(linear, state) + kerf::elastic_energy(linear, state)};
    csv << factor << ",0,0," << energy[0] << '\n';
    for (int n = 1; n <= steps && energy.back() < 1e40 && std::isfinite(energy.back()); ++n) {
      integrator.step(state);
      energy.push_back(kerf::kinetic_energy(linear, state) + kerf::elastic_energy(linear, state));
      csv << factor << ',' << n << ',' << state.t << ',' << energy.back() << '\n';
    }
    // Growth per step over the last 20 steps, where the top mode dominates; closed form: the
    // top mode's |z|^2 (energy is quadratic), z the larger root of z^2 - b z + 1 = 0 with b =
    // 2 - omega^2 dt^2 (stable, |z| = 1, while |b| <= 2).
    const std::size_t last = energy.size() - 1, first = last >= 20 ? last - 20 : 0;
    const double measured = std::pow(energy[last] / energy[first], 1.0 / double(last - first));
    const double b = 2.0 - omega_max * omega_max * dt * dt;
    const double closed = std::abs(b) <= 2.0 ? 1.0 : std::pow((std::abs(b) + std::sqrt(b * b - 4.0)) / 2.0, 2.0);
    growth << factor << ',' << dt << ',' << critical << ',' << estimate << ',' << measured << ',' << closed << ',' << last << '\n';
    std::printf("  dt = %.2f dt_crit: %3zu steps, energy %.3e -> %.3e J, growth per step %.6f (closed form %.6f)\n", factor, last, energy[0],
                energy[last], measured, closed);
  }
}

} // namespace cut_dynamics_study

int main(int argc, char** argv) {
  const auto options = kerf_measure::parse_run_options(argc, argv, "06_cut_dynamics_study [--quick] [--out DIR] [--only slice,hinge,slab,unfold,rotations,explicit]",
                                                       "output/cut_dynamics_study", {"slice", "hinge", "slab", "unfold", "rotations", "explicit"});
  if (!options) return 2;
  try {
    namespace cs = cut_dynamics_study;
    std::filesystem::create_directories(options->out);
    std::cout << "Kerf chapter 6 cut dynamics study" << (options->quick ? " (quick)" : "") << " on " << kerf_measure::cpu_model() << ", "
              << kerf_measure::now_text() << "\n";
    if (options->runs("slice")) cs::run_slice(options->quick, options->out);
    if (options->runs("hinge")) cs::run_hinge(options->quick, options->out);
    if (options->runs("slab")) cs::run_slab(options->quick, options->out);
    if (options->runs("unfold")) cs::run_unfold(options->quick, options->out);
    if (options->runs("rotations")) cs::run_rotations(options->quick, options->out);
    if (options->runs("explicit")) cs::run_explicit(options->quick, options->out);
  } catch (const std::exception& error) {
    std::cerr << "06_cut_dynamics_study: " << error.what() << '\n';
    return 1;
  }
  return 0;
}
