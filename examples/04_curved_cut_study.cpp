/* Kerf, chapter 4 study: the beam cut clean through by a curved and by a kinked surface. How
   accurate is XFEM on box meshes that ignore the cut, per unknown and per second, against a
   mesh that follows the cut, and which quadrature rule is worth its cost?

   Build:   cmake --preset release && cmake --build --preset release --target 04_curved_cut_study

   Sample runs:
     04_curved_cut_study --quick --out output/curved_cut_study_quick
     04_curved_cut_study --out figures/04_cut_quadrature
     04_curved_cut_study --only ridge --out figures/04_cut_quadrature     (one cut: dome or ridge)

   Description: the beam of chapters 1-3 (0.03 x 0.06 x 0.2 m, E = 300 kPa, nu = 0.35,
   rho = 1070 kg/m^3) is cut through its whole cross-section near mid-height by the graph
   z = z_c + h(x, y), z_c = 0.1 m, A = 10 mm:
     dome   h = A (1 - s^2)(1 - t^2),  s = (x - 0.015) / 0.015,  t = (y - 0.03) / 0.03
            (smooth; flat, h = 0, where it meets the beam's sides);
     ridge  h = A (1 - |2 x / 0.03 - 1|)   (a kink along x = 0.015, the cut's normal turning by
            2 atan(2 A / 0.015) = 106 degrees across it).
   The two parts are held apart: the base z = 0 is clamped, the top z = 0.2 is moved by
   (2, 0, -1) mm, and gravity pulls along +x (chapter 4's CalculiX test, on finer meshes). The
   cut as every method sees it is ONE triangle mesh: the graph's piecewise-linear interpolant on
   the reference mesh's x-y grid (10 x 20 cells, 400 triangles), extended by one cell beyond the
   beam's sides so that its boundary lies outside the body. Its ridge's kink lies on that grid,
   so the triangulated ridge is the ridge.

   Methods, each a ladder of meshes, each solved with linear FEM:
     reference      Tet10 on split_box_along_height_field(10 x 20 x 50): the box mesh with a node
                    layer moved onto the triangulated cut and opened along it; checked against
                    the next coarser conforming Tet10 mesh, and CalculiX solves a smaller one;
     conforming     Tet4 on split_box_along_height_field meshes with even nx (their layer follows
                    the triangulated cut where their grid holds its vertices, and its own
                    interpolant of it in between: for the ridge exactly, for the dome not);
     conforming10   the same with Tet10;
     xfem4          Tet4 XFEM (chapter 4's CutXfemModel) on box meshes with odd cell counts,
                    which put the kink and the cut's reference plane through cell middles,
                    the cut given as the triangle mesh, with each Tet4 rule;
     xfem10         Tet10 XFEM on the same meshes, with every rule ("volume_ratio" too, which
                    the scene refuses for Tet10: here to show what it costs).
   The error is ||u_h - u_ref||_L2 / ||u_ref||_L2 over the body, by the reference's own degree-2
   points (4 in each reference tet, none on the cut). The wall time of a run is everything it
   takes from the geometry to the displacements: XFEM's cut processing (AABB tree, pieces,
   enrichment), the piece rules and the model, the loads, assembly and the factorisation; the
   conforming runs' meshing, assembly and factorisation. The program writes, into the --out
   folder:
     curved_ladder.csv     one row per (cut, method, rule, mesh): unknowns, the wall time and its
                           set-up part (cut processing, rules, model), the relative L2 error,
                           split tets, quadrature points on their pieces, enrichments, the
                           smallest piece's volume fraction, and
                           why a run failed (a rule that leaves the stiffness singular);
     curved_reference.csv  the references: unknowns, time, the next coarser Tet10's error
                           against it, and CalculiX's agreement with Kerf on a conforming Tet10
                           mesh of 4 x 8 x 20 cells (its maximum nodal difference over the
                           largest displacement, against ccx's matrices solved in double and
                           against ccx's own static solve);
     curved_factor.csv     for each Tet10 XFEM run, the unknowns the conforming Tet10 ladder
                           needs for the same error (log-log interpolation) and their ratio.
   --quick runs every code path on tiny meshes in a few seconds; it is a test.

   Read chapter 4 first. */

#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/height_field_surface.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/cut/split_box_along_height_field.hpp"
#include "kerf/fem/assemble_loads.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/evaluate_displacement.hpp"
#include "kerf/fem/linear_material.hpp"
#include "kerf/fem/solve_linear_static.hpp"
#include "kerf/fem/tet_quadrature.hpp"
#include "kerf/io/calculix_deck.hpp"
#include "kerf/io/probes_csv.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/node_region.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"
#include "kerf/quadrature/piece_quadrature_rule.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"
#include "kerf/xfem/surface_enrichment.hpp"
#include "measure.hpp" // bench/measure.hpp: the command line and the clock shared with the benchmarks
#include "reference_field.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace curved_cut_study {

using kerf::QuadratureRuleKind;
using kerf_measure::clock;

double seconds_since(clock::time_point start) { return std::chrono::duration<double>(clock::now() - start).count(); }
const double not_a_number = std::numeric_limits<double>::quiet_NaN();

const Eigen::Vector3d beam_min(0.0, 0.0, 0.0);
const Eigen::Vector3d beam_max(0.03, 0.06, 0.2);
const double cut_height = 0.1;  ///< z_c (m)
const double amplitude = 0.01;  ///< A (m)
const kerf::LinearMaterial material{};
const Eigen::Vector3d gravity(9.81, 0.0, 0.0);
const Eigen::Vector3d top_motion(0.002, 0.0, -0.001);

std::string cells_text(const Eigen::Vector3i& c) { return std::to_string(c[0]) + "x" + std::to_string(c[1]) + "x" + std::to_string(c[2]); }

// @sect3{The two cuts, and the one triangle mesh every method is given}

/// The analytic height h(x, y) above z_c of the cut named `name`.
kerf::HeightField analytic_height(const std::string& name) {
  if (name == "dome")
    return [](double x, double y) {
      const double s = (x - 0.015) / 0.015, t = (y - 0.03) / 0.03;
      return amplitude * (1.0 - s * s) * (1.0 - t * t);
    };
  if (name == "ridge") return [](double x, double) { return amplitude * (1.0 - std::abs(2.0 * x / 0.03 - 1.0)); };
  throw std::invalid_argument("unknown cut " + name);
}

/// The piecewise-linear interpolant of `h` on an nx by ny grid over the beam's cross-section,
/// with height_field_surface()'s triangles: each cell split along its diagonal from (i, j) to
/// (i + 1, j + 1). Outside the cross-section it takes the value at the nearest point of it, so
/// that the surface extended beyond the sides is the same graph inside.
kerf::HeightField interpolated_height(const kerf::HeightField& h, int nx, int ny) {
  const double dx = beam_max[0] / nx, dy = beam_max[1] / ny;
  return [h, nx, ny, dx, dy](double x, double y) {
    const double u = std::clamp(x, 0.0, beam_max[0]) / dx, v = std::clamp(y, 0.0, beam_max[1]) / dy;
    const int i = std::clamp(static_cast<int>(std::floor(u)), 0, nx - 1), j = std::clamp(static_cast<int>(std::floor(v)), 0, ny - 1);
    const double a = u - i, b = v - j; // local coordinates in the cell, in [0, 1]
    const auto at = [&](int di, int dj) { return h((i + di) * dx, (j + dj) * dy); };
    // Below the diagonal (a >= b): the triangle (i,j) (i+1,j) (i+1,j+1); above it: (i,j) (i+1,j+1) (i,j+1).
    if (a >= b) return (1.0 - a) * at(0, 0) + (a - b) * at(1, 0) + b * at(1, 1);
    return (1.0 - b) * at(0, 0) + (b - a) * at(0, 1) + a * at(1, 1);
  };
}

/// The cut as XFEM is given it: the graph of `h` triangulated on the reference's grid, one
/// cell wider on every side of the beam.
kerf::TriangleSurface extended_cut_surface(const kerf::HeightField& h, const Eigen::Vector2i& grid) {
  const double dx = beam_max[0] / grid[0], dy = beam_max[1] / grid[1];
  return kerf::height_field_surface(h, cut_height, Eigen::Vector2d(-dx, -dy), Eigen::Vector2d(beam_max[0] + dx, beam_max[1] + dy),
                                    Eigen::Vector2i(grid[0] + 2, grid[1] + 2));
}

// @sect3{Boundary conditions and one solve}

std::vector<kerf::DirichletNodes> conditions(const kerf::TetMesh& mesh) {
  kerf::NodeRegion base, top;
  base.box_min = beam_min;
  base.box_max = Eigen::Vector3d(beam_max[0], beam_max[1], 0.0);
  top.box_min = Eigen::Vector3d(0.0, 0.0, beam_max[2]);
  top.box_max = beam_max;
  return {{kerf::nodes_in_region(mesh, base), Eigen::Vector3d::Zero()}, {kerf::nodes_in_region(mesh, top), top_motion}};
}

/// One run of one method on one mesh.
struct Run {
  std::string cut, method, rule;
  Eigen::Vector3i cells{0, 0, 0};
  int dofs = 0;                  ///< free unknowns
  double seconds = not_a_number; ///< geometry to displacements
  double setup_seconds = 0.0;    ///< XFEM: cut processing, rules and model; conforming: meshing
  double error = not_a_number;   ///< relative L2 error against the reference
  int split_tets = 0;            ///< XFEM: tets integrated piece by piece
  Eigen::Index piece_points = 0; ///< XFEM: quadrature points on their pieces
  double smallest_fraction = not_a_number; ///< XFEM: the smallest V_piece / V_tet of a split tet
  int enrichments = 0;           ///< XFEM: enrichments; conforming: duplicated nodes
  std::string failure;           ///< why the run gave no solution (empty: it did)
};

Run make_run(const std::string& cut, const std::string& method, const std::string& rule, const Eigen::Vector3i& cells) {
  Run r;
  r.cut = cut;
  r.method = method;
  r.rule = rule;
  r.cells = cells;
  return r;
}

/// A conforming mesh opened along the cut `h` (the reference's interpolant, sampled again at
/// this mesh's grid by split_box_along_height_field).
kerf::HeightFieldSplitMesh conforming_mesh(const kerf::HeightField& h, const Eigen::Vector3i& cells, int order) {
  return kerf::split_box_along_height_field(beam_min, beam_max, cells, cut_height, h, order);
}

Eigen::VectorXd solve_conforming(const kerf::TetMesh& mesh, int& dofs_out) {
  const kerf::DofMap dofs = kerf::make_dof_map(mesh.num_nodes(), conditions(mesh));
  dofs_out = dofs.num_free;
  return kerf::solve_linear_static(mesh, material, dofs, kerf::assemble_gravity(mesh, material.density, gravity), kerf::SolverSettings{});
}

// @sect3{The error measure}

using study::ReferenceField;   // the reference at its own degree-2 points (reference_field.hpp)
using study::sample_reference;

/// The relative L2 error of values at the reference's points, refusing points outside a mesh.
double relative_l2(const ReferenceField& ref, const Eigen::MatrixXd& values, Eigen::Index outside) {
  if (outside > 0) throw std::runtime_error(std::to_string(outside) + " reference points outside a mesh");
  return study::relative_l2(ref, values);
}

/// A conforming solution at the reference's points: in the tet that holds each. Where this
/// mesh's layer and the reference's differ (the dome between this grid's nodes), a point of the
/// thin sliver between them takes the other part's value: the geometric error of meshing a
/// curved cut with flat faces, counted as it should be.
double conforming_error(const ReferenceField& ref, const kerf::TetMesh& mesh, const Eigen::VectorXd& u) {
  Eigen::Index outside = 0;
  const Eigen::MatrixXd values = kerf::evaluate_displacement_at(mesh, u, ref.points, outside);
  return relative_l2(ref, values, outside);
}

// @sect3{XFEM on box meshes that ignore the cut}

/// The rule function a CutXfemModel takes, for one kind.
kerf::PieceRuleFunction rule_of(QuadratureRuleKind kind) {
  return [kind](const Eigen::Matrix<double, 4, 3>& X, const kerf::TetPieces& pieces, int piece, int degree) {
    kerf::PieceRuleOptions options;
    options.degree = degree;
    return kerf::piece_quadrature_rule(kind, X, pieces.triangles, pieces, piece, options);
  };
}

/// Cut processing, rules, model, loads and the solve, all inside the clock; then the error.
Run run_xfem(const std::string& cut, const kerf::TriangleSurface& surface, const Eigen::Vector3i& cells, int order,
             QuadratureRuleKind kind, const ReferenceField& ref) {
  Run run = make_run(cut, order == 1 ? "xfem4" : "xfem10", kerf::to_string(kind), cells);
  kerf::TetMesh mesh = kerf::make_box_mesh(beam_min, beam_max, cells);
  if (order == 2) mesh = kerf::tet10_from_tet4(mesh);
  const auto start = clock::now();
  const kerf::CutSurfaces cuts({surface});
  const kerf::MeshPieces pieces = kerf::cut_mesh_into_pieces(mesh, cuts);
  const kerf::SurfaceEnrichment enrichment = kerf::make_surface_enrichment(mesh, pieces);
  const kerf::CutXfemModel model(mesh, material, pieces, enrichment, rule_of(kind));
  run.setup_seconds = seconds_since(start);
  const kerf::DofMap dofs = kerf::make_cut_xfem_dof_map(model, conditions(mesh));
  run.dofs = dofs.num_free;
  run.piece_points = model.num_piece_points();
  run.enrichments = static_cast<int>(enrichment.num_enrichments());
  run.smallest_fraction = 1.0;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    if (!model.integrated_by_pieces(t)) continue;
    ++run.split_tets;
    const kerf::TetPieces& tp = pieces.tets[static_cast<std::size_t>(pieces.entry[static_cast<std::size_t>(t)])];
    for (const kerf::TetPiece& piece : tp.pieces) run.smallest_fraction = std::min(run.smallest_fraction, piece.volume / tp.volume);
  }
  Eigen::VectorXd u;
  try {
    u = kerf::solve_linear_cut_xfem(model, dofs, model.gravity_load(material.density, gravity), kerf::SolverSettings{});
  } catch (const std::runtime_error& error) {
    // A rule can leave the stiffness singular or indefinite: the lattice puts no point in a
    // piece smaller than its sub-tets, so nothing holds that piece's enrichments. A result,
    // recorded with the statistics above.
    run.failure = error.what();
    std::replace(run.failure.begin(), run.failure.end(), '"', '\'');
    return run;
  }
  run.seconds = seconds_since(start);
  Eigen::Index outside = 0;
  const Eigen::MatrixXd values = kerf::evaluate_tet_field_at(
      mesh, [&](Eigen::Index t, const Eigen::Vector3d& x) { return model.displacement_at(u, t, x); }, ref.points, outside);
  run.error = relative_l2(ref, values, outside);
  return run;
}

// @sect3{The ladders}

struct Sizes {
  Eigen::Vector3i reference;       ///< conforming Tet10, its x-y grid the cut's triangulation
  Eigen::Vector3i reference_check; ///< the next coarser conforming Tet10: the reference's own error
  Eigen::Vector3i calculix;        ///< the conforming Tet10 mesh CalculiX solves too
  std::vector<Eigen::Vector3i> conforming, conforming10, xfem4, xfem10;
  std::vector<QuadratureRuleKind> rules4, rules10;
  std::vector<Eigen::Vector3i> all_rules10; ///< the Tet10 XFEM meshes every rule runs on (the rest: subtets only)
};

Sizes study_sizes(bool quick) {
  Sizes s;
  using K = QuadratureRuleKind;
  s.rules4 = {K::subtets, K::volume_ratio, K::exact};
  s.rules10 = {K::subtets, K::exact, K::moment_fitting, K::lattice, K::volume_ratio};
  if (quick) {
    s.reference = {4, 4, 10};
    s.reference_check = {2, 2, 6};
    s.calculix = {2, 2, 4};
    s.conforming = {{2, 2, 4}};
    s.conforming10 = {{2, 2, 4}};
    s.xfem4 = {{1, 2, 5}, {3, 2, 7}};
    s.xfem10 = {{1, 2, 5}};
    s.all_rules10 = {{1, 2, 5}};
  } else {
    s.reference = {10, 20, 50};
    s.reference_check = {8, 16, 40};
    s.calculix = {4, 8, 20};
    s.conforming = {{2, 2, 4}, {2, 4, 10}, {4, 6, 16}, {4, 8, 20}, {6, 12, 30}, {8, 16, 40}, {10, 20, 50}};
    s.conforming10 = {{2, 2, 4}, {2, 4, 10}, {4, 6, 16}, {4, 8, 20}, {6, 12, 30}, {8, 16, 40}};
    s.xfem4 = {{1, 2, 5}, {3, 4, 11}, {3, 6, 19}, {5, 10, 31}, {7, 14, 41}, {9, 18, 53}};
    s.xfem10 = {{1, 2, 5}, {3, 4, 11}, {3, 6, 19}, {5, 10, 31}, {7, 14, 41}};
    s.all_rules10 = {{1, 2, 5}, {3, 4, 11}, {3, 6, 19}, {5, 10, 31}};
  }
  return s;
}

const char* const ladder_header =
    "cut,method,rule,cells,dofs,seconds,setup_seconds,rel_l2_error,split_tets,piece_points,enrichments,smallest_fraction,failure\n";

void write_row(std::ofstream& csv, const Run& r) {
  csv << r.cut << ',' << r.method << ',' << r.rule << ',' << cells_text(r.cells) << ',' << r.dofs << ',' << r.seconds << ','
      << r.setup_seconds << ',' << r.error << ',' << r.split_tets << ',' << r.piece_points << ',' << r.enrichments << ','
      << r.smallest_fraction << ",\"" << r.failure << "\"\n";
  std::printf("%-6s %-13s %-15s %-9s %7d %8.3f %8.3f %10.3e %6d %8ld %9.2e%s%s\n", r.cut.c_str(), r.method.c_str(), r.rule.c_str(),
              cells_text(r.cells).c_str(), r.dofs, r.seconds, r.setup_seconds, r.error, r.split_tets, static_cast<long>(r.piece_points),
              r.smallest_fraction, r.failure.empty() ? "" : "  FAILED: ", r.failure.c_str());
}

/// The unknowns the ladder (dofs, error), errors falling, needs for `error`: log-log
/// interpolation between its two neighbouring rungs; NaN outside the ladder's range.
double dofs_for_error(const std::vector<Run>& ladder, double error) {
  for (std::size_t k = 0; k + 1 < ladder.size(); ++k) {
    const double e0 = ladder[k].error, e1 = ladder[k + 1].error;
    if ((e0 - error) * (e1 - error) > 0.0 || e0 == e1) continue;
    const double s = std::log(error / e0) / std::log(e1 / e0);
    return std::exp(std::log(static_cast<double>(ladder[k].dofs)) +
                    s * std::log(static_cast<double>(ladder[k + 1].dofs) / ladder[k].dofs));
  }
  return not_a_number;
}

void run_cut(const std::string& cut, const Sizes& sizes, const std::string& ccx, const std::filesystem::path& out, std::ofstream& csv,
             std::ofstream& rcsv, std::ofstream& fcsv) {
  const Eigen::Vector2i grid(sizes.reference[0], sizes.reference[1]);
  const kerf::HeightField h = interpolated_height(analytic_height(cut), grid[0], grid[1]);
  const kerf::TriangleSurface surface = extended_cut_surface(h, grid);

  // The reference, its check against the next coarser conforming Tet10, and CalculiX.
  auto start = clock::now();
  const kerf::HeightFieldSplitMesh reference = conforming_mesh(h, sizes.reference, 2);
  int reference_dofs = 0;
  const Eigen::VectorXd u_ref = solve_conforming(reference.split.mesh, reference_dofs);
  const double reference_seconds = seconds_since(start);
  const ReferenceField field = sample_reference(reference.split.mesh, u_ref);
  const kerf::HeightFieldSplitMesh check = conforming_mesh(h, sizes.reference_check, 2);
  int check_dofs = 0;
  const Eigen::VectorXd u_check = solve_conforming(check.split.mesh, check_dofs);
  const double check_error = conforming_error(field, check.split.mesh, u_check);
  // CalculiX on a smaller conforming Tet10 mesh of the same kind (on the check mesh it takes
  // minutes): the opened, curved mesh is a valid FE mesh and both codes solve the same problem.
  double ccx_matrix = not_a_number, ccx_static = not_a_number;
  if (!ccx.empty()) {
    const kerf::HeightFieldSplitMesh mesh = conforming_mesh(h, sizes.calculix, 2);
    int dofs = 0;
    const Eigen::VectorXd u_kerf = solve_conforming(mesh.split.mesh, dofs);
    kerf::CalculixJob job;
    job.material = material;
    job.gravity = gravity;
    job.dirichlet = conditions(mesh.split.mesh);
    try {
      const kerf::CalculixSolution s = kerf::solve_with_calculix(ccx, out / "calculix_work", cut + "_conforming", mesh.split.mesh, job);
      const Eigen::MatrixXd u = u_kerf.reshaped(3, u_kerf.size() / 3).transpose();
      const double max_u = s.displacement.cwiseAbs().maxCoeff();
      ccx_matrix = (u - s.displacement).cwiseAbs().maxCoeff() / max_u;
      ccx_static = (u - s.static_displacement).cwiseAbs().maxCoeff() / max_u;
    } catch (const std::exception& error) {
      std::cerr << "CalculiX cross-check of " << cut << " failed: " << error.what() << '\n';
    }
  }
  rcsv << cut << ',' << cells_text(sizes.reference) << ',' << reference_dofs << ',' << reference_seconds << ','
       << cells_text(sizes.reference_check) << ',' << check_error << ',' << cells_text(sizes.calculix) << ',' << ccx_matrix << ','
       << ccx_static << '\n';
  std::printf("\n%s: reference %s Tet10, %d unknowns, %.2f s; next coarser %s: %.3e; CalculiX on %s: %.2e (matrices), %.2e (static)\n",
              cut.c_str(), cells_text(sizes.reference).c_str(), reference_dofs, reference_seconds,
              cells_text(sizes.reference_check).c_str(), check_error, cells_text(sizes.calculix).c_str(), ccx_matrix, ccx_static);
  std::printf("%-6s %-13s %-15s %-9s %7s %8s %8s %10s %6s %8s %9s\n", "cut", "method", "rule", "cells", "dofs", "time_s", "setup_s",
              "rel_L2", "split", "points", "min_frac");

  // The conforming ladders.
  std::vector<Run> conforming10;
  for (int order : {1, 2})
    for (const Eigen::Vector3i& cells : order == 1 ? sizes.conforming : sizes.conforming10) {
      Run r = make_run(cut, order == 1 ? "conforming" : "conforming10", "-", cells);
      start = clock::now();
      const kerf::HeightFieldSplitMesh mesh = conforming_mesh(h, cells, order);
      r.setup_seconds = seconds_since(start);
      const Eigen::VectorXd u = solve_conforming(mesh.split.mesh, r.dofs);
      r.seconds = seconds_since(start);
      r.error = conforming_error(field, mesh.split.mesh, u);
      r.enrichments = mesh.split.duplicated_nodes;
      write_row(csv, r);
      if (order == 2) conforming10.push_back(r);
    }

  // The XFEM ladders, every rule.
  for (int order : {1, 2})
    for (const Eigen::Vector3i& cells : order == 1 ? sizes.xfem4 : sizes.xfem10)
      for (QuadratureRuleKind kind : order == 1 ? sizes.rules4 : sizes.rules10) {
        const bool every_rule =
            order == 1 || std::find(sizes.all_rules10.begin(), sizes.all_rules10.end(), cells) != sizes.all_rules10.end();
        if (!every_rule && kind != QuadratureRuleKind::subtets) continue;
        const Run r = run_xfem(cut, surface, cells, order, kind, field);
        write_row(csv, r);
        if (order == 2 && r.failure.empty()) {
          const double needed = dofs_for_error(conforming10, r.error);
          fcsv << cut << ',' << r.rule << ',' << cells_text(cells) << ',' << r.dofs << ',' << r.error << ',' << needed << ','
               << r.dofs / needed << '\n';
        }
      }
}

} // namespace curved_cut_study

int main(int argc, char** argv) {
  namespace cs = curved_cut_study;
  const auto options = kerf_measure::parse_run_options(argc, argv, "04_curved_cut_study [--quick] [--out DIR] [--only dome,ridge]",
                                                        "output/curved_cut_study", {"dome", "ridge"});
  if (!options) return 2;
  try {
    std::filesystem::create_directories(options->out);
    std::cout << "Kerf chapter 4 curved-cut study" << (options->quick ? " (quick)" : "") << " on " << kerf_measure::cpu_model() << ", "
              << kerf_measure::now_text() << "\n";
    const cs::Sizes sizes = cs::study_sizes(options->quick);
    std::ofstream csv(options->out / "curved_ladder.csv"), rcsv(options->out / "curved_reference.csv"),
        fcsv(options->out / "curved_factor.csv");
    csv << cs::ladder_header;
    rcsv << "cut,cells,dofs,seconds,check_cells,check_rel_l2_error,calculix_cells,calculix_vs_matrices,calculix_vs_static\n";
    fcsv << "cut,rule,cells,dofs,rel_l2_error,conforming10_dofs_for_same_error,dofs_ratio\n";
    for (const std::string cut : {"dome", "ridge"})
      if (options->runs(cut)) cs::run_cut(cut, sizes, KERF_CCX, options->out, csv, rcsv, fcsv);
  } catch (const std::exception& error) {
    std::cerr << "04_curved_cut_study: " << error.what() << '\n';
    return 1;
  }
  return 0;
}
