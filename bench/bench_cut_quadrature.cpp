/* Kerf benchmark: chapter 4's triangle-mesh cuts, piece quadratures and Tet10 XFEM, on one core.

   Build and run:   cmake --build --preset release --target bench
                    (runs bench_cut_quadrature with OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1)
   By hand:         OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 bench_cut_quadrature --out bench_cut_quadrature.md
                    bench_cut_quadrature --quick      (small meshes, a few seconds: does it run?)

   On the beam of chapters 1-4 (0.03 x 0.06 x 0.2 m) it measures
     (a) cut processing of a triangle-mesh cut: the curved sheet z = 0.1 + 0.01 sin(pi y / 0.06)
         clean through the beam, as 2 x 8 x 24 and 2 x 32 x 96 triangles, on a Tet4 mesh:
         the AABB queries alone (which triangles meet each tet, exact test included) and the
         whole of cut_mesh_into_pieces (queries, splitting, gluing across faces), per tet the
         sheet meets, with the mesh's adjacency (tet_neighbours) made in the call and made once
         beforehand; beside it chapter 3's plane (make_enrichment) per tet it crosses;
     (b) the set-up of one rule (degree 2) for every piece of every completely cut tet, per
         cut tet, for each rule of piece_quadrature_rule.hpp;
     (c) one corotated assembly (forces and consistent tangent) of the Tet10 beam cut by the
         sheet, CutXfemModel with the "exact" rule, against chapter 2's CorotationalModel on
         the same mesh uncut.
   Every number is the best of at least five runs and of at least a second of repeats. The
   report is a markdown table on stdout and, with --out, in a file. */

#include "kerf/corotation/corotational_model.hpp"
#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/height_field_surface.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/linear_material.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"
#include "kerf/quadrature/piece_quadrature_rule.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"
#include "kerf/xfem/enrichment.hpp"
#include "kerf/xfem/surface_enrichment.hpp"
#include "measure.hpp"

#include <cmath>
#include <memory>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace bench {

using kerf_measure::best_time;
constexpr kerf_measure::Repeats usual_repeats{5, 1.0, 20.0};

// The sheet, clean through the beam's cross-section, with nx by ny cells of two triangles.
kerf::TriangleSurface sheet(int nx, int ny) {
  const kerf::HeightField h = [](double, double y) { return 0.01 * std::sin(M_PI * y / 0.06); };
  return kerf::height_field_surface(h, 0.1, {-0.005, -0.005}, {0.035, 0.065}, {nx, ny});
}

std::string run(bool quick) {
  std::ostringstream s;
  char line[512];
  double sink = 0.0;
  s << "## bench_cut_quadrature\n\n- CPU: " << kerf_measure::cpu_model() << "\n- date: " << kerf_measure::now_text()
    << "\n- OPENBLAS_NUM_THREADS=" << kerf_measure::environment("OPENBLAS_NUM_THREADS")
    << ", OMP_NUM_THREADS=" << kerf_measure::environment("OMP_NUM_THREADS")
    << "\n- best of >= 5 runs and >= 1 s per measurement\n\n";

  // (a) cut processing.
  const Eigen::Vector3i cells = quick ? Eigen::Vector3i(3, 6, 19) : Eigen::Vector3i(9, 18, 53);
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {0.03, 0.06, 0.2}, cells);
  std::snprintf(line, sizeof line, "### (a) cut processing, Tet4 beam %dx%dx%d cells, %lld tets\n\n", cells[0], cells[1], cells[2],
                static_cast<long long>(mesh.num_tets()));
  s << line << "| cut | triangles | tets met | AABB queries (us per tet met) | whole cut processing (us per tet met) | "
               "the same, mesh adjacency made once (us per tet met) | completely cut | partially cut |\n"
               "|---|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const Eigen::Vector2i& grid : {Eigen::Vector2i(8, 24), Eigen::Vector2i(32, 96)}) {
    const kerf::CutSurfaces cuts({sheet(grid[0], grid[1])});
    int met = 0;
    const double query_s = best_time([&] {
      met = 0;
      for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) met += cuts.triangles_meeting_tet(kerf::tet_corners(mesh, t)).empty() ? 0 : 1;
    }, usual_repeats);
    kerf::MeshPieces pieces;
    const double cut_s = best_time([&] { pieces = kerf::cut_mesh_into_pieces(mesh, cuts); }, usual_repeats);
    // The mesh's adjacency made once (as a cut that grows step by step would keep it).
    const auto neighbours = std::make_shared<const kerf::TetNeighbours>(kerf::tet_neighbours(mesh));
    const double cut_kept_s = best_time([&] { pieces = kerf::cut_mesh_into_pieces(mesh, cuts, neighbours); }, usual_repeats);
    std::snprintf(line, sizeof line, "| sine sheet | %lld | %d | %.2f | %.2f | %.2f | %d | %d |\n", static_cast<long long>(cuts.num_triangles()),
                  met, 1e6 * query_s / met, 1e6 * cut_s / met, 1e6 * cut_kept_s / met, pieces.count(kerf::SurfaceCutState::completely_cut),
                  pieces.count(kerf::SurfaceCutState::partially_cut));
    s << line;
  }
  {
    const kerf::RectangleCut plane({-1.0, -1.0, 0.1}, {3.0, 0.0, 0.0}, {0.0, 3.0, 0.0});
    kerf::Enrichment enrichment;
    const double plane_s = best_time([&] { enrichment = kerf::make_enrichment(mesh, plane); }, usual_repeats);
    std::snprintf(line, sizeof line, "| chapter 3's plane z = 0.1 (make_enrichment) | - | %d | - | %.2f | - | %d | - |\n\n", enrichment.cut_tets,
                  1e6 * plane_s / enrichment.cut_tets, enrichment.cut_tets);
    s << line;
  }

  // (b) rule set-up per cut tet.
  {
    const kerf::CutSurfaces cuts({sheet(8, 24)});
    const kerf::MeshPieces pieces = kerf::cut_mesh_into_pieces(mesh, cuts);
    int cut = 0;
    for (const kerf::TetPieces& tp : pieces.tets) cut += tp.num_pieces() > 1 ? 1 : 0;
    s << "### (b) rule set-up, degree 2, every piece of the " << cut << " completely cut tets of (a)'s coarser sheet\n\n"
      << "| rule | us per cut tet | points per cut tet |\n|---|---:|---:|\n";
    for (const kerf::QuadratureRuleKind kind :
         {kerf::QuadratureRuleKind::volume_ratio, kerf::QuadratureRuleKind::subtets, kerf::QuadratureRuleKind::exact,
          kerf::QuadratureRuleKind::moment_fitting, kerf::QuadratureRuleKind::lattice, kerf::QuadratureRuleKind::regular}) {
      long long points = 0;
      const double rule_s = best_time([&] {
        points = 0;
        for (std::size_t e = 0; e < pieces.tets.size(); ++e) {
          const kerf::TetPieces& tp = pieces.tets[e];
          if (tp.num_pieces() < 2) continue;
          const Eigen::Matrix<double, 4, 3> X = kerf::tet_corners(mesh, pieces.entry_tet[e]);
          for (int p = 0; p < tp.num_pieces(); ++p) {
            const kerf::PieceQuadratureRule rule = kerf::piece_quadrature_rule(kind, X, tp.triangles, tp, p, {});
            points += kerf::count_points(rule);
          }
        }
      }, quick ? kerf_measure::Repeats{1, 0.0, 5.0} : usual_repeats);
      std::snprintf(line, sizeof line, "| %s | %.1f | %.1f |\n", kerf::to_string(kind), 1e6 * rule_s / cut,
                    static_cast<double>(points) / cut);
      s << line;
    }
    s << '\n';
  }

  // (c) corotated Tet10 assembly, cut against uncut.
  {
    const Eigen::Vector3i cells10 = quick ? Eigen::Vector3i(2, 4, 10) : Eigen::Vector3i(3, 6, 19);
    const kerf::TetMesh mesh10 = kerf::tet10_from_tet4(kerf::make_box_mesh({0, 0, 0}, {0.03, 0.06, 0.2}, cells10));
    const kerf::LinearMaterial material;
    const kerf::CutSurfaces cuts({sheet(8, 24)});
    const kerf::MeshPieces pieces = kerf::cut_mesh_into_pieces(mesh10, cuts);
    const kerf::SurfaceEnrichment enrichment = kerf::make_surface_enrichment(mesh10, pieces);
    const kerf::PieceRuleFunction exact = [](const Eigen::Matrix<double, 4, 3>& X, const kerf::TetPieces& tp, int p, int degree) {
      kerf::PieceRuleOptions options;
      options.degree = degree;
      return kerf::piece_quadrature_rule(kerf::QuadratureRuleKind::exact, X, tp.triangles, tp, p, options);
    };
    const kerf::CutXfemModel model(mesh10, material, pieces, enrichment, exact);
    const kerf::CorotationalModel uncut(mesh10, material);
    const kerf::DofMap dofs = kerf::make_dof_map(mesh10.num_nodes(), {});
    const kerf::DofMap xdofs = kerf::make_dof_map(model.num_dof_nodes(), {});
    kerf::SparseAssembler assembler(mesh10.tets, dofs), xassembler(model.assembly_slots(), xdofs);
    Eigen::VectorXd rhs(dofs.num_free), xrhs(xdofs.num_free), f, xf;
    // A small smooth displacement, so that every rotation is a real one.
    Eigen::VectorXd u(3 * mesh10.num_nodes());
    for (Eigen::Index v = 0; v < mesh10.num_nodes(); ++v)
      u.segment<3>(3 * v) = 0.01 * Eigen::Vector3d(std::sin(mesh10.nodes(v, 2) * 10.0), 0.0, 0.1 * mesh10.nodes(v, 0));
    Eigen::VectorXd xu = Eigen::VectorXd::Zero(3 * model.num_dof_nodes());
    xu.head(u.size()) = u;
    const double uncut_s = best_time([&] {
      assembler.set_zero();
      rhs.setZero();
      uncut.assemble(u, kerf::RotationMethod::automatic, kerf::CorotationalTangent::consistent, f, &assembler, &rhs);
    }, usual_repeats);
    const double cut_s = best_time([&] {
      xassembler.set_zero();
      xrhs.setZero();
      model.assemble(xu, kerf::RotationMethod::automatic, kerf::CorotationalTangent::consistent, xf, &xassembler, &xrhs);
    }, usual_repeats);
    sink += f.sum() + xf.sum();
    int split = 0;
    for (Eigen::Index t = 0; t < mesh10.num_tets(); ++t) split += model.integrated_by_pieces(t) ? 1 : 0;
    std::snprintf(line, sizeof line,
                  "### (c) corotated Tet10 assembly, beam %dx%dx%d cells, %lld tets (%d integrated piece by piece, %lld points on "
                  "their pieces)\n\n| model | ms per assembly |\n|---|---:|\n| uncut (CorotationalModel) | %.3f |\n"
                  "| cut by the sheet (CutXfemModel, rule exact) | %.3f |\n| ratio | %.2f |\n",
                  cells10[0], cells10[1], cells10[2], static_cast<long long>(mesh10.num_tets()), split,
                  static_cast<long long>(model.num_piece_points()), 1e3 * uncut_s, 1e3 * cut_s, cut_s / uncut_s);
    s << line;
  }
  if (sink == 42.0) s << ' ';
  return s.str();
}

} // namespace bench

int main(int argc, char** argv) {
  const auto options = kerf_measure::parse_run_options(argc, argv, "bench_cut_quadrature [--quick] [--out FILE.md]", "");
  if (!options) return 2;
  try {
    const std::string text = bench::run(options->quick);
    std::cout << text;
    if (!options->out.empty()) std::ofstream(options->out) << text;
  } catch (const std::exception& e) {
    std::cerr << "bench_cut_quadrature: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
