/* Kerf, chapter 3 study: how accurate is shifted-Heaviside XFEM against a conforming cut mesh,
   per unknown and per second, and where does it fail?

   Build:   cmake --preset release && cmake --build --preset release --target 03_xfem_study

   Sample runs:
     03_xfem_study --quick --out output/xfem_study_quick
     03_xfem_study --out figures/03_xfem_heaviside
     03_xfem_study --only sweep --out figures/03_xfem_heaviside     (one part: ladders, offsets, sweep, fraction)

   Description: the beam of chapters 1 and 2 (0.03 x 0.06 x 0.2 m, E = 300 kPa, nu = 0.35,
   rho = 1070 kg/m^3), clamped at z = 0, cut half-way through its depth by a rectangle
   [0, x1] x [0, 0.06] x {z}, under Schoch et al.'s three loads (section 6):
     gravity  9.81 m/s^2 along +x;
     pull     the top edge x = 0 (z = 0.2, all y) moved up by 0.02 m;
     move     the top edge x = 0.03 moved by (+0.03, 0, -0.015) m.
   Each is solved with linear and with corotated FEM. The program writes, into the --out folder:
     ladder.csv     one row per (case, model, method, mesh), the cut at x1 = 0.0153, z = 0.1003
                    (Schoch et al.'s moved by 0.3 mm, off every node layer and cell middle): DOFs,
                    wall time, relative L2 error against the reference, and the enrichment's
                    counts (partially cut tets among them). Methods: "xfem" (uniform Tet4 box
                    meshes that ignore the cut), "conforming" (Tet4 box meshes whose node layers
                    nearest to x1 and z are moved onto them, the cut opened by duplicating nodes)
                    and "conforming10" (the same with Tet10: the reference's own ladder);
     ladder_offsets.csv  the linear ladders again for three more places of the cut, for the
                    spread of the comparison;
     reference.csv  the reference (a fine conforming Tet10 mesh opened along the cut) and its
                    cross-check by CalculiX on the same mesh, for the linear cases;
     front_sweep.csv  gravity, linear: the tip u_x at (0.03, 0.03, 0.2) against the front x1 from
                    0.001 to 0.029 m, XFEM on 3x6x19 (plane z = 0.1 and 0.1003) and 5x10x31
                    (0.1003), with the enrichment's counts, "separated" where the simulated cut
                    frees the top, and conforming Tet4 and Tet10 meshes fitted to every x1;
     fraction.csv   the cut plane moved a distance d above a node layer of a small mesh, d / h
                    from 1e-1 to 1e-12: smallest piece volume fractions, condition number of
                    K_ff (plain and Jacobi-scaled) and the difference from the solution with the
                    cut exactly on the layer, with the default minimum-fraction rule and without;
     section.csv    the deformed cross-section y = 0.03 of the XFEM solution of "pull" (corotated),
                    piece by piece, for a picture of the opened cut.
   --quick runs every code path on tiny meshes (and the sweep at three x1) in a few seconds; it is a test.

   Read chapter 3 first. */

#include "kerf/corotation/corotational_model.hpp"
#include "kerf/corotation/quasi_static_solver.hpp"
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/cut/split_mesh_along_cut.hpp"
#include "kerf/fem/assemble_loads.hpp"
#include "kerf/fem/assemble_stiffness.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/evaluate_displacement.hpp"
#include "kerf/fem/linear_material.hpp"
#include "kerf/fem/solve_linear_static.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/fem/tet_quadrature.hpp"
#include "kerf/io/calculix_deck.hpp"
#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/node_region.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"
#include "kerf/scene/scene.hpp"
#include "kerf/scene/xfem_loads.hpp"
#include "kerf/solve/linear_solver.hpp"
#include "kerf/xfem/enrichment.hpp"
#include "kerf/xfem/xfem_field.hpp"
#include "kerf/xfem/xfem_model.hpp"
#include "measure.hpp" // bench/measure.hpp: the command line shared with the benchmarks
#include "reference_field.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace xfem_study {

using clock = std::chrono::steady_clock;
double seconds_since(clock::time_point start) { return std::chrono::duration<double>(clock::now() - start).count(); }
const double not_a_number = std::numeric_limits<double>::quiet_NaN();

const Eigen::Vector3d beam_min(0.0, 0.0, 0.0);
const Eigen::Vector3d beam_max(0.03, 0.06, 0.2);
const double cut_height = 0.1, front_x = 0.015;

/// Where a half-depth cut stands: its front x = x1 and its plane z.
struct CutPlace {
  double x1 = front_x;
  double z = cut_height;
};

/// The ladders' cut: Schoch et al.'s, moved by 0.3 mm in x and z so that neither the front nor the
/// plane lies on a node layer or a cell middle of any ladder mesh, and the tets at the front are
/// partially cut (ladder.csv counts them). On Schoch et al.'s own place, x = 0.015 and z = 0.1, the
/// odd cell counts of the XFEM ladder put both through cell middles, where every section at the
/// front ends exactly on it: a coincidence, not the method (results.md, "Where the cut ends").
const CutPlace ladder_place{0.0153, 0.1003};

/// The half-depth cut [0, x1] x [0, 0.06] x {z}, normal +z (Schoch et al.'s with x1 = 0.015, z = 0.1).
kerf::RectangleCut make_cut(double z, double x1 = front_x) {
  return kerf::RectangleCut(Eigen::Vector3d(0.0, 0.0, z), Eigen::Vector3d(x1, 0.0, 0.0), Eigen::Vector3d(0.0, 0.06, 0.0));
}
kerf::RectangleCut make_cut(const CutPlace& place) { return make_cut(place.z, place.x1); }

std::string cells_text(const Eigen::Vector3i& c) { return std::to_string(c[0]) + "x" + std::to_string(c[1]) + "x" + std::to_string(c[2]); }

// @sect3{The three load cases}

struct LoadCase {
  std::string name;
  Eigen::Vector3d gravity{0, 0, 0};
  bool has_edge = false;
  double edge_x = 0.0;             ///< the top edge x = edge_x, z = 0.2, all y
  Eigen::Vector3d edge_displacement{0, 0, 0};
};

std::vector<LoadCase> load_cases() {
  LoadCase gravity{"gravity", {9.81, 0, 0}};
  LoadCase pull{"pull", {0, 0, 0}, true, 0.0, {0, 0, 0.02}};
  LoadCase move{"move", {0, 0, 0}, true, 0.03, {0.03, 0, -0.015}};
  return {gravity, pull, move};
}

std::vector<int> nodes_in_box(const kerf::TetMesh& mesh, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  kerf::NodeRegion region;
  region.box_min = lo;
  region.box_max = hi;
  return kerf::nodes_in_region(mesh, region);
}

/// The base z = 0 clamped, and for "pull" and "move" the top edge prescribed. On a split mesh the
/// top edge is far from the cut, so no duplicate is among its nodes.
std::vector<kerf::DirichletNodes> conditions(const kerf::TetMesh& mesh, const LoadCase& c) {
  std::vector<kerf::DirichletNodes> list;
  list.push_back({nodes_in_box(mesh, beam_min, Eigen::Vector3d(beam_max[0], beam_max[1], 0.0)), {0, 0, 0}});
  if (c.has_edge)
    list.push_back({nodes_in_box(mesh, Eigen::Vector3d(c.edge_x, 0, beam_max[2]), Eigen::Vector3d(c.edge_x, beam_max[1], beam_max[2])),
                    c.edge_displacement});
  return list;
}

const kerf::LinearMaterial material{};

kerf::QuasiStaticSettings corotated_settings() {
  kerf::QuasiStaticSettings settings;
  settings.load_steps = 10;
  settings.tangent = kerf::CorotationalTangent::consistent;
  return settings;
}

/// One solve: the displacements and what it cost.
struct Solution {
  Eigen::VectorXd u;
  double seconds = 0.0; ///< assembly + solve (and, for XFEM, the cut processing and the model)
  int dofs = 0;         ///< free unknowns
  int iterations = 1;
  bool converged = true;
};

// @sect3{Conforming FEM: the cut opened by duplicated nodes}

/// The box mesh with `cells`, its node layers moved along x and z so that one lies on the front
/// x1 and one on the plane z: the layer nearest to each (never a face of the beam) goes there
/// exactly, and the layers between it and the faces are spaced evenly again (a piecewise linear
/// map of each coordinate, which keeps every tet's orientation). For even cell counts and
/// Schoch et al.'s place (0.015, 0.1) nothing moves.
kerf::TetMesh fitted_box_mesh(const Eigen::Vector3i& cells, const CutPlace& place) {
  kerf::TetMesh mesh = kerf::make_box_mesh(beam_min, beam_max, cells);
  const auto fit = [&](int axis, double target) {
    const int n = cells[axis];
    const double length = beam_max[axis], h = length / n;
    const int layer = std::clamp(static_cast<int>(std::lround(target / h)), 1, n - 1);
    for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) {
      double& c = mesh.nodes(v, axis);
      const long k = std::lround(c / h);
      if (k == 0) c = 0.0;
      else if (k == n) c = length;
      else if (k == layer) c = target;
      else if (k < layer) c = target * k / layer;
      else c = target + (length - target) * static_cast<double>(k - layer) / (n - layer);
    }
  };
  fit(0, place.x1);
  fit(2, place.z);
  return mesh;
}

/// The fitted box mesh, promoted to Tet10 for order 2, then opened along the cut.
kerf::SplitMesh conforming_mesh(const Eigen::Vector3i& cells, int order, const CutPlace& place) {
  kerf::TetMesh mesh = fitted_box_mesh(cells, place);
  if (order == 2) mesh = kerf::tet10_from_tet4(mesh);
  return kerf::split_mesh_along_cut(mesh, make_cut(place), 1e-9);
}

Solution solve_conforming(const kerf::TetMesh& mesh, const LoadCase& c, bool corotated) {
  const kerf::DofMap dofs = kerf::make_dof_map(mesh.num_nodes(), conditions(mesh, c));
  Solution s;
  s.dofs = dofs.num_free;
  const auto start = clock::now();
  const Eigen::VectorXd f = kerf::assemble_gravity(mesh, material.density, c.gravity);
  if (!corotated) {
    s.u = kerf::solve_linear_static(mesh, material, dofs, f, kerf::SolverSettings{});
  } else {
    const kerf::CorotationalModel model(mesh, material);
    const kerf::QuasiStaticResult r = kerf::solve_quasi_static(model, dofs, f, corotated_settings());
    s.u = r.u;
    s.iterations = r.total_iterations;
    s.converged = r.converged;
  }
  s.seconds = seconds_since(start);
  return s;
}

// @sect3{XFEM on a mesh that does not conform to the cut}

/// Everything an XFEM solve keeps alive: the model holds the mesh and the enrichment by reference.
struct XfemRun {
  kerf::TetMesh mesh;
  kerf::Enrichment enrichment;
  std::unique_ptr<kerf::XfemModel> model;
  Solution solution;
};

/// Cut processing, model, loads and the solve, all inside the clock.
void solve_xfem(XfemRun& run, const kerf::RectangleCut& cut, const LoadCase& c, bool corotated,
                const kerf::EnrichmentSettings& settings = {}) {
  const auto start = clock::now();
  run.enrichment = kerf::make_enrichment(run.mesh, cut, settings);
  run.model = std::make_unique<kerf::XfemModel>(run.mesh, material, run.enrichment);
  const kerf::DofMap dofs = kerf::make_xfem_dof_map(*run.model, conditions(run.mesh, c));
  kerf::Scene scene;
  scene.material = material;
  scene.gravity = c.gravity;
  const Eigen::VectorXd f = kerf::xfem_scene_loads(scene, *run.model, kerf::boundary_faces(run.mesh));
  Solution& s = run.solution;
  s.dofs = dofs.num_free;
  if (!corotated) {
    s.u = kerf::solve_linear_xfem(*run.model, dofs, f, kerf::SolverSettings{});
  } else {
    const kerf::QuasiStaticResult r = kerf::solve_quasi_static(*run.model, dofs, f, corotated_settings());
    s.u = r.u;
    s.iterations = r.total_iterations;
    s.converged = r.converged;
  }
  s.seconds = seconds_since(start);
}

// @sect3{The error measure}

// The reference at its own degree-2 points (examples/reference_field.hpp), shared with chapter
// 4's curved-cut study.
using study::ReferenceField;
using study::relative_l2;
using study::sample_reference;

/// A conforming solution at the reference's points. A point of the reference lies strictly on
/// one side of the plane z = 0.1, and so in a tet of the coarse split mesh on the same side.
double conforming_error(const ReferenceField& ref, const kerf::TetMesh& mesh, const Eigen::VectorXd& u) {
  Eigen::Index outside = 0;
  const Eigen::MatrixXd values = kerf::evaluate_displacement_at(mesh, u, ref.points, outside);
  if (outside > 0) throw std::runtime_error("reference points outside a conforming mesh");
  return relative_l2(ref, values);
}

double xfem_error(const ReferenceField& ref, const XfemRun& run) {
  Eigen::Index outside = 0;
  const Eigen::MatrixXd values = kerf::xfem_displacement_at(*run.model, run.solution.u, ref.points, outside);
  if (outside > 0) throw std::runtime_error("reference points outside an XFEM mesh");
  return relative_l2(ref, values);
}

// @sect3{A picture of the opened cut}

/// The XFEM field on a grid of points in the mid-plane y = 0.03, each point moved by the field
/// of its own side: plotted as dots, the two faces of the cut separate where it opens.
void write_section(const XfemRun& run, const std::filesystem::path& file, double plane_z) {
  const int nx = 31, nz = 201;
  Eigen::MatrixXd points(nx * nz, 3);
  for (int i = 0; i < nx; ++i)
    for (int k = 0; k < nz; ++k) points.row(i * nz + k) << beam_max[0] * i / (nx - 1), 0.03, beam_max[2] * k / (nz - 1);
  // No point on the plane z = 0.1 itself, where the side would be a convention: nudge them.
  for (Eigen::Index p = 0; p < points.rows(); ++p)
    if (std::abs(points(p, 2) - plane_z) < 1e-12) points(p, 2) += 1e-6;
  Eigen::Index outside = 0;
  const Eigen::MatrixXd u = kerf::xfem_displacement_at(*run.model, run.solution.u, points, outside);
  std::ofstream csv(file);
  csv << "x,z,above,deformed_x,deformed_z\n";
  for (Eigen::Index p = 0; p < points.rows(); ++p)
    csv << points(p, 0) << ',' << points(p, 2) << ',' << (points(p, 2) > plane_z ? 1 : 0) << ',' << points(p, 0) + u(p, 0) << ','
        << points(p, 2) + u(p, 2) << '\n';
}

// @sect3{The ladders}

struct Sizes {
  // Linear solves are cheap, so the linear reference is finer than the corotated one, which
  // takes some 40 Newton iterations; the corotated ladders stop below max_corotated_cells.
  Eigen::Vector3i reference[2];       ///< [linear, corotated]
  Eigen::Vector3i reference_check[2]; ///< the next coarser conforming Tet10, to estimate the reference's own error
  Eigen::Vector3i calculix;           ///< the conforming Tet10 mesh CalculiX cross-checks (the linear check mesh)
  std::vector<Eigen::Vector3i> xfem, conforming, conforming10;
  int max_corotated_cells = 0;
  std::vector<Eigen::Vector3i> fraction_meshes; ///< front x = 0.015 on a node layer, and mid-cell
  std::vector<double> fraction_offsets;         ///< d / h
  std::vector<CutPlace> spread_places;          ///< more generic places for the linear ladders, for their spread
  std::vector<double> sweep_x1;                 ///< the front positions of the front sweep
  std::vector<std::pair<Eigen::Vector3i, double>> sweep_meshes; ///< XFEM meshes of the sweep and their plane z
  Eigen::Vector3i sweep_conforming;             ///< conforming Tet4 mesh of the sweep (fitted to every x1)
  Eigen::Vector3i sweep_reference;              ///< conforming Tet10 mesh of the sweep (fitted to every x1)
};

Sizes study_sizes(bool quick) {
  Sizes s;
  if (quick) {
    s.reference[0] = s.reference[1] = {2, 4, 10};
    s.reference_check[0] = s.reference_check[1] = {2, 2, 4};
    s.xfem = {{1, 2, 5}, {3, 2, 7}};
    s.conforming = {{2, 2, 4}, {2, 4, 6}};
    s.conforming10 = {{2, 2, 4}};
    s.max_corotated_cells = 1000;
    s.fraction_meshes = {{2, 2, 10}, {3, 2, 10}};
    s.fraction_offsets = {1e-1, 1e-4, 1e-7};
    s.spread_places = {{0.0147, 0.0997}};
    s.sweep_x1 = {0.005, 0.0153, 0.0251};
    s.sweep_meshes = {{{3, 6, 19}, 0.1003}};
    s.sweep_conforming = {3, 6, 20};
    s.sweep_reference = {2, 4, 10};
  } else {
    s.reference[0] = {6, 12, 40};
    s.reference_check[0] = {4, 8, 26};
    s.reference[1] = {4, 8, 26};
    s.reference_check[1] = {2, 4, 14};
    s.xfem = {{1, 2, 5}, {3, 2, 7}, {3, 4, 11}, {3, 6, 19}, {5, 10, 31}, {7, 14, 41}, {9, 18, 53}};
    s.conforming = {{2, 2, 4}, {2, 4, 10}, {4, 6, 16}, {4, 8, 20}, {6, 12, 30}, {8, 16, 40}};
    s.conforming10 = {{2, 2, 4}, {2, 4, 10}, {4, 6, 16}, {4, 8, 20}};
    s.max_corotated_cells = 4100;
    s.fraction_meshes = {{4, 4, 10}, {3, 4, 10}};
    for (int k = 1; k <= 15; ++k) s.fraction_offsets.push_back(std::pow(10.0, -0.5 * k));
    // 0.3 mm and 0.9 mm either side of Schoch et al.'s place in x, mixed in z: on the three-cell
    // meshes 0.0147 and 0.0141 fall in the other half of the cell than 0.0153 and 0.0159.
    s.spread_places = {{0.0147, 0.0997}, {0.0159, 0.1011}, {0.0141, 0.1006}};
    for (int k = 0; k <= 56; ++k) s.sweep_x1.push_back(0.001 + 0.0005 * k);
    s.sweep_meshes = {{{3, 6, 19}, 0.1}, {{3, 6, 19}, 0.1003}, {{5, 10, 31}, 0.1003}};
    s.sweep_conforming = {3, 6, 20};
    s.sweep_reference = {4, 8, 20};
  }
  s.calculix = s.reference_check[0];
  return s;
}

const char* const ladder_header = "case,model,method,cells,dofs,seconds,iterations,converged,rel_l2_error,enriched_nodes,front_nodes,"
                                  "cut_tets,partially_cut,completely_cut,x1,z\n";

/// Runs every ladder for every case and model (only the linear ones if linear_only) with the cut
/// at `place`, appending to `csv` (ladder_header) and, when given, to `rcsv` (reference.csv).
void run_ladders(const Sizes& sizes, const std::string& ccx, const std::filesystem::path& out, const CutPlace& place, std::ofstream& csv,
                 std::ofstream* rcsv, bool linear_only) {
  std::printf("\nLadders with the cut's front at x1 = %g m and its plane at z = %g m%s\n", place.x1, place.z,
              linear_only ? " (linear only)" : "");
  std::printf("%-8s %-6s %-13s %-9s %7s %8s %10s %5s %5s\n", "case", "model", "method", "cells", "dofs", "time_s", "rel_L2", "iter",
              "part.");
  for (const LoadCase& c : load_cases())
    for (bool corotated : {false, true}) {
      if (corotated && linear_only) continue;
      const char* model = corotated ? "corot" : "linear";
      const Eigen::Vector3i reference_cells = sizes.reference[corotated], check_cells = sizes.reference_check[corotated];
      const kerf::SplitMesh reference_mesh = conforming_mesh(reference_cells, 2, place);
      const kerf::SplitMesh check_mesh = conforming_mesh(check_cells, 2, place);
      const Solution ref = solve_conforming(reference_mesh.mesh, c, corotated);
      const ReferenceField field = sample_reference(reference_mesh.mesh, ref.u);
      const double max_u = ref.u.reshaped(3, ref.u.size() / 3).colwise().norm().maxCoeff();
      const Solution check = solve_conforming(check_mesh.mesh, c, corotated);
      const double check_error = conforming_error(field, check_mesh.mesh, check.u);
      // CalculiX on a conforming split Tet10 mesh (the linear check mesh: ccx on the reference
      // itself takes minutes), both routes, against Kerf's solution on the same mesh.
      double ccx_matrix = not_a_number, ccx_static = not_a_number, ccx_static_s = not_a_number, ccx_matrix_s = not_a_number;
      if (!corotated && !ccx.empty() && rcsv != nullptr) {
        const kerf::SplitMesh& ccx_mesh = check_mesh;
        const Eigen::VectorXd& u_kerf_flat = check.u;
        const double ccx_max_u = u_kerf_flat.reshaped(3, u_kerf_flat.size() / 3).colwise().norm().maxCoeff();
        kerf::CalculixJob job;
        job.material = material;
        job.dirichlet = conditions(ccx_mesh.mesh, c);
        job.gravity = c.gravity;
        try {
          const kerf::CalculixSolution cs = kerf::solve_with_calculix(ccx, out / "calculix_work", "conforming_" + c.name, ccx_mesh.mesh, job);
          const Eigen::MatrixXd u_kerf = u_kerf_flat.reshaped(3, u_kerf_flat.size() / 3).transpose();
          ccx_matrix = (cs.displacement - u_kerf).rowwise().norm().maxCoeff() / ccx_max_u;
          ccx_static = (cs.static_displacement - u_kerf).rowwise().norm().maxCoeff() / ccx_max_u;
          ccx_static_s = cs.static_seconds;
          ccx_matrix_s = cs.matrix_seconds;
        } catch (const std::exception& error) {
          std::cerr << "CalculiX cross-check of " << c.name << " failed: " << error.what() << '\n';
        }
      }
      if (rcsv != nullptr)
        *rcsv << c.name << ',' << model << ',' << cells_text(reference_cells) << ',' << ref.dofs << ',' << ref.seconds << ','
           << ref.iterations << ',' << ref.converged << ',' << max_u << ',' << cells_text(check_cells) << ',' << check_error << ','
           << ccx_matrix << ',' << ccx_static << ',' << ccx_static_s << ',' << ccx_matrix_s << ',' << place.x1 << ',' << place.z << '\n';
      std::printf("%-8s %-6s %-13s %-9s %7d %8.3f %10s %5d  max|u| = %.4g m, next coarser Tet10 %s: %.3e, CalculiX on %s: %.2e (matrix), "
                  "%.2e (static)\n",
                  c.name.c_str(), model, "reference", cells_text(reference_cells).c_str(), ref.dofs, ref.seconds, "-", ref.iterations,
                  max_u, cells_text(check_cells).c_str(), check_error, cells_text(check_cells).c_str(), ccx_matrix, ccx_static);

      const auto row = [&](const char* method, const Eigen::Vector3i& cells, const Solution& s, double error, int enriched, int front,
                           int cut_tets, int partially, int completely) {
        csv << c.name << ',' << model << ',' << method << ',' << cells_text(cells) << ',' << s.dofs << ',' << s.seconds << ','
            << s.iterations << ',' << s.converged << ',' << error << ',' << enriched << ',' << front << ',' << cut_tets << ',' << partially
            << ',' << completely << ',' << place.x1 << ',' << place.z << '\n';
        std::printf("%-8s %-6s %-13s %-9s %7d %8.3f %10.3e %5d %5d%s\n", c.name.c_str(), model, method, cells_text(cells).c_str(), s.dofs,
                    s.seconds, error, s.iterations, partially, s.converged ? "" : " NOT CONVERGED");
      };
      const auto too_big = [&](const Eigen::Vector3i& cells) { return corotated && cells.prod() > sizes.max_corotated_cells; };
      for (const Eigen::Vector3i& cells : sizes.xfem) {
        if (too_big(cells)) continue;
        XfemRun run;
        run.mesh = kerf::make_box_mesh(beam_min, beam_max, cells);
        const auto partially = [&] { return run.enrichment.classification.count(kerf::ElementCutState::partially_cut); };
        const auto completely = [&] { return run.enrichment.classification.count(kerf::ElementCutState::completely_cut); };
        try {
          solve_xfem(run, make_cut(place), c, corotated);
        } catch (const std::runtime_error& error) {
          // A cut the enrichment extends through the whole depth (one cell across x) leaves a
          // piece no condition holds, and the library refuses it by name.
          std::printf("%-8s %-6s %-13s %-9s separated: %s\n", c.name.c_str(), model, "xfem", cells_text(cells).c_str(), error.what());
          csv << c.name << ',' << model << ",xfem," << cells_text(cells) << ",nan,nan,0,0,nan," << run.enrichment.num_enriched() << ','
              << run.enrichment.front_nodes << ',' << run.enrichment.cut_tets << ',' << partially() << ',' << completely() << ','
              << place.x1 << ',' << place.z << '\n';
          continue;
        }
        row("xfem", cells, run.solution, xfem_error(field, run), static_cast<int>(run.enrichment.num_enriched()),
            run.enrichment.front_nodes, run.enrichment.cut_tets, partially(), completely());
        if (!linear_only && c.name == "pull" && corotated && cells == sizes.xfem[std::min<std::size_t>(3, sizes.xfem.size() - 1)]) {
          kerf::write_xfem_vtu(out / "pull_corot_xfem_pieces.vtu", *run.model, run.solution.u);
          write_section(run, out / "section.csv", place.z);
        }
      }
      for (int order : {1, 2})
        for (const Eigen::Vector3i& cells : order == 1 ? sizes.conforming : sizes.conforming10) {
          if (too_big(cells)) continue;
          const kerf::SplitMesh mesh = conforming_mesh(cells, order, place);
          const Solution s = solve_conforming(mesh.mesh, c, corotated);
          row(order == 1 ? "conforming" : "conforming10", cells, s, conforming_error(field, mesh.mesh, s.u), mesh.duplicated_nodes, 0, 0, 0,
              0);
        }
    }
}

// @sect3{Where it fails: a sliver piece}

/// The cut plane a distance d = offset h above the node layer z = 0.1 of a mesh with cells of
/// height h. The tets of the layer above are then cut into a sliver of height d and the rest:
/// the smaller piece holds about 3 d / h of a tet with a face on the layer, (d / h)^2 of one
/// with an edge on it and (d / h)^3 of one with a corner on it. With the minimum-fraction rule
/// the corners on the sliver's side are moved onto the cut once the sliver is below 1e-4, which
/// turns the problem back into the cut exactly on the layer.
void run_fraction_study(const Eigen::Vector3i& cells, const std::vector<double>& offsets, std::ofstream& csv, std::ofstream& uncut) {
  const LoadCase pull = load_cases()[1];
  const double h = beam_max[2] / cells[2];
  const std::string front = std::abs(std::remainder(front_x / (beam_max[0] / cells[0]), 1.0)) < 1e-9 ? "on_layer" : "mid_cell";
  // The solution with the cut exactly on the layer, sampled at the degree-2 points of the mesh.
  XfemRun exact;
  exact.mesh = kerf::make_box_mesh(beam_min, beam_max, cells);
  solve_xfem(exact, make_cut(cut_height), pull, false);
  ReferenceField field = sample_reference(exact.mesh, exact.solution.u);
  {
    Eigen::Index outside = 0;
    field.values = kerf::xfem_displacement_at(*exact.model, exact.solution.u, field.points, outside);
  }

  std::cout << "\nSliver study: mesh " << cells_text(cells) << ", front " << front << " (h = " << h << " m), cut plane at z = 0.1 + d, case pull, linear\n";
  std::printf("%9s %5s %10s %10s %4s %4s %6s %10s %10s %10s\n", "d/h", "rule", "min_frac", "max_frac", "cut", "snap", "dofs",
              "cond", "cond_jac", "rel_diff");
  for (double offset : offsets)
    for (double rule : {kerf::default_minimum_volume_fraction, 0.0}) {
      XfemRun run;
      run.mesh = exact.mesh;
      const kerf::RectangleCut cut = make_cut(cut_height + offset * h);
      run.enrichment = kerf::make_enrichment(run.mesh, cut, kerf::EnrichmentSettings{rule});
      run.model = std::make_unique<kerf::XfemModel>(run.mesh, material, run.enrichment);
      const kerf::DofMap dofs = kerf::make_xfem_dof_map(*run.model, conditions(run.mesh, pull));
      double min_fraction = 1.0, max_fraction = 0.0;
      for (Eigen::Index t = 0; t < run.mesh.num_tets(); ++t)
        if (run.enrichment.tet_side[static_cast<std::size_t>(t)] == kerf::TetSide::cut) {
          const double f = std::min(run.enrichment.fraction_above[static_cast<std::size_t>(t)], run.enrichment.fraction_below(t));
          min_fraction = std::min(min_fraction, f);
          max_fraction = std::max(max_fraction, f);
        }
      if (run.enrichment.cut_tets == 0) min_fraction = max_fraction = not_a_number;
      // K_ff, dense: its extreme eigenvalues, and those of D^-1/2 K_ff D^-1/2 (Jacobi scaling).
      kerf::SparseAssembler assembler(run.model->assembly_slots(), dofs);
      Eigen::VectorXd rhs = Eigen::VectorXd::Zero(dofs.num_free);
      run.model->assemble_linear_stiffness(assembler, rhs);
      const Eigen::MatrixXd K = assembler.matrix().toDense();
      const Eigen::VectorXd eig = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(K, Eigen::EigenvaluesOnly).eigenvalues();
      const Eigen::VectorXd d = K.diagonal().cwiseSqrt().cwiseInverse();
      const Eigen::VectorXd eig_jacobi =
          Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(d.asDiagonal() * K * d.asDiagonal(), Eigen::EigenvaluesOnly).eigenvalues();
      // The solution, and its difference from the cut on the layer away from the slab 0.1 <= z <= 0.1 + d,
      // where the two cuts put a point on different sides.
      double difference = not_a_number;
      bool ok = true;
      try {
        kerf::Scene scene;
        scene.material = material;
        const Eigen::VectorXd f = kerf::xfem_scene_loads(scene, *run.model, kerf::boundary_faces(run.mesh));
        run.solution.u = kerf::solve_linear_xfem(*run.model, dofs, f, kerf::SolverSettings{});
        Eigen::Index outside = 0;
        const Eigen::MatrixXd values = kerf::xfem_displacement_at(*run.model, run.solution.u, field.points, outside);
        double num = 0.0, den = 0.0;
        for (Eigen::Index p = 0; p < field.points.rows(); ++p) {
          const double z = field.points(p, 2);
          if (z >= cut_height - 1e-12 && z <= cut_height + offset * h + 1e-12) continue;
          num += field.weights[p] * (values.row(p) - field.values.row(p)).squaredNorm();
          den += field.weights[p] * field.values.row(p).squaredNorm();
        }
        difference = std::sqrt(num / den);
      } catch (const std::exception& error) {
        ok = false;
        std::cerr << "d/h = " << offset << ", rule " << rule << ": " << error.what() << '\n';
      }
      const double condition = eig.maxCoeff() / eig.minCoeff(), jacobi = eig_jacobi.maxCoeff() / eig_jacobi.minCoeff();
      csv << front << ',' << cells_text(cells) << ',' << offset << ',' << rule << ',' << min_fraction << ',' << max_fraction << ',' << run.enrichment.cut_tets << ','
          << run.enrichment.snapped_nodes << ',' << run.enrichment.num_enriched() << ',' << dofs.num_free << ',' << eig.minCoeff() << ','
          << eig.maxCoeff() << ',' << condition << ',' << jacobi << ',' << difference << ',' << ok << '\n';
      std::printf("%9.2e %5s %10.2e %10.2e %4d %4d %6d %10.3e %10.3e %10.3e%s\n", offset, rule > 0 ? "1e-4" : "off", min_fraction,
                  max_fraction, run.enrichment.cut_tets, run.enrichment.snapped_nodes, dofs.num_free, condition, jacobi, difference,
                  ok ? "" : " SOLVE FAILED");
    }
  // The uncut beam on the same mesh, for scale.
  const kerf::DofMap dofs = kerf::make_dof_map(exact.mesh.num_nodes(), conditions(exact.mesh, pull));
  kerf::SparseAssembler assembler(exact.mesh.tets, dofs);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(dofs.num_free);
  kerf::assemble_linear_stiffness(exact.mesh, material, assembler, rhs);
  const Eigen::VectorXd eig =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(assembler.matrix().toDense(), Eigen::EigenvaluesOnly).eigenvalues();
  std::printf("uncut beam on the same mesh: %d DOFs, condition number %.3e\n", dofs.num_free, eig.maxCoeff() / eig.minCoeff());
  uncut << front << ',' << cells_text(cells) << ',' << dofs.num_free << ',' << eig.maxCoeff() / eig.minCoeff() << '\n';
}

// @sect3{Where the simulated cut ends: the front swept through an element}

/// The tip deflection u_x at (0.03, 0.03, 0.2) under gravity (linear) as the front x1 moves
/// through the elements, on each sweep mesh, with the counts of what the enrichment made of the
/// cut, and the same on conforming meshes fitted to every x1 (Tet4 and Tet10). An x1 whose
/// simulated cut separates the body is recorded as "separated". Writes front_sweep.csv.
void run_front_sweep(const Sizes& sizes, const std::filesystem::path& out) {
  const LoadCase gravity = load_cases()[0];
  Eigen::MatrixXd tip(1, 3);
  tip << 0.03, 0.03, 0.2;
  const auto tip_ux = [&](auto&& evaluate) {
    Eigen::Index outside = 0;
    const Eigen::MatrixXd u = evaluate(tip, outside);
    return outside > 0 ? not_a_number : u(0, 0);
  };
  const auto conforming_tip = [&](const Eigen::Vector3i& cells, int order, const CutPlace& place) {
    const kerf::SplitMesh mesh = conforming_mesh(cells, order, place);
    const Solution s = solve_conforming(mesh.mesh, gravity, false);
    return tip_ux([&](const Eigen::MatrixXd& p, Eigen::Index& outside) { return kerf::evaluate_displacement_at(mesh.mesh, s.u, p, outside); });
  };
  std::ofstream csv(out / "front_sweep.csv");
  csv << "cells,z,x1,status,enriched_nodes,front_nodes,cut_tets,partially_cut,completely_cut,tip_ux_xfem,tip_ux_conforming,"
         "tip_ux_conforming10\n";
  std::cout << "\nFront sweep: gravity, linear, tip u_x at (0.03, 0.03, 0.2); conforming Tet4 " << cells_text(sizes.sweep_conforming)
            << " and Tet10 " << cells_text(sizes.sweep_reference) << " fitted to every x1\n";
  std::printf("%-8s %7s %7s %9s %5s %5s %5s %12s %12s %12s\n", "cells", "z", "x1", "status", "enr", "part", "compl", "xfem", "conf_tet4",
              "conf_tet10");
  // The conforming answers depend on x1 and z only: once per plane and x1, then the XFEM meshes
  // of that plane one after the other (one block of rows each, for the chart's lines).
  std::vector<double> planes;
  for (const auto& [cells, z] : sizes.sweep_meshes)
    if (std::find(planes.begin(), planes.end(), z) == planes.end()) planes.push_back(z);
  for (double z : planes) {
    std::vector<double> conforming, conforming10;
    for (double x1 : sizes.sweep_x1) {
      conforming.push_back(conforming_tip(sizes.sweep_conforming, 1, CutPlace{x1, z}));
      conforming10.push_back(conforming_tip(sizes.sweep_reference, 2, CutPlace{x1, z}));
    }
    for (const auto& [cells, mesh_z] : sizes.sweep_meshes) {
      if (mesh_z != z) continue;
      for (std::size_t i = 0; i < sizes.sweep_x1.size(); ++i) {
        const double x1 = sizes.sweep_x1[i];
        XfemRun run;
        run.mesh = kerf::make_box_mesh(beam_min, beam_max, cells);
        std::string status = "solved";
        double xfem = not_a_number;
        try {
          solve_xfem(run, make_cut(CutPlace{x1, z}), gravity, false);
          xfem = tip_ux([&](const Eigen::MatrixXd& p, Eigen::Index& outside) {
            return kerf::xfem_displacement_at(*run.model, run.solution.u, p, outside);
          });
        } catch (const std::runtime_error& error) {
          // The library refuses a piece no Dirichlet condition holds, naming it.
          status = "separated";
          std::printf("  %s, x1 = %g: %s\n", cells_text(cells).c_str(), x1, error.what());
        }
        const int partially = run.enrichment.classification.count(kerf::ElementCutState::partially_cut);
        const int completely = run.enrichment.classification.count(kerf::ElementCutState::completely_cut);
        csv << cells_text(cells) << ',' << z << ',' << x1 << ',' << status << ',' << run.enrichment.num_enriched() << ','
            << run.enrichment.front_nodes << ',' << run.enrichment.cut_tets << ',' << partially << ',' << completely << ','
            << std::setprecision(17) << xfem << ',' << conforming[i] << ',' << conforming10[i] << std::setprecision(6) << '\n';
        std::printf("%-8s %7.4f %7.4f %9s %5d %5d %5d %12.6g %12.6g %12.6g\n", cells_text(cells).c_str(), z, x1, status.c_str(),
                    static_cast<int>(run.enrichment.num_enriched()), partially, completely, xfem, conforming[i], conforming10[i]);
      }
    }
  }
}

} // namespace xfem_study

int main(int argc, char** argv) {
  // --only PARTS (comma-separated: ladders, offsets, sweep, fraction) runs only those parts, so
  // that one part can be regenerated without the others; the default runs all four.
  const auto options = kerf_measure::parse_run_options(argc, argv,
                                                       "03_xfem_study [--quick] [--out DIR] [--only ladders,offsets,sweep,fraction]",
                                                       "output/xfem_study", {"ladders", "offsets", "sweep", "fraction"});
  if (!options) return 2;
  try {
    std::filesystem::create_directories(options->out);
    std::cout << "Kerf chapter 3 study" << (options->quick ? " (quick)" : "") << " on " << kerf_measure::cpu_model() << "\n";
    const auto start = xfem_study::clock::now();
    const xfem_study::Sizes sizes = xfem_study::study_sizes(options->quick);
    if (options->runs("ladders")) {
      std::ofstream ladder(options->out / "ladder.csv"), reference(options->out / "reference.csv");
      ladder << xfem_study::ladder_header;
      reference << "case,model,cells,dofs,seconds,iterations,converged,max_u_m,check_cells,check_rel_l2,ccx_matrix_max_rel,"
                   "ccx_static_max_rel,ccx_static_s,ccx_matrix_s,x1,z\n";
      xfem_study::run_ladders(sizes, KERF_CCX, options->out, xfem_study::ladder_place, ladder, &reference, false);
    }
    if (options->runs("offsets")) {
      std::ofstream spread(options->out / "ladder_offsets.csv");
      spread << xfem_study::ladder_header;
      for (const xfem_study::CutPlace& place : sizes.spread_places)
        xfem_study::run_ladders(sizes, KERF_CCX, options->out, place, spread, nullptr, true);
    }
    if (options->runs("sweep")) xfem_study::run_front_sweep(sizes, options->out);
    if (options->runs("fraction")) {
      std::ofstream csv(options->out / "fraction.csv"), uncut(options->out / "fraction_uncut.csv");
      csv << "front,cells,offset,rule,min_fraction,max_fraction,cut_tets,snapped_nodes,enriched_nodes,dofs,lambda_min,lambda_max,"
             "condition,jacobi_condition,rel_l2_difference,solve_ok\n";
      uncut << "front,cells,dofs,condition\n";
      for (const Eigen::Vector3i& cells : sizes.fraction_meshes) xfem_study::run_fraction_study(cells, sizes.fraction_offsets, csv, uncut);
    }
    std::printf("\ntotal %.1f s\n", xfem_study::seconds_since(start));
  } catch (const std::exception& error) {
    std::cerr << "03_xfem_study: " << error.what() << '\n';
    return 1;
  }
  return 0;
}
