/* Kerf benchmark: chapter 3's shifted-Heaviside XFEM against the uncut mesh, on one core.

   Build and run:   cmake --build --preset release --target bench
                    (runs bench_xfem with OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1)
   By hand:         OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 bench_xfem --out bench_xfem.md
                    bench_xfem --quick      (a small mesh, a few seconds: does it run?)

   On the beam of chapter 3 (0.03 x 0.06 x 0.2 m, clamped at z = 0, top edge x = 0 pulled up
   0.02 m) with Schoch et al.'s half-depth cut [0, 0.015] x [0, 0.06] x {0.1}, it measures
     (a) the cut processing, make_enrichment (level set, minimum-fraction rule, classification,
         clipping of every tet the plane crosses, the enrichment rules), per tet crossed;
     (b) one assembly of the linear stiffness into the fixed CSR pattern: XfemModel's K^X
         (eqs. 60-63) against chapter 1's uncut K on the same mesh;
     (c) one factorisation and solve (CHOLMOD) of the enriched K_ff against the uncut K_ff;
     (d) one corotated assembly of forces and tangent at the linear solution: XfemModel against
         CorotationalModel on the same mesh (consistent tangent).
   Every number is the best of at least five runs and of at least a second of repeats. The
   report is a markdown table on stdout and, with --out, in a file. */

#include "kerf/corotation/corotational_model.hpp"
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/fem/assemble_stiffness.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/linear_material.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/node_region.hpp"
#include "kerf/solve/linear_solver.hpp"
#include "kerf/xfem/enrichment.hpp"
#include "kerf/xfem/xfem_model.hpp"
#include "measure.hpp"

#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace bench {

using kerf_measure::best_time;
constexpr kerf_measure::Repeats usual_repeats{5, 1.0, 20.0};

std::vector<int> nodes_in_box(const kerf::TetMesh& mesh, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  kerf::NodeRegion region;
  region.box_min = lo;
  region.box_max = hi;
  return kerf::nodes_in_region(mesh, region);
}

struct Times {
  double uncut = 0.0, xfem = 0.0;
};

std::string run(bool quick) {
  const Eigen::Vector3i cells = quick ? Eigen::Vector3i(3, 6, 19) : Eigen::Vector3i(9, 18, 53);
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {0.03, 0.06, 0.2}, cells);
  const kerf::LinearMaterial material;
  const kerf::RectangleCut cut({0, 0, 0.1}, {0.015, 0, 0}, {0, 0.06, 0});
  const std::vector<kerf::DirichletNodes> conditions{{nodes_in_box(mesh, {0, 0, 0}, {0.03, 0.06, 0}), {0, 0, 0}},
                                                     {nodes_in_box(mesh, {0, 0, 0.2}, {0, 0.06, 0.2}), {0, 0, 0.02}}};
  double sink = 0.0;

  // (a) cut processing.
  kerf::Enrichment enrichment;
  const double enrich_s = best_time([&] { enrichment = kerf::make_enrichment(mesh, cut); }, usual_repeats);
  int crossed = 0;
  for (auto side : enrichment.tet_side) crossed += (side == kerf::TetSide::cut || side == kerf::TetSide::beyond) ? 1 : 0;
  const kerf::XfemModel model(mesh, material, enrichment);
  const kerf::DofMap xdofs = kerf::make_xfem_dof_map(model, conditions);
  const kerf::DofMap dofs = kerf::make_dof_map(mesh.num_nodes(), conditions);

  // (b) linear assembly.
  kerf::SparseAssembler xassembler(model.assembly_slots(), xdofs), assembler(mesh.tets, dofs);
  Eigen::VectorXd xrhs(xdofs.num_free), rhs(dofs.num_free);
  Times assemble;
  assemble.uncut = best_time([&] {
    assembler.set_zero();
    rhs.setZero();
    kerf::assemble_linear_stiffness(mesh, material, assembler, rhs);
  }, usual_repeats);
  assemble.xfem = best_time([&] {
    xassembler.set_zero();
    xrhs.setZero();
    model.assemble_linear_stiffness(xassembler, xrhs);
  }, usual_repeats);

  // (c) factorise and solve.
  Times solve;
  Eigen::VectorXd u(dofs.num_free), xu(xdofs.num_free);
  solve.uncut = best_time([&] {
    auto solver = kerf::make_linear_solver({});
    solver->analyze_pattern(assembler.matrix());
    solver->factorize(assembler.matrix());
    solver->solve(rhs, u);
  }, usual_repeats);
  solve.xfem = best_time([&] {
    auto solver = kerf::make_linear_solver({});
    solver->analyze_pattern(xassembler.matrix());
    solver->factorize(xassembler.matrix());
    solver->solve(xrhs, xu);
  }, usual_repeats);

  // (d) corotated assembly at the linear solutions.
  const kerf::CorotationalModel corot(mesh, material);
  const Eigen::VectorXd u_full = dofs.expand(u), xu_full = xdofs.expand(xu);
  Eigen::VectorXd f_int, f_int_x;
  Times corotated;
  corotated.uncut = best_time([&] {
    assembler.set_zero();
    rhs.setZero();
    corot.assemble(u_full, kerf::RotationMethod::automatic, kerf::CorotationalTangent::consistent, f_int, &assembler, &rhs);
  }, usual_repeats);
  corotated.xfem = best_time([&] {
    xassembler.set_zero();
    xrhs.setZero();
    model.assemble(xu_full, kerf::RotationMethod::automatic, kerf::CorotationalTangent::consistent, f_int_x, &xassembler, &xrhs);
  }, usual_repeats);
  sink += f_int.sum() + f_int_x.sum();

  int enriched_tets = 0;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) enriched_tets += model.has_enriched_corner(t) ? 1 : 0;
  std::ostringstream s;
  char line[512];
  s << "## bench_xfem\n\n- CPU: " << kerf_measure::cpu_model() << "\n- date: " << kerf_measure::now_text()
    << "\n- OPENBLAS_NUM_THREADS=" << kerf_measure::environment("OPENBLAS_NUM_THREADS")
    << ", OMP_NUM_THREADS=" << kerf_measure::environment("OMP_NUM_THREADS")
    << "\n- best of >= 5 runs and >= 1 s per measurement\n\n";
  std::snprintf(line, sizeof line,
                "Beam Tet4, cells %dx%dx%d, %lld tets, %lld nodes; cut [0, 0.015] x [0, 0.06] x {0.1}: %d tets crossed by the plane "
                "(%d cut, %d beyond the front), %lld enriched nodes, %d tets with an enriched corner; %d DOFs uncut, %d enriched.\n\n",
                cells[0], cells[1], cells[2], static_cast<long long>(mesh.num_tets()), static_cast<long long>(mesh.num_nodes()), crossed,
                enrichment.cut_tets, crossed - enrichment.cut_tets, static_cast<long long>(enrichment.num_enriched()), enriched_tets,
                dofs.num_free, xdofs.num_free);
  s << line;
  std::snprintf(line, sizeof line, "| step | uncut (ms) | XFEM (ms) | XFEM / uncut |\n|---|---:|---:|---:|\n"
                "| (a) make_enrichment | - | %.3f | %.2f us per tet crossed (%.3f us per tet of the mesh) |\n", 1e3 * enrich_s,
                1e6 * enrich_s / crossed, 1e6 * enrich_s / static_cast<double>(mesh.num_tets()));
  s << line;
  const auto row = [&](const char* name, const Times& t) {
    std::snprintf(line, sizeof line, "| %s | %.3f | %.3f | %.3f |\n", name, 1e3 * t.uncut, 1e3 * t.xfem, t.xfem / t.uncut);
    s << line;
  };
  row("(b) linear assembly of K_ff", assemble);
  row("(c) CHOLMOD analyse + factorise + solve", solve);
  row("(d) corotated forces + consistent tangent", corotated);
  s << "\nnonzeros of K_ff: uncut " << assembler.num_stored_entries() << ", enriched " << xassembler.num_stored_entries() << "\n";
  if (sink == 42.0) s << ' ';
  return s.str();
}

} // namespace bench

int main(int argc, char** argv) {
  const auto options = kerf_measure::parse_run_options(argc, argv, "bench_xfem [--quick] [--out FILE.md]", "");
  if (!options) return 2;
  try {
    const std::string text = bench::run(options->quick);
    std::cout << text;
    if (!options->out.empty()) std::ofstream(options->out) << text;
  } catch (const std::exception& e) {
    std::cerr << "bench_xfem: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
