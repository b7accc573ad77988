/* Kerf, chapter 1 study: how accurate, how fast, and where Tet4 fails.

   Build:   cmake --preset release && cmake --build --preset release --target 01_beam_study

   Sample runs:
     01_beam_study --quick --out output/beam_study_quick
     01_beam_study --out figures/01_linear_fem
     01_beam_study --only calculix --out figures/01_linear_fem   (one part: ladder, locking, calculix)

   Description: the beam of chapter 1 (0.03 x 0.06 x 0.2 m, E = 300 kPa, nu = 0.35,
   rho = 1070 kg/m^3, clamped at z = 0) under two loads: (a) gravity g = (9.81, 0, 0) m/s^2,
   test case 1 of Schoch et al., and (b) a uniform traction on the top face z = 0.2 with total
   force (0.5, 0, 0) N. The program writes, into the --out folder:
     ladder.csv     Tet4 and Tet10 on a refinement ladder: DOFs, wall times, L2 and tip errors
                    against a converged fine Tet10 reference;
     reference.csv  how accurate that reference itself is (next-coarser level, observed rate);
     locking.csv    Tet4 and Tet10 on one mesh as nu -> 0.5, against a reference at the same nu;
     calculix.csv   Kerf against CalculiX on the same meshes: agreement and whole-run wall time
                    (only when ccx was found at configure time).
   --quick runs every code path on tiny meshes in a few seconds; it is a test. The full run
   takes a few minutes and produces the numbers of chapter 1's results page. */

#include "kerf/fem/assemble_loads.hpp"
#include "kerf/fem/assemble_stiffness.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/evaluate_displacement.hpp"
#include "kerf/fem/l2_error.hpp"
#include "kerf/fem/linear_material.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/io/calculix_deck.hpp"
#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/node_region.hpp"
#include "kerf/mesh/point_locator.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"
#include "kerf/solve/linear_solver.hpp"
#include "measure.hpp" // bench/measure.hpp: the command line shared with the benchmarks

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace beam_study {

using clock = std::chrono::steady_clock;

/// Seconds elapsed since `start`.
double seconds_since(clock::time_point start) { return std::chrono::duration<double>(clock::now() - start).count(); }

// The beam and its two load cases, as in chapter 1's demo scene.
const Eigen::Vector3d beam_min(0.0, 0.0, 0.0);
const Eigen::Vector3d beam_max(0.03, 0.06, 0.2);
const Eigen::Vector3d gravity(9.81, 0.0, 0.0);            // m/s^2, load case (a)
const Eigen::Vector3d top_total_force(0.5, 0.0, 0.0);     // N on the face z = 0.2, load case (b)
const Eigen::Vector3d tip_point(0.015, 0.03, 0.2);        // centre of the top face
constexpr int error_quadrature_degree = 4;                // 27 points per tet (Stroud)

enum class LoadCase { gravity, traction };
const char* name_of(LoadCase load) { return load == LoadCase::gravity ? "gravity" : "traction"; }
const char* element_name(int order) { return order == 1 ? "Tet4" : "Tet10"; }

/// "nx x ny x nz", as the tables print a mesh.
std::string cells_text(const Eigen::Vector3i& cells) {
  return std::to_string(cells[0]) + "x" + std::to_string(cells[1]) + "x" + std::to_string(cells[2]);
}

/// The nodes of the clamped face z = 0 or of the loaded face z = 0.2, as a scene's box region.
kerf::NodeRegion face_region(double z) {
  kerf::NodeRegion region;
  region.box_min = Eigen::Vector3d(beam_min[0], beam_min[1], z);
  region.box_max = Eigen::Vector3d(beam_max[0], beam_max[1], z);
  return region;
}

/// The box mesh of the beam with cells[0] x cells[1] x cells[2] hex cells, six tets each;
/// promoted to Tet10 (mid-edge nodes on straight edges) for order 2.
kerf::TetMesh make_beam_mesh(const Eigen::Vector3i& cells, int order) {
  kerf::TetMesh tet4 = kerf::make_box_mesh(beam_min, beam_max, cells);
  return order == 1 ? tet4 : kerf::tet10_from_tet4(tet4);
}

/// The clamp: every node on z = 0 held at u = 0.
kerf::DirichletNodes clamp(const kerf::TetMesh& mesh) { return {kerf::nodes_in_region(mesh, face_region(0.0)), {0, 0, 0}}; }

/// The nodal loads (3#V) of a load case, assembled as chapter 1 does.
Eigen::VectorXd beam_loads(const kerf::TetMesh& mesh, const kerf::LinearMaterial& material, LoadCase load) {
  if (load == LoadCase::gravity) return kerf::assemble_gravity(mesh, material.density, gravity);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * mesh.num_nodes());
  kerf::add_uniform_traction(mesh, kerf::boundary_faces(mesh), kerf::node_mask(mesh, face_region(beam_max[2])),
                             top_total_force, f);
  return f;
}

/// One solve of the beam and what its three stages cost.
struct BeamSolution {
  kerf::TetMesh mesh;
  Eigen::VectorXd u; ///< 3#V nodal displacements
  int num_free = 0;
  double setup_seconds = 0.0;    ///< mesh, DOF map, pattern + scatter map, symbolic analysis
  double assembly_seconds = 0.0; ///< loads and stiffness into the fixed pattern
  double solve_seconds = 0.0;    ///< numeric factorisation and the two triangular solves
  double total_seconds() const { return setup_seconds + assembly_seconds + solve_seconds; }
};

/// Solves the beam once, timing the stages of chapter 1's program (make_mesh + setup_system,
/// assemble_system, solve) with the same library calls, and CHOLMOD as the solver.
BeamSolution solve_beam(const Eigen::Vector3i& cells, int order, const kerf::LinearMaterial& material, LoadCase load) {
  BeamSolution s;
  auto start = clock::now();
  s.mesh = make_beam_mesh(cells, order);
  const kerf::DofMap dofs = kerf::make_dof_map(s.mesh.num_nodes(), {clamp(s.mesh)});
  kerf::SparseAssembler assembler(s.mesh.tets, dofs);
  const auto solver = kerf::make_linear_solver(kerf::SolverSettings{});
  solver->analyze_pattern(assembler.matrix());
  s.setup_seconds = seconds_since(start);

  start = clock::now();
  Eigen::VectorXd rhs = dofs.restrict_to_free(beam_loads(s.mesh, material, load));
  kerf::assemble_linear_stiffness(s.mesh, material, assembler, rhs);
  s.assembly_seconds = seconds_since(start);

  start = clock::now();
  solver->factorize(assembler.matrix());
  Eigen::VectorXd u_free = Eigen::VectorXd::Zero(dofs.num_free);
  solver->solve(rhs, u_free);
  s.u = dofs.expand(u_free);
  s.solve_seconds = seconds_since(start);
  s.num_free = dofs.num_free;
  return s;
}

/// The best (shortest total) of `repeats` solves: on a shared machine the minimum is the time
/// the work needs, everything above it is someone else's.
BeamSolution best_of(int repeats, const Eigen::Vector3i& cells, int order, const kerf::LinearMaterial& material, LoadCase load) {
  BeamSolution best = solve_beam(cells, order, material, load);
  for (int r = 1; r < repeats; ++r) {
    BeamSolution next = solve_beam(cells, order, material, load);
    if (next.total_seconds() < best.total_seconds()) best = std::move(next);
  }
  return best;
}

/// A fine solution used as the "exact" field u(x): it locates x in its own mesh and evaluates
/// its displacement there (eq. 14). It owns its mesh, which the locator refers to, so it is
/// neither copied nor moved.
class ReferenceField {
public:
  explicit ReferenceField(BeamSolution solution)
      : mesh_(std::move(solution.mesh)), u_(std::move(solution.u)), num_free_(solution.num_free), locator_(mesh_) {
    // ||u_ref|| integrated on the reference's own mesh: no point location needed.
    norm_ = kerf::l2_error(mesh_, u_, [](const Eigen::Vector3d&) { return Eigen::Vector3d::Zero().eval(); },
                           error_quadrature_degree);
  }
  ReferenceField(const ReferenceField&) = delete;
  ReferenceField& operator=(const ReferenceField&) = delete;

  /// u_ref(x); throws if x lies outside the beam (it never should: both meshes fill the box).
  Eigen::Vector3d operator()(const Eigen::Vector3d& x) const {
    const kerf::PointLocation where = locator_.locate(x);
    if (where.tet < 0) throw std::runtime_error("reference field: point outside the beam");
    return kerf::evaluate_displacement(mesh_, u_, where.tet, where.xi);
  }
  double l2_norm() const { return norm_; }
  int num_free() const { return num_free_; }

private:
  kerf::TetMesh mesh_;
  Eigen::VectorXd u_;
  int num_free_;
  kerf::PointLocator locator_;
  double norm_ = 0.0;
};

/// Relative errors of a coarse solution against the reference: the L2 norm of eq. (83) over
/// the coarse mesh, with u_ref evaluated at the coarse quadrature points, and the x-displacement
/// at the tip point.
struct RelativeErrors {
  double l2 = 0.0;
  double tip = 0.0;
};

RelativeErrors relative_errors(const BeamSolution& coarse, const ReferenceField& reference) {
  const kerf::VectorField exact = [&reference](const Eigen::Vector3d& x) { return reference(x); };
  RelativeErrors e;
  e.l2 = kerf::l2_error(coarse.mesh, coarse.u, exact, error_quadrature_degree) / reference.l2_norm();
  const kerf::PointLocator locator(coarse.mesh);
  const kerf::PointLocation where = locator.locate(tip_point);
  const double tip_coarse = kerf::evaluate_displacement(coarse.mesh, coarse.u, where.tet, where.xi)[0];
  const double tip_reference = reference(tip_point)[0];
  e.tip = std::abs(tip_coarse - tip_reference) / std::abs(tip_reference);
  return e;
}

/// What the study runs; --quick shrinks every list to tiny meshes.
struct StudyPlan {
  std::vector<int> tet4_ladder;   ///< k of cells (1, 2, 6) k
  std::vector<int> tet10_ladder;  ///< the last rung doubles as the reference's next-coarser level
  int reference_k = 8;            ///< Tet10 reference: cells (1, 2, 6) k
  int timing_repeats = 3;
  Eigen::Vector3i locking_cells{3, 6, 20};
  Eigen::Vector3i locking_reference_cells{6, 12, 40};
  std::vector<double> locking_poisson{0.3, 0.35, 0.4, 0.45, 0.49, 0.499, 0.4999};
  std::vector<std::pair<int, int>> calculix_meshes; ///< (order, k)
  int calculix_matrix_route_max_dofs = 25000;
};

StudyPlan full_plan() {
  StudyPlan plan;
  plan.tet4_ladder = {1, 2, 3, 4, 6, 8, 11, 14};
  plan.tet10_ladder = {1, 2, 3, 4, 6};
  plan.reference_k = 8;
  plan.calculix_meshes = {{1, 4}, {1, 8}, {1, 14}, {2, 2}, {2, 4}, {2, 6}};
  return plan;
}

StudyPlan quick_plan() {
  StudyPlan plan;
  plan.tet4_ladder = {1, 2};
  plan.tet10_ladder = {1, 2};
  plan.reference_k = 3;
  plan.timing_repeats = 1;
  plan.locking_cells = {1, 2, 6};
  plan.locking_reference_cells = {2, 4, 12};
  plan.locking_poisson = {0.35, 0.4999};
  plan.calculix_meshes = {{1, 1}, {2, 1}};
  return plan;
}

Eigen::Vector3i ladder_cells(int k) { return Eigen::Vector3i(1, 2, 6) * k; }

/// One row of ladder.csv.
struct LadderRow {
  std::string element;
  Eigen::Vector3i cells;
  int k = 0;
  int dofs = 0;
  Eigen::Index tets = 0;
  LoadCase load = LoadCase::gravity;
  double assembly_s = 0, solve_s = 0, total_s = 0;
  RelativeErrors error;
};

/// The observed order of convergence between two rungs k_a < k_b: h shrinks like 1/k.
double observed_rate(double error_a, double error_b, int k_a, int k_b) {
  return std::log(error_a / error_b) / std::log(static_cast<double>(k_b) / k_a);
}

/// Runs the refinement ladder and the reference study; writes ladder.csv and reference.csv.
void run_ladder(const StudyPlan& plan, const std::filesystem::path& out) {
  const kerf::LinearMaterial material; // E = 300 kPa, nu = 0.35, rho = 1070 kg/m^3
  std::ofstream ladder(out / "ladder.csv");
  ladder << "element,load,cells,k,dofs,tets,assembly_s,solve_s,total_s,rel_l2_error,rel_tip_error\n";
  std::ofstream reference_csv(out / "reference.csv");
  reference_csv << "load,reference_cells,reference_dofs,coarser_cells,coarser_dofs,rel_l2_difference,observed_l2_rate,"
                   "estimated_reference_rel_l2_error,rel_tip_difference,observed_tip_rate,estimated_reference_rel_tip_error,"
                   "reference_solve_s\n";

  std::cout << "\nRefinement ladder, cells (1,2,6)k, errors against a Tet10 reference on cells "
            << cells_text(ladder_cells(plan.reference_k)) << "\n";
  std::printf("%-6s %-9s %-9s %8s %8s %10s %9s %9s %11s %11s\n", "elem", "load", "cells", "dofs", "tets", "assembly_s",
              "solve_s", "total_s", "rel_L2_err", "rel_tip_err");
  for (LoadCase load : {LoadCase::gravity, LoadCase::traction}) {
    const auto start = clock::now();
    const ReferenceField reference(solve_beam(ladder_cells(plan.reference_k), 2, material, load));
    const double reference_seconds = seconds_since(start);

    std::vector<LadderRow> tet10_rows;
    for (int order : {1, 2})
      for (int k : order == 1 ? plan.tet4_ladder : plan.tet10_ladder) {
        const BeamSolution s = best_of(plan.timing_repeats, ladder_cells(k), order, material, load);
        LadderRow row{element_name(order), ladder_cells(k), k, s.num_free, s.mesh.num_tets(), load,
                      s.assembly_seconds, s.solve_seconds, s.total_seconds(), relative_errors(s, reference)};
        ladder << row.element << ',' << name_of(load) << ',' << cells_text(row.cells) << ',' << k << ',' << row.dofs << ','
               << row.tets << ',' << row.assembly_s << ',' << row.solve_s << ',' << row.total_s << ',' << row.error.l2 << ','
               << row.error.tip << '\n';
        std::printf("%-6s %-9s %-9s %8d %8ld %10.4f %9.4f %9.4f %11.3e %11.3e\n", row.element.c_str(), name_of(load),
                    cells_text(row.cells).c_str(), row.dofs, static_cast<long>(row.tets), row.assembly_s, row.solve_s,
                    row.total_s, row.error.l2, row.error.tip);
        if (order == 2) tet10_rows.push_back(row);
      }

    // How good is the reference? Its difference to the finest Tet10 rung d = |u_c - u_ref| is,
    // if the error behaves like C h^p on both, e_c - e_ref = e_ref ((k_ref / k_c)^p - 1), so
    // e_ref ~ d / ((k_ref / k_c)^p - 1) (Richardson), with p observed on the last two rungs.
    const LadderRow& finer = tet10_rows.back();
    const LadderRow& coarser = tet10_rows[tet10_rows.size() - 2];
    const double ratio = static_cast<double>(plan.reference_k) / finer.k;
    const double rate_l2 = observed_rate(coarser.error.l2, finer.error.l2, coarser.k, finer.k);
    const double rate_tip = observed_rate(coarser.error.tip, finer.error.tip, coarser.k, finer.k);
    const double estimate_l2 = finer.error.l2 / (std::pow(ratio, rate_l2) - 1.0);
    const double estimate_tip = finer.error.tip / (std::pow(ratio, rate_tip) - 1.0);
    reference_csv << name_of(load) << ',' << cells_text(ladder_cells(plan.reference_k)) << ',' << reference.num_free() << ','
                  << cells_text(finer.cells) << ',' << finer.dofs << ',' << finer.error.l2 << ',' << rate_l2 << ','
                  << estimate_l2 << ',' << finer.error.tip << ',' << rate_tip << ',' << estimate_tip << ','
                  << reference_seconds << '\n';
    std::printf("reference (%s, Tet10 %s, %d dofs, %.2f s): vs next-coarser Tet10 %s: rel L2 diff %.2e (rate %.2f) "
                "-> estimated reference error %.1e; tip diff %.2e (rate %.2f) -> %.1e\n",
                name_of(load), cells_text(ladder_cells(plan.reference_k)).c_str(), reference.num_free(), reference_seconds,
                cells_text(finer.cells).c_str(), finer.error.l2, rate_l2, estimate_l2, finer.error.tip, rate_tip,
                estimate_tip);
  }
}

/// Tet4 and Tet10 on one mesh as nu -> 0.5 (gravity, E fixed), each against a fine Tet10
/// solution with the same nu; writes locking.csv.
void run_locking(const StudyPlan& plan, const std::filesystem::path& out) {
  std::ofstream csv(out / "locking.csv");
  csv << "element,poisson,cells,dofs,rel_l2_error,rel_tip_error,tip_ux_m,reference_tip_ux_m\n";
  std::cout << "\nLocking: gravity, cells " << cells_text(plan.locking_cells) << ", Tet10 reference on cells "
            << cells_text(plan.locking_reference_cells) << " at the same nu\n";
  std::printf("%-6s %-7s %8s %11s %11s %12s %12s\n", "elem", "nu", "dofs", "rel_L2_err", "rel_tip_err", "tip_ux_m", "ref_tip_ux_m");
  // The CSV lists all Tet4 rows before the Tet10 rows, so that a plot draws each as one line.
  std::ostringstream rows_of[2];
  for (double nu : plan.locking_poisson) {
    kerf::LinearMaterial material;
    material.poisson = nu;
    const ReferenceField reference(solve_beam(plan.locking_reference_cells, 2, material, LoadCase::gravity));
    const double reference_tip = reference(tip_point)[0];
    for (int order : {1, 2}) {
      const BeamSolution s = solve_beam(plan.locking_cells, order, material, LoadCase::gravity);
      const RelativeErrors e = relative_errors(s, reference);
      const kerf::PointLocator locator(s.mesh);
      const kerf::PointLocation where = locator.locate(tip_point);
      const double tip = kerf::evaluate_displacement(s.mesh, s.u, where.tet, where.xi)[0];
      rows_of[order - 1] << element_name(order) << ',' << nu << ',' << cells_text(plan.locking_cells) << ',' << s.num_free << ',' << e.l2
          << ',' << e.tip << ',' << tip << ',' << reference_tip << '\n';
      std::printf("%-6s %-7g %8d %11.3e %11.3e %12.5e %12.5e\n", element_name(order), nu, s.num_free, e.l2, e.tip, tip,
                  reference_tip);
    }
  }
  csv << rows_of[0].str() << rows_of[1].str();
}

/// Runs a shell command and returns its wall time in seconds; throws if it fails.
double timed_system(const std::string& command) {
  const auto start = clock::now();
  if (std::system(command.c_str()) != 0) throw std::runtime_error("command failed: " + command);
  return seconds_since(start);
}

/// Best-of-3 wall time of `run`, but no more repeats once 10 s have been spent: large CalculiX
/// runs take long enough that one of them is already a fair measurement.
template <class Run>
double best_wall_time(Run&& run) {
  double best = run(), spent = best;
  for (int r = 1; r < 3 && spent < 10.0; ++r) {
    const double t = run();
    best = std::min(best, t);
    spent += t;
  }
  return best;
}

/// The scene file chapter 1's program reads for the same beam, mesh and load case.
std::string beam_scene_json(const Eigen::Vector3i& cells, int order, LoadCase load) {
  std::ostringstream s;
  s.precision(17);
  s << "{\n  \"name\": \"beam\",\n  \"mesh\": {\"box\": {\"min\": [0, 0, 0], \"max\": [" << beam_max[0] << ", " << beam_max[1]
    << ", " << beam_max[2] << "], \"cells\": [" << cells[0] << ", " << cells[1] << ", " << cells[2] << "]}, \"order\": "
    << order << "},\n  \"material\": {\"young\": 300e3, \"poisson\": 0.35, \"density\": 1070},\n"
    << "  \"dirichlet\": [{\"region\": {\"box\": {\"min\": [0, 0, 0], \"max\": [" << beam_max[0] << ", " << beam_max[1]
    << ", 0]}}, \"displacement\": [0, 0, 0]}],\n";
  if (load == LoadCase::gravity)
    s << "  \"gravity\": [" << gravity[0] << ", " << gravity[1] << ", " << gravity[2] << "]\n}\n";
  else
    s << "  \"traction\": [{\"region\": {\"box\": {\"min\": [0, 0, " << beam_max[2] << "], \"max\": [" << beam_max[0] << ", "
      << beam_max[1] << ", " << beam_max[2] << "]}}, \"total_force\": [" << top_total_force[0] << ", " << top_total_force[1]
      << ", " << top_total_force[2] << "]}]\n}\n";
  return s.str();
}

/// The top-face traction as concentrated nodal forces for CalculiX, computed here from the
/// face areas and independently of kerf::add_uniform_traction: a face carries the share
/// F A_face / A_top of the total force; on a 3-node triangle a third of it goes to each corner
/// (int N_a dA = A/3), on a 6-node triangle nothing goes to the corners (int lambda(2 lambda - 1)
/// dA = 0) and a third to each mid-edge node (int 4 lambda_i lambda_j dA = A/3).
Eigen::VectorXd top_face_nodal_forces(const kerf::TetMesh& mesh) {
  const kerf::BoundaryFaces boundary = kerf::boundary_faces(mesh);
  const double z_top = beam_max[2], tolerance = 1e-9 * (beam_max - beam_min).norm();
  const auto area_of = [&](Eigen::Index f) {
    const Eigen::Vector3d x0 = mesh.nodes.row(boundary.faces(f, 0)), x1 = mesh.nodes.row(boundary.faces(f, 1)),
                          x2 = mesh.nodes.row(boundary.faces(f, 2));
    return 0.5 * (x1 - x0).cross(x2 - x0).norm();
  };
  std::vector<Eigen::Index> top;
  double top_area = 0.0;
  for (Eigen::Index f = 0; f < boundary.faces.rows(); ++f) {
    bool on_top = true;
    for (int c = 0; c < 3; ++c) on_top = on_top && std::abs(mesh.nodes(boundary.faces(f, c), 2) - z_top) < tolerance;
    if (!on_top) continue;
    top.push_back(f);
    top_area += area_of(f);
  }
  Eigen::VectorXd forces = Eigen::VectorXd::Zero(3 * mesh.num_nodes());
  for (Eigen::Index f : top) {
    const Eigen::Vector3d face_force = top_total_force * (area_of(f) / top_area);
    const int first = mesh.order() == 1 ? 0 : 3; // tri3: the corners; tri6: the mid-edge nodes
    for (int c = first; c < first + 3; ++c) forces.segment<3>(3 * boundary.faces(f, c)) += face_force / 3.0;
  }
  return forces;
}

/// max_v |u_a(v) - u_b(v)| / max_v |u_b(v)| over the nodes, for #V by 3 displacement rows.
double relative_max_difference(const Eigen::MatrixXd& u_a, const Eigen::MatrixXd& u_b) {
  return (u_a - u_b).rowwise().norm().maxCoeff() / u_b.rowwise().norm().maxCoeff();
}

/// Kerf against CalculiX on a few ladder meshes; writes calculix.csv.
void run_calculix_comparison(const StudyPlan& plan, const std::filesystem::path& out, const std::string& ccx,
                             const std::string& chapter_binary) {
  const std::filesystem::path work = out / "calculix_work";
  std::filesystem::create_directories(work);
  const kerf::LinearMaterial material;
  std::ofstream csv(out / "calculix.csv");
  csv << "element,load,cells,dofs,rel_max_diff_static,rel_max_diff_matrix,kerf_run_s,ccx_run_s,kerf_over_ccx\n";
  std::cout << "\nKerf against CalculiX (" << ccx << "), whole-run process wall times, best of up to 3\n";
  std::printf("%-6s %-9s %-9s %8s %14s %14s %10s %10s %8s\n", "elem", "load", "cells", "dofs", "diff_static", "diff_matrix",
              "kerf_s", "ccx_s", "ratio");
  for (const auto& [order, k] : plan.calculix_meshes)
    for (LoadCase load : {LoadCase::gravity, LoadCase::traction}) {
      const Eigen::Vector3i cells = ladder_cells(k);
      const BeamSolution kerf_solution = solve_beam(cells, order, material, load);
      Eigen::MatrixXd u_kerf(kerf_solution.mesh.num_nodes(), 3);
      for (Eigen::Index v = 0; v < u_kerf.rows(); ++v) u_kerf.row(v) = kerf_solution.u.segment<3>(3 * v).transpose();

      kerf::CalculixJob job;
      job.material = material;
      job.dirichlet = {clamp(kerf_solution.mesh)};
      if (load == LoadCase::gravity)
        job.gravity = gravity;
      else
        job.nodal_loads = top_face_nodal_forces(kerf_solution.mesh);
      const std::string jobname = std::string(element_name(order)) + "_" + name_of(load) + "_" + cells_text(cells);
      // ccx's own static run, as a user would start it: this one is timed, and its .dat gives
      // its displacements to the 7 digits ccx prints.
      job.procedure = kerf::CalculixProcedure::static_solve;
      kerf::write_calculix_deck(work / (jobname + ".inp"), kerf_solution.mesh, job);
      const double ccx_seconds = best_wall_time([&] { return kerf::run_calculix(ccx, work, jobname); });
      const Eigen::MatrixXd u_ccx_static =
          kerf::read_calculix_displacements(work / (jobname + ".dat"), kerf_solution.mesh.num_nodes());
      // The matrix route (ccx's own K and M, solved here in double precision) compares all
      // digits, but ccx writes the matrices as text and takes minutes on the largest meshes,
      // so we take it only up to the size limit of the plan.
      double diff_matrix = std::nan("");
      if (kerf_solution.num_free <= plan.calculix_matrix_route_max_dofs) {
        job.procedure = kerf::CalculixProcedure::matrix_storage;
        kerf::write_calculix_deck(work / (jobname + "_matrices.inp"), kerf_solution.mesh, job);
        kerf::run_calculix(ccx, work, jobname + "_matrices");
        const kerf::CalculixMatrices matrices =
            kerf::read_calculix_matrices(work / (jobname + "_matrices"), kerf_solution.mesh.num_nodes());
        diff_matrix = relative_max_difference(
            u_kerf, kerf::solve_calculix_matrices(matrices, kerf_solution.mesh.num_nodes(), job));
      }

      const std::filesystem::path scene = work / (jobname + ".json");
      std::ofstream(scene) << beam_scene_json(cells, order, load);
      // One thread, as ccx runs (kerf::run_calculix): a serial Kerf against a serial CalculiX.
      const std::string command =
          "OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 \"" + chapter_binary + "\" --quiet --scene \"" + scene.string() + "\" --out \"" + (work / jobname).string() + "\"";
      const double kerf_seconds = best_wall_time([&] { return timed_system(command); });

      const double diff_static = relative_max_difference(u_kerf, u_ccx_static);
      csv << element_name(order) << ',' << name_of(load) << ',' << cells_text(cells) << ',' << kerf_solution.num_free << ','
          << diff_static << ',' << diff_matrix << ',' << kerf_seconds << ',' << ccx_seconds << ','
          << kerf_seconds / ccx_seconds << '\n';
      std::printf("%-6s %-9s %-9s %8d %14.3e %14.3e %10.3f %10.3f %8.3f\n", element_name(order), name_of(load),
                  cells_text(cells).c_str(), kerf_solution.num_free, diff_static, diff_matrix, kerf_seconds, ccx_seconds,
                  kerf_seconds / ccx_seconds);
    }
  std::filesystem::remove_all(work);
}

} // namespace beam_study

/// `01_beam_study [--quick] [--out DIR]`: see the header comment.
int main(int argc, char** argv) {
  try {
    const std::optional<kerf_measure::RunOptions> options =
        kerf_measure::parse_run_options(argc, argv, "01_beam_study [--quick] [--out DIR] [--only ladder,locking,calculix]",
                                        "output/beam_study", {"ladder", "locking", "calculix"});
    if (!options) return 2;
    const bool quick = options->quick;
    const std::filesystem::path& out = options->out;
    std::filesystem::create_directories(out);
    const beam_study::StudyPlan plan = quick ? beam_study::quick_plan() : beam_study::full_plan();
    const auto start = beam_study::clock::now();
    if (options->runs("ladder")) beam_study::run_ladder(plan, out);
    if (options->runs("locking")) beam_study::run_locking(plan, out);
    if (options->runs("calculix")) {
      const std::string ccx = KERF_CCX;
      if (ccx.empty())
        std::cout << "\nccx not found at configure time: no CalculiX comparison\n";
      else
        beam_study::run_calculix_comparison(plan, out, ccx, KERF_CHAPTER01_BINARY);
    }
    std::cout << "\nwrote " << out.string() << "/*.csv in " << beam_study::seconds_since(start) << " s\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "01_beam_study: " << e.what() << '\n';
    return 3;
  }
}
