/* Kerf benchmark: chapter 1's linear static pipeline, piece by piece, on one core.

   Build and run:   cmake --build --preset release --target bench
                    (runs bench_linear_fem with OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1)
   By hand:         OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 bench_linear_fem --out bench.md
                    bench_linear_fem --quick      (small meshes, a few seconds: does it run?)

   On the beam of chapter 1 (0.03 x 0.06 x 0.2 m, clamped at z = 0, gravity along x), meshed
   with (1, 2, 6) k box cells and promoted to Tet10 where asked, it measures
     (a) element stiffness blocks per second: tet4_stiffness / tet10_stiffness alone;
     (b) assembly: the blocks plus their scatter into the fixed pattern, blocks per second;
     (c) the time to build the pattern and the scatter map (SparseAssembler's constructor);
     (d) the solve: CHOLMOD (analyse + factorise + solve), and CG with a Jacobi or an
         incomplete Cholesky preconditioner to a relative residual of 1e-8;
     (e) CalculiX's wall time for the same mesh and load, when ccx was found at configure time;
     (f) CHOLMOD with each fill-reducing ordering (kerf::CholmodSolver): analyse and factorise
         times, the factor's entries and the factorisation's flops.
   Every number is the best of at least three runs and of at least half a second of repeats:
   the minimum is what the work costs, the rest is noise from the machine. The report is a
   markdown table on stdout and, with --out, in a file. */

#include "kerf/fem/assemble_loads.hpp"
#include "kerf/fem/assemble_stiffness.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/linear_material.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/fem/tet_stiffness.hpp"
#include "kerf/io/calculix_deck.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/node_region.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"
#include "kerf/solve/cholmod_solver.hpp"
#include "kerf/solve/linear_solver.hpp"
#include "measure.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace bench {

using kerf_measure::best_time;
using kerf_measure::clock;

/// Every measurement's rule, as the report states it: the best of at least three runs and of
/// at least half a second of repeats, unless 20 s have gone by.
constexpr kerf_measure::Repeats usual_repeats{3, 0.5, 20.0};

/// The chapter 1 beam with (1, 2, 6) k cells, Tet4 (order 1) or Tet10 (order 2).
kerf::TetMesh beam_mesh(int k, int order) {
  const kerf::TetMesh tet4 = kerf::make_box_mesh({0, 0, 0}, {0.03, 0.06, 0.2}, Eigen::Vector3i(1, 2, 6) * k);
  return order == 1 ? tet4 : kerf::tet10_from_tet4(tet4);
}

/// The clamp at z = 0.
kerf::DirichletNodes clamp(const kerf::TetMesh& mesh) {
  kerf::NodeRegion base;
  base.box_max = {0.03, 0.06, 0.0};
  return {kerf::nodes_in_region(mesh, base), {0, 0, 0}};
}

/// (a) Element stiffness matrices alone, every tet once. The sum of one entry per block keeps
/// the compiler from skipping work whose result nobody reads.
template <int n>
double element_stiffness_sweep(const kerf::TetMesh& mesh, const kerf::LinearMaterial& material) {
  double sink = 0.0;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    Eigen::Matrix<double, n, 3> X;
    for (int a = 0; a < n; ++a) X.row(a) = mesh.nodes.row(mesh.tets(t, a));
    if constexpr (n == 4)
      sink += kerf::tet4_stiffness(X, material)(0, 0);
    else
      sink += kerf::tet10_stiffness(X, material)(0, 0);
  }
  return sink;
}

/// (f) CHOLMOD with one fill-reducing ordering on one mesh.
struct OrderingTiming {
  std::string ordering;
  double analyze_seconds = 1e300, factorize_seconds = 1e300;
  double factor_entries = 0, factorisation_flops = 0;
  int ordered_vertices = 0;
};

/// One row of the report.
struct Measurement {
  std::string element;
  std::string cells;
  Eigen::Index tets = 0;
  int dofs = 0;
  Eigen::Index stored_entries = 0;
  double blocks_per_second = 0, assembled_blocks_per_second = 0, pattern_seconds = 0;
  double analyze_seconds = 0, factorize_seconds = 0, solve_seconds = 0;
  double pipeline_seconds = 0; ///< pattern + assembly + CHOLMOD analyse/factorise/solve
  double cg_jacobi_seconds = 0, cg_ichol_seconds = 0;
  int cg_jacobi_iterations = 0, cg_ichol_iterations = 0;
  double ccx_seconds = -1; ///< -1: not measured
  std::vector<OrderingTiming> orderings;
};

/// (f): the best of two fresh solvers per ordering (a factorisation on a large mesh with a
/// poor ordering takes seconds; two runs of it are enough to see the machine's noise).
std::vector<OrderingTiming> time_orderings(const Eigen::SparseMatrix<double>& K) {
  std::vector<OrderingTiming> timings;
  for (const char* ordering : {"cholmod", "amd", "metis", "nested-dissection"}) {
    OrderingTiming t;
    t.ordering = ordering;
    for (int r = 0; r < 2; ++r) {
      kerf::CholmodSolver solver(ordering);
      auto start = clock::now();
      solver.analyze_pattern(K);
      t.analyze_seconds = std::min(t.analyze_seconds, std::chrono::duration<double>(clock::now() - start).count());
      start = clock::now();
      solver.factorize(K);
      t.factorize_seconds = std::min(t.factorize_seconds, std::chrono::duration<double>(clock::now() - start).count());
      t.factor_entries = solver.statistics().factor_entries;
      t.factorisation_flops = solver.statistics().factorisation_flops;
      t.ordered_vertices = solver.statistics().ordered_vertices;
    }
    timings.push_back(t);
  }
  return timings;
}

/// Preconditioner set-up plus a CG solve from zero to 1e-8; returns {seconds, iterations}.
std::pair<double, int> time_cg(const std::string& type, const Eigen::SparseMatrix<double>& K, const Eigen::VectorXd& rhs) {
  kerf::SolverSettings settings;
  settings.type = type;
  settings.tolerance = 1e-8;
  settings.max_iterations = 100000;
  int iterations = 0;
  const double seconds = best_time([&] {
    const auto solver = kerf::make_linear_solver(settings);
    solver->analyze_pattern(K);
    solver->factorize(K);
    Eigen::VectorXd u = Eigen::VectorXd::Zero(rhs.size());
    solver->solve(rhs, u);
    iterations = solver->iterations();
  }, usual_repeats);
  return {seconds, iterations};
}

/// Everything measured on one mesh.
Measurement measure(int k, int order, const std::string& ccx, const std::filesystem::path& work) {
  const kerf::LinearMaterial material;
  const Eigen::Vector3d gravity(9.81, 0, 0);
  const kerf::TetMesh mesh = beam_mesh(k, order);
  const kerf::DofMap dofs = kerf::make_dof_map(mesh.num_nodes(), {clamp(mesh)});
  Measurement m;
  m.element = order == 1 ? "Tet4" : "Tet10";
  m.cells = std::to_string(k) + "x" + std::to_string(2 * k) + "x" + std::to_string(6 * k);
  m.tets = mesh.num_tets();
  m.dofs = dofs.num_free;
  const double num_tets = static_cast<double>(mesh.num_tets());

  double sink = 0.0;
  m.blocks_per_second = num_tets / best_time([&] {
                          sink += order == 1 ? element_stiffness_sweep<4>(mesh, material)
                                             : element_stiffness_sweep<10>(mesh, material);
                        }, usual_repeats);

  m.pattern_seconds = best_time([&] { kerf::SparseAssembler assembler(mesh.tets, dofs); }, usual_repeats);
  kerf::SparseAssembler assembler(mesh.tets, dofs);
  m.stored_entries = assembler.num_stored_entries();
  const Eigen::VectorXd f_free = dofs.restrict_to_free(kerf::assemble_gravity(mesh, material.density, gravity));
  Eigen::VectorXd rhs = f_free;
  m.assembled_blocks_per_second = num_tets / best_time([&] {
                                    assembler.set_zero();
                                    rhs = f_free;
                                    kerf::assemble_linear_stiffness(mesh, material, assembler, rhs);
                                  }, usual_repeats);
  const Eigen::SparseMatrix<double>& K = assembler.matrix();

  // CHOLMOD, stage by stage: the best of three fresh solvers.
  m.analyze_seconds = m.factorize_seconds = m.solve_seconds = 1e300;
  for (int r = 0; r < 3; ++r) {
    const auto solver = kerf::make_linear_solver(kerf::SolverSettings{});
    auto start = clock::now();
    solver->analyze_pattern(K);
    m.analyze_seconds = std::min(m.analyze_seconds, std::chrono::duration<double>(clock::now() - start).count());
    start = clock::now();
    solver->factorize(K);
    m.factorize_seconds = std::min(m.factorize_seconds, std::chrono::duration<double>(clock::now() - start).count());
    start = clock::now();
    Eigen::VectorXd u(rhs.size());
    solver->solve(rhs, u);
    m.solve_seconds = std::min(m.solve_seconds, std::chrono::duration<double>(clock::now() - start).count());
  }
  m.pipeline_seconds = m.pattern_seconds + num_tets / m.assembled_blocks_per_second + m.analyze_seconds +
                       m.factorize_seconds + m.solve_seconds;

  m.orderings = time_orderings(K);
  std::tie(m.cg_jacobi_seconds, m.cg_jacobi_iterations) = time_cg("cg-jacobi", K, rhs);
  std::tie(m.cg_ichol_seconds, m.cg_ichol_iterations) = time_cg("cg-ichol", K, rhs);

  if (!ccx.empty()) {
    kerf::CalculixJob job;
    job.material = material;
    job.dirichlet = {clamp(mesh)};
    job.gravity = gravity;
    const std::string jobname = m.element + "_" + m.cells;
    std::filesystem::create_directories(work);
    kerf::write_calculix_deck(work / (jobname + ".inp"), mesh, job);
    m.ccx_seconds = best_time([&] { kerf::run_calculix(ccx, work, jobname); }, {3, 0.0, 10.0});
  }
  if (sink == 42.0) std::cout << ' '; // uses the sink; never true in practice
  return m;
}

/// The markdown report.
std::string report(const std::vector<Measurement>& rows, const std::string& ccx) {
  std::ostringstream s;
  char line[512];
  s << "## bench_linear_fem\n\n"
    << "- CPU: " << kerf_measure::cpu_model() << "\n- date: " << kerf_measure::now_text()
    << "\n- OPENBLAS_NUM_THREADS=" << kerf_measure::environment("OPENBLAS_NUM_THREADS")
    << ", OMP_NUM_THREADS=" << kerf_measure::environment("OMP_NUM_THREADS") << "\n- beam 0.03 x 0.06 x 0.2 m, cells (1,2,6)k, clamped at z = 0, "
    << "gravity; best of >= 3 runs and >= 0.5 s per measurement\n\n";
  s << "### Element stiffness and assembly\n\n"
    << "| element | cells | tets | DOFs | stored entries | stiffness blocks/s | assembled blocks/s | pattern + scatter map (s) |\n"
    << "|---|---|---:|---:|---:|---:|---:|---:|\n";
  for (const Measurement& m : rows) {
    std::snprintf(line, sizeof line, "| %s | %s | %ld | %d | %ld | %.3g M | %.3g M | %.4f |\n", m.element.c_str(),
                  m.cells.c_str(), static_cast<long>(m.tets), m.dofs, static_cast<long>(m.stored_entries),
                  m.blocks_per_second / 1e6, m.assembled_blocks_per_second / 1e6, m.pattern_seconds);
    s << line;
  }
  s << "\n### Solve (seconds)\n\n"
    << "| element | cells | DOFs | CHOLMOD analyse | factorise | solve | CHOLMOD total | pattern+assembly+CHOLMOD "
    << "| CG-Jacobi 1e-8 (iterations) | CG-IChol 1e-8 (iterations) | CalculiX run |\n"
    << "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const Measurement& m : rows) {
    const std::string ccx_text = m.ccx_seconds < 0 ? std::string("-") : std::to_string(m.ccx_seconds).substr(0, 6);
    std::snprintf(line, sizeof line, "| %s | %s | %d | %.4f | %.4f | %.4f | %.4f | %.4f | %.3f (%d) | %.3f (%d) | %s |\n",
                  m.element.c_str(), m.cells.c_str(), m.dofs, m.analyze_seconds, m.factorize_seconds, m.solve_seconds,
                  m.analyze_seconds + m.factorize_seconds + m.solve_seconds, m.pipeline_seconds, m.cg_jacobi_seconds,
                  m.cg_jacobi_iterations, m.cg_ichol_seconds, m.cg_ichol_iterations, ccx_text.c_str());
    s << line;
  }
  s << "\n### CHOLMOD's fill-reducing orderings (best of 2)\n\n"
    << "\"cholmod\": CHOLMOD's own choice on the graph of the unknowns; the others on the graph of the nodes "
    << "(kerf::unknown_blocks). Flops and factor entries are CHOLMOD's counts for the ordering.\n\n"
    << "| element | cells | DOFs | ordering | graph vertices | analyse (s) | factorise (s) | analyse + factorise (s) "
    << "| factor entries | flops | Gflop/s |\n"
    << "|---|---|---:|---|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const Measurement& m : rows)
    for (const OrderingTiming& t : m.orderings) {
      std::snprintf(line, sizeof line, "| %s | %s | %d | %s | %d | %.4f | %.4f | %.4f | %.3g | %.3g | %.1f |\n", m.element.c_str(),
                    m.cells.c_str(), m.dofs, t.ordering.c_str(), t.ordered_vertices, t.analyze_seconds, t.factorize_seconds,
                    t.analyze_seconds + t.factorize_seconds, t.factor_entries, t.factorisation_flops,
                    t.factorisation_flops / t.factorize_seconds * 1e-9);
      s << line;
    }
  s << "\nCalculiX: " << (ccx.empty() ? std::string("not found at configure time") : ccx + " (static deck, whole process)")
    << "\n";
  return s.str();
}

} // namespace bench

/// `bench_linear_fem [--quick] [--out FILE.md]`: see the header comment.
int main(int argc, char** argv) {
  try {
    const std::optional<kerf_measure::RunOptions> options =
        kerf_measure::parse_run_options(argc, argv, "bench_linear_fem [--quick] [--out FILE.md]", {});
    if (!options) return 2;
    const bool quick = options->quick;
    const std::filesystem::path& out = options->out;
    const std::string ccx = KERF_CCX;
    const std::filesystem::path work = std::filesystem::temp_directory_path() / "kerf_bench_calculix";
    // (order, k): Tet4 up to about 110k DOFs, Tet10 up to about 110k DOFs (target 2).
    const std::vector<std::pair<int, int>> meshes =
        quick ? std::vector<std::pair<int, int>>{{1, 2}, {2, 1}}
              : std::vector<std::pair<int, int>>{{1, 4}, {1, 8}, {1, 14}, {2, 2}, {2, 4}, {2, 7}};
    std::vector<bench::Measurement> rows;
    for (const auto& [order, k] : meshes) {
      rows.push_back(bench::measure(k, order, ccx, work));
      std::cerr << "measured " << rows.back().element << " " << rows.back().cells << '\n';
    }
    std::filesystem::remove_all(work);
    const std::string text = bench::report(rows, ccx);
    std::cout << text;
    if (!out.empty()) std::ofstream(out) << text;
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "bench_linear_fem: " << e.what() << '\n';
    return 3;
  }
}
