/* Kerf benchmark: chapter 8's time step on the liver, against chapter 7's, on one core.

   Build and run:   cmake --build --preset release --target bench
                    (runs bench_real_time with OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1)
   By hand:         OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 bench_real_time --out bench_real_time.md
                    bench_real_time --quick      (the smallest liver, a few steps: does it run?)
                    bench_real_time --only 10000 (the 10k liver alone)

   The scene of chapter 7's demo (examples/07_liver_cut.json): the liver of mesh/liver_shape.hpp
   meshed into about 2k, 10k, 30k and 100k Tet4, E = 4 kPa, nu = 0.45, rho = 1060 kg/m^3, held at
   the back as the demo holds it, gravity switched on at t = 0, Rayleigh damping
   C = 2 M + 0.01 K_R, Newmark's average acceleration at dt = 10 ms, the Bernstein lumped mass; cut
   by the sheet the demo's blade leaves (the plane y = -0.005 from x = -0.03 on, from z = 0 up).
   The cut is fixed here: chapter 8's program grows it; what a change of topology costs is
   measured apart (below).

   For each mesh, 100 steps (1 s, the sag's first swing) from rest:
   - the reference: chapter 8's step solved to a relative gradient of 1e-9 (tests/chapter_08
     shows it is chapter 7's Newton step to 2e-12), and up to 10k tets chapter 7's steps on the
     same body (Newton with CHOLMOD, and its default, the checked frozen step with CG), for their
     time and to show the reference is theirs;
   - chapter 8's step at 3, 4 and 6 iterations a step: wall-clock ms per step, split into the
     passes over the pieces, the solves with the factor and the rest; its error: the largest
     distance of a node from the reference's over all steps, relative to the reference's largest
     displacement, and the sag (the lowest node's drop) at 1 s against the reference's.
   - a change of topology: the step's set_body from the liver cut up to x = -0.025 to the liver
     cut up to x = -0.03, the blade 5 mm further (the factor of the mesh's nodes kept, the rows
     of the enrichments the cut did not change kept), against a new integrator's set_body
     on the second (everything factorised); best of 5.
   The whole process's processor and wall time close the report: the program's own clocks are
   not all it costs. With --out FILE.md the rows also go to FILE.csv. */

#include "kerf/corotation/corotated_pieces.hpp"
#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/dynamics/lumped_mass.hpp"
#include "kerf/dynamics/nonlinear_newmark.hpp"
#include "kerf/dynamics/quasi_newton_newmark.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/mesh/liver_mesh.hpp"
#include "kerf/quadrature/gauss_piece_rules.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"
#include "kerf/xfem/surface_enrichment.hpp"
#include "measure.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace {

const kerf::LinearMaterial tissue{4000.0, 0.45, 1060.0};
constexpr double dt = 0.01, rayleigh_alpha = 2.0, rayleigh_beta = 0.01;

double seconds_since(kerf_measure::clock::time_point start) {
  return std::chrono::duration<double>(kerf_measure::clock::now() - start).count();
}

// The liver cut by the demo's sheet from x = cut_end on, with everything its model refers to.
struct CutLiver {
  const kerf::TetMesh& mesh;
  kerf::CutSurfaces cuts;
  kerf::MeshPieces pieces;
  kerf::SurfaceEnrichment enrichment;
  kerf::CutXfemModel model;
  kerf::DofMap dofs;
  Eigen::SparseMatrix<double> M;
  Eigen::VectorXd weight;
  kerf::CorotatedPieces corotated;

  static kerf::TriangleSurface sheet(double cut_end) {
    kerf::TriangleSurface s;
    s.vertices.resize(4, 3);
    s.vertices << cut_end, -0.005, 0.0, 0.3, -0.005, 0.0, 0.3, -0.005, 0.3, cut_end, -0.005, 0.3;
    s.triangles.resize(2, 3);
    s.triangles << 0, 1, 2, 0, 2, 3;
    return s;
  }
  static kerf::PieceQuadratureRule subtets(const Eigen::Matrix<double, 4, 3>&, const kerf::TetPieces& tet_pieces, int piece, int degree) {
    return kerf::subtet_rule(tet_pieces, piece, degree);
  }

  CutLiver(const kerf::TetMesh& liver, const std::vector<kerf::DirichletNodes>& held, double cut_end)
      : mesh(liver), cuts(std::vector<kerf::TriangleSurface>{sheet(cut_end)}), pieces(kerf::cut_mesh_into_pieces(mesh, cuts)),
        enrichment(kerf::make_surface_enrichment(mesh, pieces)), model(mesh, tissue, pieces, enrichment, subtets),
        dofs(kerf::make_cut_xfem_dof_map(model, held)),
        M(kerf::lump_cut_xfem_mass(model, tissue.density, kerf::LumpingScheme::bernstein, subtets)),
        corotated(model, tissue, kerf::RotationMethod::automatic) {
    Eigen::VectorXd down = Eigen::VectorXd::Zero(M.rows());
    for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) down[3 * v + 2] = -9.81;
    weight = M * down;
  }
  kerf::QuasiNewtonBody body() const { return {&corotated, M, dofs, weight, mesh.num_nodes(), rayleigh_alpha, rayleigh_beta}; }
};

// The nodes the demo holds: the upper back and the underside's back half.
std::vector<kerf::DirichletNodes> demo_holds(const kerf::TetMesh& mesh) {
  std::vector<int> nodes;
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) {
    const double y = mesh.nodes(v, 1), z = mesh.nodes(v, 2);
    if ((y >= 0.045 && z >= -0.01) || (y >= -0.01 && z <= -0.03)) nodes.push_back(static_cast<int>(v));
  }
  return {{nodes, {0, 0, 0}}};
}

struct Run {
  std::vector<Eigen::VectorXd> u; // the mesh's nodes' displacements after each step
  double total = 0.0, pieces = 0.0, solve = 0.0; // seconds over all steps
  double evaluations = 0.0;                       // per step
};

Run chapter_8_run(const CutLiver& liver, const kerf::QuasiNewtonNewmarkSettings& settings, int steps) {
  kerf::QuasiNewtonNewmark newmark(dt, tissue, settings);
  newmark.set_body(liver.body());
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(liver.M.rows());
  kerf::DynamicState state = newmark.initial_state(zero, zero, 0.0);
  Run run;
  for (int n = 0; n < steps; ++n) {
    const auto start = kerf_measure::clock::now();
    const kerf::QuasiNewtonStepReport report = newmark.step(state);
    run.total += seconds_since(start);
    run.pieces += report.pieces_seconds;
    run.solve += report.solve_seconds;
    run.evaluations += report.iterations + 1;
    run.u.push_back(state.u.head(3 * liver.mesh.num_nodes()));
  }
  run.evaluations /= steps;
  return run;
}

Run chapter_7_run(const CutLiver& liver, kerf::RotationUpdate update, int steps) {
  const kerf::DofMap all_free = kerf::make_dof_map(liver.model.num_dof_nodes(), {});
  kerf::SparseAssembler assembler(liver.model.assembly_slots(), all_free);
  kerf::NonlinearDynamicSystem system;
  system.M = liver.M;
  system.rayleigh_alpha = rayleigh_alpha;
  system.rayleigh_beta = rayleigh_beta;
  system.dofs = liver.dofs;
  const Eigen::VectorXd f = liver.weight, zero = Eigen::VectorXd::Zero(liver.M.rows());
  system.load = [f](double) { return f; };
  system.motion = [zero](double) { return kerf::PrescribedMotion{zero, zero, zero}; };
  system.internal_force = [&](const Eigen::VectorXd& u, kerf::CorotationalTangent tangent, Eigen::VectorXd& f_int,
                              const Eigen::SparseMatrix<double>** K) {
    Eigen::VectorXd unused = Eigen::VectorXd::Zero(u.size());
    if (K) assembler.set_zero();
    liver.model.assemble(u, kerf::RotationMethod::automatic, tangent, f_int, K ? &assembler : nullptr, K ? &unused : nullptr);
    if (K) *K = &assembler.matrix();
  };
  system.elastic_energy = [&](const Eigen::VectorXd& u) { return liver.model.energy(u, true); };
  kerf::NonlinearNewmarkSettings settings;
  settings.update = update;
  settings.tolerance = update == kerf::RotationUpdate::newton ? 1e-9 : 1e-6;
  if (update == kerf::RotationUpdate::checked) {
    settings.solver.type = "cg-jacobi";
    settings.solver.tolerance = settings.tolerance;
  }
  kerf::NonlinearNewmarkIntegrator newmark(system, dt, settings);
  kerf::DynamicState state = newmark.initial_state(zero, zero, 0.0);
  Run run;
  for (int n = 0; n < steps; ++n) {
    const auto start = kerf_measure::clock::now();
    newmark.step(state);
    run.total += seconds_since(start);
    run.u.push_back(state.u.head(3 * liver.mesh.num_nodes()));
  }
  return run;
}

double largest_displacement(const std::vector<Eigen::VectorXd>& run) {
  double largest = 0.0;
  for (const Eigen::VectorXd& u : run)
    for (Eigen::Index v = 0; 3 * v < u.size(); ++v) largest = std::max(largest, u.segment<3>(3 * v).norm());
  return largest;
}
double largest_difference(const std::vector<Eigen::VectorXd>& a, const std::vector<Eigen::VectorXd>& b) {
  double largest = 0.0;
  for (std::size_t n = 0; n < a.size(); ++n)
    for (Eigen::Index v = 0; 3 * v < a[n].size(); ++v) largest = std::max(largest, (a[n].segment<3>(3 * v) - b[n].segment<3>(3 * v)).norm());
  return largest;
}
double sag(const Eigen::VectorXd& u) { // the lowest node's drop (m)
  double lowest = 0.0;
  for (Eigen::Index v = 0; 3 * v < u.size(); ++v) lowest = std::min(lowest, u[3 * v + 2]);
  return -lowest;
}

} // namespace

int main(int argc, char** argv) {
  const auto options = kerf_measure::parse_run_options(argc, argv, "bench_real_time [--quick] [--out FILE.md] [--only 2000,10000,30000,100000]",
                                                       {}, {"2000", "10000", "30000", "100000"});
  if (!options) return 2;
  const auto process_start = kerf_measure::clock::now();
  std::vector<int> sizes;
  for (const int n : options->quick ? std::vector<int>{2000} : std::vector<int>{2000, 10000, 30000, 100000})
    if (options->quick || options->runs(std::to_string(n))) sizes.push_back(n);
  const int steps = options->quick ? 5 : 100;

  std::ostringstream table, topology, csv;
  csv << "tets,nodes,enrichments,step,iterations,ms_per_step,pieces_ms,solve_ms,rest_ms,evaluations_per_step,error,sag_mm,reference_sag_mm\n";
  table << "| tets | nodes | enrichments | step | ms/step | pieces | solve | rest | evaluations/step | error | sag at 1 s (mm) |\n"
        << "|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|\n";
  topology << "| tets | enrichments before, after | grown factor (ms) | columns kept | everything factorised (ms) |\n|---:|---:|---:|---:|---:|\n";
  for (const int target : sizes) {
    const kerf::TetMesh mesh = kerf::make_liver_mesh(target);
    const std::vector<kerf::DirichletNodes> held = demo_holds(mesh);
    const CutLiver liver(mesh, held, -0.03);
    const long tets = static_cast<long>(mesh.num_tets()), nodes = static_cast<long>(mesh.num_nodes());
    const long enrichments = static_cast<long>(liver.enrichment.num_enrichments());
    std::cerr << "bench_real_time: " << tets << " tets, " << nodes << " nodes, " << enrichments << " enrichments\n";
    const auto row = [&](const std::string& label, const std::string& iterations, const Run& run, double error, double reference_sag) {
      const double ms = 1e3 / steps, rest = run.total - run.pieces - run.solve;
      const double end_sag = sag(run.u.back());
      char line[512];
      std::snprintf(line, sizeof line, "| %ld | %ld | %ld | %s | %.2f | %.2f | %.2f | %.2f | %.1f | %.2e | %.2f (%.2f) |\n", tets, nodes,
                    enrichments, label.c_str(), ms * run.total, ms * run.pieces, ms * run.solve, ms * rest, run.evaluations, error,
                    1e3 * end_sag, 1e3 * reference_sag);
      table << line;
      std::cerr << line;
      std::snprintf(line, sizeof line, "%ld,%ld,%ld,%s,%s,%.4f,%.4f,%.4f,%.4f,%.2f,%.4e,%.4f,%.4f\n", tets, nodes, enrichments, label.c_str(),
                    iterations.c_str(), ms * run.total, ms * run.pieces, ms * run.solve, ms * rest, run.evaluations, error, 1e3 * end_sag,
                    1e3 * reference_sag);
      csv << line;
    };
    kerf::QuasiNewtonNewmarkSettings tight;
    tight.tolerance = 1e-9;
    const bool with_reference = target <= 30000 || options->quick;
    Run reference;
    double largest = 0.0, reference_sag = 0.0;
    if (with_reference) {
      reference = chapter_8_run(liver, tight, steps);
      largest = largest_displacement(reference.u);
      reference_sag = sag(reference.u.back());
      row("chapter 8, tight (the reference)", "tight", reference, 0.0, reference_sag);
    }
    const auto error_of = [&](const Run& run) { return with_reference ? largest_difference(run.u, reference.u) / largest : 0.0; };
    if (target <= 10000) {
      const Run newton = chapter_7_run(liver, kerf::RotationUpdate::newton, steps);
      row("chapter 7, Newton (CHOLMOD)", "newton", newton, error_of(newton), reference_sag);
      const Run checked = chapter_7_run(liver, kerf::RotationUpdate::checked, steps);
      row("chapter 7, checked (CG, its default)", "checked", checked, error_of(checked), reference_sag);
    }
    for (int iterations : {3, 4, 6}) {
      kerf::QuasiNewtonNewmarkSettings settings;
      settings.iterations = iterations;
      const Run run = chapter_8_run(liver, settings, steps);
      row("chapter 8, " + std::to_string(iterations) + " iterations", std::to_string(iterations), run, error_of(run), reference_sag);
    }
    // A change of topology: the cut grown by 5 mm, from x = -0.025 to x = -0.03 (the demo's blade
    // moves 1.25 mm a step), best of 5.
    const CutLiver shorter(mesh, held, -0.025);
    kerf::QuasiNewtonNewmark grown(dt, tissue, {});
    double grown_ms = 1e300, fresh_ms = 1e300;
    for (int repeat = 0; repeat < 5; ++repeat) {
      grown.set_body(shorter.body());
      auto start = kerf_measure::clock::now();
      grown.set_body(liver.body());
      grown_ms = std::min(grown_ms, 1e3 * seconds_since(start));
      kerf::QuasiNewtonNewmark fresh(dt, tissue, {});
      start = kerf_measure::clock::now();
      fresh.set_body(liver.body());
      fresh_ms = std::min(fresh_ms, 1e3 * seconds_since(start));
    }
    char line[256];
    std::snprintf(line, sizeof line, "| %ld | %ld, %ld | %.1f (%d factorisation) | %ld | %.1f |\n", tets,
                  static_cast<long>(shorter.enrichment.num_enrichments()), enrichments, grown_ms, grown.factorisations(),
                  static_cast<long>(grown.kept_enrichment_columns()), fresh_ms);
    topology << line;
    std::cerr << line;
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const double cpu = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                     1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);

  std::ostringstream report;
  report << "# Chapter 8 benchmark: the time step of the cut liver, against chapter 7's\n\n"
         << kerf_measure::machine_lines() << "- " << steps
         << " steps of 10 ms from rest, wall-clock ms per step (one run each); error: the largest distance of a mesh node from the "
            "reference's over all steps, relative to the reference's largest displacement; sag: the lowest node's drop at the end "
            "(the reference's in brackets)\n\n"
         << table.str() << "\nA change of topology (the step's set_body; the cut's geometry, pieces and model not included):\n\n"
         << topology.str() << "\nThe whole process: " << cpu << " s of processor time (user and system, getrusage), "
         << seconds_since(process_start) << " s of wall time, " << usage.ru_maxrss / 1024 << " MB at most.\n";
  std::cout << report.str();
  kerf_measure::write_report(options->out, report.str(), csv.str());
  return 0;
}
