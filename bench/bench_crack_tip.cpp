/* Kerf benchmark: chapter 5's branch enrichment against chapter 4's Heaviside-only enrichment on
   the same cut, on one core.

   Build and run:   cmake --build --preset release --target bench_crack_tip_run
                    (runs bench_crack_tip with OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1)
   By hand:         OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 bench_crack_tip --out bench_crack_tip.md
                    bench_crack_tip --quick      (the smallest mesh only: does it run?)

   On the beam of chapters 3-5 (0.03 x 0.06 x 0.2 m, clamped at z = 0, gravity along +x) with the
   half-depth cut [0, 0.0147] x [0, 0.06] x {0.1003} (chapter 3's place moved 0.6 mm in x, so that
   on these uniform meshes the front lies neither on a node layer nor in the cells' diagonal
   faces x = z), as a triangle surface overhanging the beam on three sides, it
   measures for Heaviside-only and for geometric branch enrichment (default radius):
     (a) the set-up: pieces, fronts, enrichment and the model with its quadrature points;
     (b) one assembly of the linear stiffness K_ff into its fixed CSR pattern;
     (c) one CHOLMOD analyse + factorise + solve of K_ff;
   with the unknowns, the branch nodes and the stored nonzeros. The branch tets are integrated
   with examples/05_paulus_study.cpp's cheaper rules (degree 3 on front sub-tets refined once,
   degree 3 elsewhere) and, on the smallest mesh, also with the model's defaults (the collapsed
   rule), whose set-up and assembly cost the table shows. Each time is the best of at least
   three runs (set-up: one run). */

#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/node_region.hpp"
#include "kerf/solve/linear_solver.hpp"
#include "kerf/xfem/crack_tip_body.hpp"
#include "measure.hpp"

#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace bench {

using kerf_measure::best_time;
constexpr kerf_measure::Repeats repeats{3, 0.5, 20.0};

struct Variant {
  const char* name;
  kerf::TipTreatment treatment;
  kerf::BranchRules rules;
};

std::string run(bool quick) {
  const std::vector<Eigen::Vector3i> meshes =
      quick ? std::vector<Eigen::Vector3i>{{3, 6, 19}} : std::vector<Eigen::Vector3i>{{3, 6, 19}, {5, 10, 31}, {7, 14, 41}};
  const kerf::BranchRules cheap{kerf::FrontRule::refined_subtets, 2, 3, 0};
  const std::vector<Variant> variants{{"Heaviside-only", kerf::TipTreatment::heaviside_only, {}},
                                      {"geometric branch, study rules", kerf::TipTreatment::geometric, cheap},
                                      {"geometric branch, default rules", kerf::TipTreatment::geometric, {}}};
  const kerf::LinearMaterial material;
  const kerf::TriangleSurface cut = kerf::rectangle_surface(kerf::RectangleCut({-0.01, -0.01, 0.1003}, {0.0247, 0, 0}, {0, 0.08, 0}));
  kerf::NodeRegion base;
  base.box_max = {0.03, 0.06, 0.0};

  std::ostringstream s;
  char line[512];
  s << "## bench_crack_tip\n\n- CPU: " << kerf_measure::cpu_model() << "\n- date: " << kerf_measure::now_text()
    << "\n- OPENBLAS_NUM_THREADS=" << kerf_measure::environment("OPENBLAS_NUM_THREADS")
    << ", OMP_NUM_THREADS=" << kerf_measure::environment("OMP_NUM_THREADS")
    << "\n- set-up: one run; assembly and solve: best of >= 3 runs and >= 0.5 s\n\n"
    << "| mesh | enrichment | unknowns | branch nodes | nonzeros of K_ff | set-up (ms) | assembly (ms) | solve (ms) |\n"
    << "|---|---|---:|---:|---:|---:|---:|---:|\n";
  double sink = 0.0;
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const Eigen::Vector3i& cells = meshes[m];
    const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {0.03, 0.06, 0.2}, cells);
    for (const Variant& v : variants) {
      // The default rules cost minutes per model beyond the smallest mesh: measured there only.
      if (v.treatment != kerf::TipTreatment::heaviside_only && v.rules.front_rule == kerf::FrontRule::collapsed && m > 0) continue;
      const auto start = kerf_measure::clock::now();
      const kerf::CrackTipBody body(mesh, {cut}, material, v.treatment, 0.0, v.rules);
      const double setup = std::chrono::duration<double>(kerf_measure::clock::now() - start).count();
      const kerf::DofMap dofs = kerf::make_cut_xfem_dof_map(body.model(), {{kerf::nodes_in_region(mesh, base), {0, 0, 0}}});
      kerf::SparseAssembler assembler(body.model().assembly_slots(), dofs);
      Eigen::VectorXd rhs(dofs.num_free), u(dofs.num_free);
      const double assemble = best_time([&] {
        assembler.set_zero();
        rhs.setZero();
        body.model().assemble_linear_stiffness(assembler, rhs);
      }, repeats);
      rhs += Eigen::VectorXd::Ones(dofs.num_free) * 1e-3; // any right-hand side: the cost does not depend on it
      const double solve = best_time([&] {
        auto solver = kerf::make_linear_solver({});
        solver->analyze_pattern(assembler.matrix());
        solver->factorize(assembler.matrix());
        solver->solve(rhs, u);
      }, repeats);
      sink += u.sum();
      const int branch = body.branch() ? body.branch()->num_branch_nodes() : 0;
      std::snprintf(line, sizeof line, "| %dx%dx%d (%lld tets) | %s | %d | %d | %lld | %.1f | %.2f | %.2f |\n", cells[0], cells[1], cells[2],
                    static_cast<long long>(mesh.num_tets()), v.name, dofs.num_free, branch,
                    static_cast<long long>(assembler.num_stored_entries()), 1e3 * setup, 1e3 * assemble, 1e3 * solve);
      s << line;
      std::cout << line << std::flush;
    }
  }
  if (sink == 42.0) s << ' ';
  return s.str();
}

} // namespace bench

int main(int argc, char** argv) {
  const auto options = kerf_measure::parse_run_options(argc, argv, "bench_crack_tip [--quick] [--out FILE.md]", "");
  if (!options) return 2;
  try {
    const std::string text = bench::run(options->quick);
    std::cout << '\n' << text;
    if (!options->out.empty()) std::ofstream(options->out) << text;
  } catch (const std::exception& e) {
    std::cerr << "bench_crack_tip: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
