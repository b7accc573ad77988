/* Kerf, chapter 5 study: how far the demo's cut opens, on meshes fine enough to say what the
   answer is.

   Build:   cmake --preset release && cmake --build --preset release --target 05_opening_study

   Sample runs:
     05_opening_study --quick --out output/opening_study_quick
     05_opening_study --out figures/05_crack_tip
     05_opening_study --only forces --out /tmp/o

   Description: chapter 5's demo (chapters/05_crack_tip/main.cpp): the beam [0, 0.03] x
   [0, 0.06] x [0, 0.2] m, E = 300 kPa, nu = 0.35, Tet4, clamped at z = 0, cut by the rectangle
   [0, 0.015] x [0, 0.06] x {0.1}, its top edge x = 0, z = 0.2 moved up by d = 0.02 m. Measured
   on each mesh: the opening u_z(z = 0.1005) - u_z(z = 0.0995) at y = 0.03 at the crack's mouth
   x = 0 and at x = 0.0075, and the force F on the pulled edge, from the strain energy
   W = F d / 2.

   A displacement prescribed on a line has no mesh-independent answer: a line has no capacity in
   3D elasticity (its H^1 functions have no trace there), so the energy needed to move it, and F,
   fall like 1 / ln(1 / h) on finer meshes, and every field in the limit is zero. What a finer
   mesh can check is the body's response to the forces the demo's edge exerts: the reactions
   R_i at the demo's seven edge nodes (0, 0.01 i, 0.2), applied as loads with the edge free, give
   the demo's solution back on the demo's mesh (the same equations), and a problem whose opening,
   0.1 m from the loads, has a limit. The opening is linear in the loads, so each mesh is
   factorised once and solved for a unit force along x, y and z at each of the seven nodes: 21
   influence coefficients, from which the opening under the edge forces of any run follows. The
   parts:
     demo        the demo (default radius), and its scene with the topological rule and with
                 chapter 4's ("enrichment": "none") on its 3 x 6 x 19 mesh: their openings and
                 edge reactions (always run);
     line        the prescribed edge displacement on conforming box meshes nx x 2 nx x nz (nx and
                 nz even: node planes on x = 0.015 and z = 0.1; nz the even number nearest
                 19 nx / 3, the demo's proportion), opened along the rectangle by duplicated nodes
                 (chapter 3's split_mesh_along_cut), and the same meshes uncut: F falls on and on;
     forces      the three runs' edge forces, as point forces and as a line load (below), on
                 conforming meshes 6k x 12k x 38k (k = 1..4) and on XFEM meshes 3m x 6m x 19m
                 (m = 1, 3, 5, 7: the front through the middle of a row of cells, as on the demo's
                 3 x 6 x 19), solved by the program's own steps (scene, pieces, crack-tip
                 enrichment with the scene's rules) with a fixed radius of 0.01 m (geometric,
                 Laborde et al. 2005), the default radius (two mean edges of the front's tets: the
                 demo refined) and radius 0 (topological). Every one of these meshes has the
                 demo's edge nodes.
   It writes opening.csv (one row per mesh and load, as it goes) and prints each row, then each
   ladder's limit by Richardson's extrapolation with the observed order of its last three meshes,
   and of the three before them (opening_limits.csv), and the reference of each run's opening:
   the mean of the four ladders' limits under its forces, with their spread
   (opening_reference.csv). --quick runs every part on its smallest meshes (a test).

   Read chapter 5 first. */

#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/cut/split_mesh_along_cut.hpp"
#include "kerf/fem/assemble_stiffness.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/evaluate_displacement.hpp"
#include "kerf/fem/linear_material.hpp"
#include "kerf/fem/solve_linear_static.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/fem/tet_stiffness.hpp"
#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/point_locator.hpp"
#include "kerf/scene/cut_xfem_loads.hpp"
#include "kerf/scene/scene.hpp"
#include "kerf/scene/scene_crack_tip.hpp"
#include "kerf/scene/scene_cuts.hpp"
#include "kerf/scene/scene_mesh.hpp"
#include "kerf/scene/scene_quadrature.hpp"
#include "kerf/scene/scene_xfem_dofs.hpp"
#include "kerf/solve/linear_solver.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"
#include "measure.hpp" // bench/measure.hpp: the command line shared with the benchmarks

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace opening_study {

using clock = std::chrono::steady_clock;
double seconds_since(clock::time_point start) { return std::chrono::duration<double>(clock::now() - start).count(); }
const double not_a_number = std::numeric_limits<double>::quiet_NaN();

const kerf::LinearMaterial material{300e3, 0.35, 1070};
const double pull = 0.02; // m, the edge x = 0, z = 0.2 moved along +z

std::string cells_text(const Eigen::Vector3i& c) {
  return std::to_string(c[0]) + "x" + std::to_string(c[1]) + "x" + std::to_string(c[2]);
}

// @sect3{The load on the top edge}
//
// Either the demo's: the edge x = 0, z = 0.2 moved by (0, 0, d), every node on it held there. Or
// forces R_i at the demo's seven edge nodes y_i = 0.01 i, i = 0 .. 6, with the edge otherwise
// free, in one of two readings that give the same nodal loads on the demo's mesh:
//   points  a point force R_i at (0, y_i, 0.2);
//   line    a line load q(y) = sum_i q_i phi_i(y) along the edge, phi_i the demo's hats, with
//           sum_j M_ij q_j = R_i (M_ij = int phi_i phi_j dy: its consistent nodal loads on the
//           demo's mesh are R_i); on a mesh whose edge nodes include the y_i its nodal loads are
//           int psi_k q dy, psi_k that mesh's hats along the edge, exact by Simpson's rule.
// The two differ within 0.01 m of the edge, 0.1 m from the cut; what Saint-Venant's principle
// leaves of that at the cut is the difference of their openings (the study measures it).
enum class Reading { points, line };
const char* name(Reading r) { return r == Reading::points ? "points" : "line_load"; }

const int edge_nodes = 7;              // the demo's, at y = 0, 0.01, ..., 0.06
const double demo_spacing = 0.01;      // m
const int edge_loads = 3 * edge_nodes; // a unit force along x, y, z at each

bool on_edge(const Eigen::Vector3d& x) { return std::abs(x.z() - 0.2) < 1e-12 && std::abs(x.x()) < 1e-12; }

/// i if x is the demo's edge node (0, 0.01 i, 0.2), else -1.
int edge_node_index(const Eigen::Vector3d& x) {
  if (!on_edge(x)) return -1;
  const long i = std::lround(x.y() / demo_spacing);
  return std::abs(x.y() - demo_spacing * static_cast<double>(i)) < 1e-12 ? static_cast<int>(i) : -1;
}

/// q_i from sum_j M_ij q_j = R_i, M the mass matrix of the demo's hats along the edge
/// (tridiagonal: L / 3 at the ends, 2 L / 3 inside, L / 6 beside the diagonal).
std::vector<Eigen::Vector3d> line_density(const std::vector<Eigen::Vector3d>& R) {
  const auto n = static_cast<Eigen::Index>(R.size());
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n), rhs(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    M(i, i) = (i == 0 || i == n - 1 ? 1.0 : 2.0) * demo_spacing / 3.0;
    if (i + 1 < n) M(i, i + 1) = M(i + 1, i) = demo_spacing / 6.0;
    rhs.row(i) = R[static_cast<std::size_t>(i)].transpose();
  }
  const Eigen::MatrixXd q = M.partialPivLu().solve(rhs);
  std::vector<Eigen::Vector3d> density;
  for (Eigen::Index i = 0; i < n; ++i) density.emplace_back(q.row(i).transpose());
  return density;
}

/// The nodal loads of the forces R_i, read as `reading`, added to the first 3 #V DOFs of f (the
/// standard ones).
void add_edge_forces(const kerf::TetMesh& mesh, Reading reading, const std::vector<Eigen::Vector3d>& R,
                     Eigen::VectorXd& f) {
  std::vector<std::pair<double, Eigen::Index>> edge; // (y, node), sorted by y
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v)
    if (on_edge(mesh.nodes.row(v).transpose())) edge.emplace_back(mesh.nodes(v, 1), v);
  std::sort(edge.begin(), edge.end());
  int found = 0;
  for (const auto& [y, v] : edge) found += edge_node_index(mesh.nodes.row(v).transpose()) >= 0;
  if (found != edge_nodes) throw std::runtime_error("the mesh lacks some of the demo's edge nodes");
  if (reading == Reading::points) {
    for (const auto& [y, v] : edge)
      if (const int i = edge_node_index(mesh.nodes.row(v).transpose()); i >= 0)
        f.segment<3>(3 * v) += R[static_cast<std::size_t>(i)];
    return;
  }
  const std::vector<Eigen::Vector3d> q = line_density(R);
  const auto q_at = [&](double y) { // linear between the demo's nodes
    const auto i = std::min<std::size_t>(static_cast<std::size_t>(std::max(0.0, y / demo_spacing)), q.size() - 2);
    const double s = y / demo_spacing - static_cast<double>(i);
    return Eigen::Vector3d((1.0 - s) * q[i] + s * q[i + 1]);
  };
  for (std::size_t k = 0; k + 1 < edge.size(); ++k) {
    // On [y_a, y_b], inside one of the demo's intervals, q is linear: int psi_a q = l (2 q_a + q_b) / 6.
    const double ya = edge[k].first, yb = edge[k + 1].first, l = yb - ya;
    const Eigen::Vector3d qa = q_at(ya), qb = q_at(yb);
    f.segment<3>(3 * edge[k].second) += l * (2.0 * qa + qb) / 6.0;
    f.segment<3>(3 * edge[k + 1].second) += l * (qa + 2.0 * qb) / 6.0;
  }
}

/// Unit load number `load` of the 21: a unit force along x, y or z (load % 3) at the demo's edge
/// node load / 3.
std::vector<Eigen::Vector3d> unit_edge_force(int load) {
  std::vector<Eigen::Vector3d> R(edge_nodes, Eigen::Vector3d::Zero());
  R[static_cast<std::size_t>(load / 3)][load % 3] = 1.0;
  return R;
}

/// The 21 numbers R_{i,c}, node by node.
Eigen::VectorXd stacked(const std::vector<Eigen::Vector3d>& R) {
  Eigen::VectorXd r(edge_loads);
  for (int i = 0; i < edge_nodes; ++i) r.segment<3>(3 * i) = R[static_cast<std::size_t>(i)];
  return r;
}

// @sect3{What is measured}

/// The probes: 0.5 mm above and below the cut plane at y = 0.03, at the mouth x = 0 and at
/// x = 0.0075, half-way to the front (the rows of chapter 5's test of the demo).
Eigen::MatrixXd probe_points() {
  Eigen::MatrixXd p(4, 3);
  p << 0.0, 0.03, 0.1005, 0.0, 0.03, 0.0995, 0.0075, 0.03, 0.1005, 0.0075, 0.03, 0.0995;
  return p;
}

/// The openings at the mouth and at x = 0.0075 from the four probes' displacements.
Eigen::Vector2d openings(const Eigen::MatrixXd& at_probes) {
  return {at_probes(0, 2) - at_probes(1, 2), at_probes(2, 2) - at_probes(3, 2)};
}

struct Row {
  std::string part, method, forces_of = "-";
  Eigen::Vector3i cells{0, 0, 0};
  double h = 0.0; ///< the cells' width in x, 0.03 / nx (m)
  int unknowns = 0, branch_nodes = 0;
  double radius = not_a_number; ///< the enrichment radius (m), 0 topological; NaN without branch functions
  Eigen::Vector2d opening{not_a_number, not_a_number}; ///< at x = 0 and x = 0.0075 (m)
  double force = 0.0;                                  ///< on the edge along z (N): 2 W / d, or the sum of the loads
  double seconds = 0.0;
};

/// The element stiffness of plain Tet4 FEM times the element's displacements.
Eigen::Matrix<double, 12, 1> tet4_force(const kerf::TetMesh& mesh, Eigen::Index t, const Eigen::VectorXd& u) {
  Eigen::Matrix<double, 12, 1> ue;
  for (int a = 0; a < 4; ++a) ue.segment<3>(3 * a) = u.segment<3>(3 * mesh.tets(t, a));
  return kerf::tet4_stiffness(kerf::tet_corners(mesh, t), material) * ue;
}

/// The strain energy 1/2 u^T K u of plain Tet4 FEM, tet by tet.
double tet4_energy(const kerf::TetMesh& mesh, const Eigen::VectorXd& u) {
  double W = 0.0;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    Eigen::Matrix<double, 12, 1> ue;
    for (int a = 0; a < 4; ++a) ue.segment<3>(3 * a) = u.segment<3>(3 * mesh.tets(t, a));
    W += 0.5 * ue.dot(tet4_force(mesh, t, u));
  }
  return W;
}

/// The reactions at the demo's edge nodes, (K u)_v summed over the tets around each: every such
/// tet must be a plain Tet4 (`plain`), where K_e u_e is chapter 1's. Their z-components add up
/// to F = 2 W / d (the study prints both).
std::vector<Eigen::Vector3d> edge_reactions(const kerf::TetMesh& mesh, const Eigen::VectorXd& u,
                                            const std::function<bool(Eigen::Index)>& plain) {
  std::vector<Eigen::Vector3d> R(edge_nodes, Eigen::Vector3d::Zero());
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    bool touches = false;
    for (int a = 0; a < 4; ++a) touches = touches || edge_node_index(mesh.nodes.row(mesh.tets(t, a)).transpose()) >= 0;
    if (!touches) continue;
    if (!plain(t)) throw std::runtime_error("a tet at the pulled edge is cut or enriched");
    const Eigen::Matrix<double, 12, 1> f = tet4_force(mesh, t, u);
    for (int a = 0; a < 4; ++a)
      if (const int i = edge_node_index(mesh.nodes.row(mesh.tets(t, a)).transpose()); i >= 0)
        R[static_cast<std::size_t>(i)] += f.segment<3>(3 * a);
  }
  return R;
}

// @sect3{The influence of the edge forces on the opening}
//
// The openings under the 21 unit edge forces, in each reading: two 2 x 21 matrices G, so that the
// openings under forces R are G stacked(R). K_ff is factorised once: the clamp prescribes zeros,
// so a load's right-hand side is its free part, nothing lifted.
struct Influence {
  Eigen::Vector3i cells{0, 0, 0};
  int unknowns = 0, branch_nodes = 0;
  double radius = not_a_number;
  Eigen::MatrixXd points = Eigen::MatrixXd::Zero(2, edge_loads), line = Eigen::MatrixXd::Zero(2, edge_loads);
  double seconds = 0.0;
};

/// G of both readings for a clamped body: `K_ff` its stiffness, `size` its DOFs,
/// `opening_of(u)` the openings of a solution.
void fill_influence(Influence& influence, const kerf::TetMesh& mesh, const kerf::DofMap& dofs,
                    const Eigen::SparseMatrix<double>& K_ff, Eigen::Index size,
                    const std::function<Eigen::Vector2d(const Eigen::VectorXd&)>& opening_of) {
  const std::unique_ptr<kerf::LinearSolver> solver = kerf::make_linear_solver(kerf::SolverSettings{});
  solver->analyze_pattern(K_ff);
  solver->factorize(K_ff);
  for (const Reading reading : {Reading::points, Reading::line})
    for (int load = 0; load < edge_loads; ++load) {
      Eigen::VectorXd f = Eigen::VectorXd::Zero(size);
      add_edge_forces(mesh, reading, unit_edge_force(load), f);
      Eigen::VectorXd x = Eigen::VectorXd::Zero(dofs.num_free);
      solver->solve(dofs.restrict_to_free(f), x);
      (reading == Reading::points ? influence.points : influence.line).col(load) = opening_of(dofs.expand(x));
    }
  influence.unknowns = dofs.num_free;
}

kerf::DirichletNodes clamp(const kerf::TetMesh& mesh) {
  kerf::DirichletNodes clamped;
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v)
    if (std::abs(mesh.nodes(v, 2)) < 1e-12) clamped.nodes.push_back(static_cast<int>(v));
  return clamped;
}

// @sect3{Conforming FEM}

/// The beam on a box mesh, opened along the rectangle if `cut` (the mesh must then have node
/// planes on x = 0.015 and z = 0.1).
kerf::TetMesh conforming_mesh(const Eigen::Vector3i& cells, bool cut) {
  const kerf::TetMesh box = kerf::make_box_mesh({0, 0, 0}, {0.03, 0.06, 0.2}, cells);
  return cut ? kerf::split_mesh_along_cut(box, kerf::RectangleCut({0, 0, 0.1}, {0.015, 0, 0}, {0, 0.06, 0}), 1e-9).mesh
             : box;
}

/// The part "line": the edge pulled by d, on a conforming mesh, cut or not.
Row pull_conforming(const Eigen::Vector3i& cells, bool cut) {
  Row row{"line", cut ? "conforming" : "uncut", "-", cells, 0.03 / cells[0]};
  const auto start = clock::now();
  const kerf::TetMesh mesh = conforming_mesh(cells, cut);
  kerf::DirichletNodes pulled;
  pulled.displacement = {0, 0, pull};
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v)
    if (on_edge(mesh.nodes.row(v).transpose())) pulled.nodes.push_back(static_cast<int>(v));
  const kerf::DofMap dofs = kerf::make_dof_map(mesh.num_nodes(), {clamp(mesh), pulled});
  const Eigen::VectorXd u = kerf::solve_linear_static(mesh, material, dofs, Eigen::VectorXd::Zero(3 * mesh.num_nodes()),
                                                      kerf::SolverSettings{});
  row.unknowns = dofs.num_free;
  row.force = 2.0 * tet4_energy(mesh, u) / pull;
  if (cut) {
    Eigen::Index outside = 0;
    row.opening = openings(kerf::evaluate_displacement_at(mesh, u, probe_points(), outside));
    if (outside != 0) throw std::runtime_error("a probe lies outside the conforming mesh " + cells_text(cells));
  }
  row.seconds = seconds_since(start);
  return row;
}

/// The part "forces" on a conforming mesh.
Influence conforming_influence(const Eigen::Vector3i& cells) {
  Influence influence{cells};
  const auto start = clock::now();
  const kerf::TetMesh mesh = conforming_mesh(cells, true);
  const kerf::DofMap dofs = kerf::make_dof_map(mesh.num_nodes(), {clamp(mesh)});
  kerf::SparseAssembler assembler(mesh.tets, dofs);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(dofs.num_free);
  kerf::assemble_linear_stiffness(mesh, material, assembler, rhs);
  const Eigen::MatrixXd points = probe_points();
  fill_influence(influence, mesh, dofs, assembler.matrix(), 3 * mesh.num_nodes(), [&](const Eigen::VectorXd& u) {
    Eigen::Index outside = 0;
    const Eigen::MatrixXd at = kerf::evaluate_displacement_at(mesh, u, points, outside);
    if (outside != 0) throw std::runtime_error("a probe lies outside the conforming mesh " + cells_text(cells));
    return openings(at);
  });
  influence.seconds = seconds_since(start);
  return influence;
}

// @sect3{XFEM: the demo's scene}

/// The demo's scene (chapters/05_crack_tip/main.cpp) on `cells` with `crack_tip` (JSON); the
/// edge's prescribed displacement only if `pulled`.
std::string demo_scene(const Eigen::Vector3i& cells, const std::string& crack_tip, bool pulled) {
  const std::string edge =
      R"(, {"region": {"box": {"min": [0, 0, 0.2], "max": [0, 0.06, 0.2]}}, "displacement": [0, 0, 0.02]})";
  return R"({"name": "beam", "mesh": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0.2], "cells": [)" +
         std::to_string(cells[0]) + ", " + std::to_string(cells[1]) + ", " + std::to_string(cells[2]) +
         R"(]}, "order": 1},
  "material": {"young": 300e3, "poisson": 0.35, "density": 1070}, "model": "linear",
  "dirichlet": [{"region": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0]}}})" +
         (pulled ? edge : std::string()) + R"(],
  "cuts": [{"rectangle": {"origin": [0, 0, 0.1], "edge1": [0.015, 0, 0], "edge2": [0, 0.06, 0]}}],
  "crack_tip": )" +
         crack_tip + "}";
}

/// The program's model of the demo's scene (chapter 5's CrackTip: scene, mesh, cuts, pieces,
/// crack-tip enrichment with the scene's rules, DOF map), built in place: the model refers to
/// the rest.
struct XfemBody {
  kerf::Scene scene;
  kerf::TetMesh mesh;
  kerf::CutSurfaces cuts;
  kerf::MeshPieces pieces;
  kerf::SceneCrackTip tip;
  kerf::PieceRuleFunction rule;
  kerf::CutXfemModel model;
  kerf::DofMap dofs;

  XfemBody(const Eigen::Vector3i& cells, const std::string& crack_tip, bool pulled)
      : scene(kerf::parse_scene(demo_scene(cells, crack_tip, pulled), "opening study", ".")),
        mesh(kerf::make_scene_mesh(scene, &std::cerr)), cuts(kerf::scene_cut_surfaces(scene, &std::cerr)),
        pieces(kerf::scene_mesh_pieces(scene, mesh, cuts, &std::cerr)), tip(scene, mesh, pieces, cuts, &std::cerr),
        rule(kerf::scene_piece_rule(scene, mesh.order())),
        model(mesh, scene.material, pieces, tip.sign_enrichment(), rule, tip.tip_functions()),
        dofs(kerf::scene_cut_xfem_dof_map(scene, model, tip.fronts(), &std::cerr)) {}
  XfemBody(const XfemBody&) = delete;
  XfemBody& operator=(const XfemBody&) = delete;

  Eigen::Vector2d opening(const Eigen::VectorXd& u, const kerf::PointLocator& locator) const {
    const Eigen::MatrixXd points = probe_points();
    Eigen::MatrixXd at(points.rows(), 3);
    for (Eigen::Index p = 0; p < points.rows(); ++p) {
      const Eigen::Vector3d x = points.row(p).transpose();
      const kerf::PointLocation where = locator.locate(x);
      if (where.tet < 0) throw std::runtime_error("a probe lies outside the XFEM mesh");
      at.row(p) = model.displacement_at(u, where.tet, x).transpose();
    }
    return openings(at);
  }
};

/// The part "demo": the program's run of the demo's scene with `crack_tip`, and the reactions of
/// its pulled edge.
Row pull_xfem(const std::string& method, const std::string& crack_tip, std::vector<Eigen::Vector3d>& reactions) {
  const Eigen::Vector3i cells(3, 6, 19);
  Row row{"demo", method, "-", cells, 0.03 / cells[0]};
  const auto start = clock::now();
  const XfemBody body(cells, crack_tip, true);
  const Eigen::VectorXd f = kerf::cut_xfem_scene_loads(body.scene, body.model, kerf::boundary_faces(body.mesh));
  const Eigen::VectorXd u = kerf::solve_linear_cut_xfem(body.model, body.dofs, f, body.scene.solver);
  row.unknowns = body.dofs.num_free;
  row.branch_nodes = body.tip.num_branch_nodes();
  row.radius = body.tip.branch() ? body.tip.radius() : not_a_number;
  row.force = 2.0 * body.model.energy(u, false) / pull;
  reactions = edge_reactions(body.mesh, u, [&](Eigen::Index t) {
    return !body.model.has_branch_functions(t) && body.pieces.entry[static_cast<std::size_t>(t)] < 0;
  });
  row.opening = body.opening(u, kerf::PointLocator(body.mesh));
  row.seconds = seconds_since(start);
  return row;
}

/// The part "forces" on an XFEM mesh.
Influence xfem_influence(const Eigen::Vector3i& cells, const std::string& crack_tip) {
  Influence influence{cells};
  const auto start = clock::now();
  const XfemBody body(cells, crack_tip, false);
  kerf::SparseAssembler assembler(body.model.assembly_slots(), body.dofs);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(body.dofs.num_free);
  body.model.assemble_linear_stiffness(assembler, rhs);
  const kerf::PointLocator locator(body.mesh);
  fill_influence(influence, body.mesh, body.dofs, assembler.matrix(), 3 * body.model.num_dof_nodes(),
                 [&](const Eigen::VectorXd& u) { return body.opening(u, locator); });
  influence.branch_nodes = body.tip.num_branch_nodes();
  influence.radius = body.tip.branch() ? body.tip.radius() : not_a_number;
  influence.seconds = seconds_since(start);
  return influence;
}

// @sect3{Output}

const char* csv_header =
    "part,method,forces_of,cells,h,unknowns,branch_nodes,radius,opening_mouth,opening_middle,force,seconds";

void print(std::ostream& out, const Row& r) {
  out << r.part << ',' << r.method << ',' << r.forces_of << ',' << cells_text(r.cells) << ',' << r.h << ','
      << r.unknowns << ',' << r.branch_nodes << ',' << r.radius << ',' << r.opening[0] << ',' << r.opening[1] << ','
      << r.force << ',' << r.seconds << '\n';
}

// @sect3{Richardson's extrapolation}

/// f(h) = f_0 + C h^p through three points h_1 > h_2 > h_3: p from
/// (f_1 - f_2) / (f_2 - f_3) = (h_1^p - h_2^p) / (h_2^p - h_3^p), by bisection on (0.05, 6) (the
/// right side grows with p for any h_1 > h_2 > h_3); NaN if the three values are not monotone
/// or p falls outside the bracket.
struct Extrapolation {
  double order = not_a_number, limit = not_a_number;
};

Extrapolation richardson(const double h[3], const double f[3]) {
  Extrapolation e;
  const double d12 = f[0] - f[1], d23 = f[1] - f[2];
  if (d12 * d23 <= 0.0) return e;
  const double target = d12 / d23;
  const auto ratio = [&](double p) {
    return (std::pow(h[0], p) - std::pow(h[1], p)) / (std::pow(h[1], p) - std::pow(h[2], p));
  };
  double lo = 0.05, hi = 6.0;
  if (target < ratio(lo) || target > ratio(hi)) return e;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (ratio(mid) < target ? lo : hi) = mid;
  }
  e.order = 0.5 * (lo + hi);
  const double C = d23 / (std::pow(h[1], e.order) - std::pow(h[2], e.order));
  e.limit = f[2] - C * std::pow(h[2], e.order);
  return e;
}

/// For each ladder (part, method and whose forces) with three meshes or more: the extrapolation
/// of the opening at the mouth (and of the force, in the part "line") from its last three
/// meshes, and from the three before them. Then, for each run's forces and each reading, the
/// reference: the mean of its ladders' limits, and half their spread.
void write_limits(const std::vector<Row>& rows, const std::filesystem::path& out) {
  std::map<std::string, std::vector<const Row*>> ladders;
  for (const Row& r : rows)
    if (r.part != "demo") ladders[r.part + "," + r.method + "," + r.forces_of].push_back(&r);
  std::ofstream csv(out / "opening_limits.csv");
  csv << "part,method,forces_of,quantity,meshes,h_finest,finest,order,limit,order_before,limit_before\n";
  std::printf("\nRichardson's extrapolation (the last three meshes; the three before them):\n");
  std::map<std::string, std::vector<double>> limits; // by part and forces
  for (const auto& [name, ladder] : ladders) {
    if (ladder.size() < 3) continue;
    std::vector<std::pair<std::string, double (*)(const Row&)>> quantities = {
        {"opening_mouth", [](const Row& r) { return r.opening[0]; }}};
    if (ladder.front()->part == "line")
      quantities.emplace_back("force", [](const Row& r) { return r.force; }); // fixed elsewhere
    for (const auto& [quantity, value] : quantities) {
      const auto fit = [&](std::size_t last) {
        const double h[3] = {ladder[last - 2]->h, ladder[last - 1]->h, ladder[last]->h};
        const double f[3] = {value(*ladder[last - 2]), value(*ladder[last - 1]), value(*ladder[last])};
        return richardson(h, f);
      };
      const std::size_t last = ladder.size() - 1;
      const Extrapolation now = fit(last), before = ladder.size() >= 4 ? fit(last - 1) : Extrapolation{};
      csv << name << ',' << quantity << ',' << ladder.size() << ',' << ladder[last]->h << ',' << value(*ladder[last])
          << ',' << now.order << ',' << now.limit << ',' << before.order << ',' << before.limit << '\n';
      std::printf("  %-40s %-14s finest %-11.6g order %5.2f limit %-11.6g (before: order %5.2f limit %.6g)\n",
                  name.c_str(), quantity.c_str(), value(*ladder[last]), now.order, now.limit, before.order,
                  before.limit);
      if (ladder.front()->part != "line")
        limits[ladder.front()->part + "," + ladder.front()->forces_of].push_back(now.limit);
    }
  }
  std::ofstream reference(out / "opening_reference.csv");
  reference << "part,forces_of,ladders,reference,half_spread,demo_opening,demo_over_reference\n";
  std::printf(
      "\nThe reference of each run's opening at the mouth (the mean of its ladders' limits, +- half their spread):\n");
  for (const auto& [name, values] : limits) {
    double sum = 0.0, lo = values.front(), hi = values.front();
    for (const double v : values) {
      sum += v;
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    const double mean = sum / static_cast<double>(values.size());
    const std::string forces_of = name.substr(name.find(',') + 1);
    double demo = not_a_number;
    for (const Row& r : rows)
      if (r.part == "demo" && r.method == forces_of) demo = r.opening[0];
    reference << name << ',' << values.size() << ',' << mean << ',' << 0.5 * (hi - lo) << ',' << demo << ','
              << demo / mean << '\n';
    std::printf("  %-24s %zu ladders: %.6g m +- %.2g (%.2f %%); the run on 3x6x19 opens %.6g m, %.4f of it\n",
                name.c_str(), values.size(), mean, 0.5 * (hi - lo), 50.0 * (hi - lo) / mean, demo, demo / mean);
  }
}

} // namespace opening_study

int main(int argc, char** argv) {
  namespace os = opening_study;
  const auto options =
      kerf_measure::parse_run_options(argc, argv, "05_opening_study [--quick] [--out DIR] [--only line,forces]",
                                      "output/opening_study", {"line", "forces"});
  if (!options) return 2;
  try {
    std::filesystem::create_directories(options->out);
    std::cout << "Kerf chapter 5 opening study" << (options->quick ? " (quick)" : "") << " on "
              << kerf_measure::cpu_model() << "\n";
    const auto start = os::clock::now();
    std::ofstream csv(options->out / "opening.csv");
    csv << os::csv_header << '\n';
    std::cout << os::csv_header << '\n';
    std::vector<os::Row> rows;
    const auto keep = [&](const os::Row& row) {
      rows.push_back(row);
      os::print(csv, row);
      csv.flush();
      os::print(std::cout, row);
      std::cout.flush();
    };
    // The demo, and its scene with the topological rule and with chapter 4's: their openings and
    // the reactions of their pulled edges.
    const std::vector<std::pair<std::string, std::string>> runs = {{"default", R"({"enrichment": "branch"})"},
                                                                   {"topological", R"({"radius": 0})"},
                                                                   {"none", R"({"enrichment": "none"})"}};
    std::map<std::string, std::vector<Eigen::Vector3d>> reactions;
    for (const auto& [method, crack_tip] : runs) {
      keep(os::pull_xfem(method, crack_tip, reactions[method]));
      std::printf("its edge reactions (N) at y = 0, 0.01, ..., 0.06:\n");
      double sum_z = 0.0;
      for (const Eigen::Vector3d& R : reactions[method]) {
        std::printf("  %12.6g %12.6g %12.6g\n", R.x(), R.y(), R.z());
        sum_z += R.z();
      }
      std::printf("  sum of z: %.9g N against 2 W / d = %.9g N\n", sum_z, rows.back().force);
    }
    if (options->runs("line")) {
      // nx x 2 nx x nz, nz the even number nearest 19 nx / 3.
      const auto cells = [](int nx) {
        const double target = 19.0 * nx / 3.0;
        int nz = static_cast<int>(std::lround(target));
        if (nz % 2 == 1) nz += target > nz ? 1 : -1;
        return Eigen::Vector3i(nx, 2 * nx, nz);
      };
      const std::vector<int> ladder =
          options->quick ? std::vector<int>{2} : std::vector<int>{2, 4, 6, 8, 10, 12, 14, 16};
      for (const bool cut : {true, false})
        for (const int nx : ladder) keep(os::pull_conforming(cells(nx), cut));
    }
    if (options->runs("forces")) {
      // Each mesh once, its openings under every run's forces in both readings.
      const auto rows_of = [&](const std::string& method, const os::Influence& influence) {
        for (const os::Reading reading : {os::Reading::points, os::Reading::line})
          for (const auto& [run, crack_tip] : runs) {
            os::Row row{os::name(reading),
                        method,
                        run,
                        influence.cells,
                        0.03 / influence.cells[0],
                        influence.unknowns,
                        influence.branch_nodes,
                        influence.radius};
            row.opening =
                (reading == os::Reading::points ? influence.points : influence.line) * os::stacked(reactions[run]);
            for (const Eigen::Vector3d& R : reactions[run]) row.force += R.z();
            row.seconds = influence.seconds;
            keep(row);
          }
      };
      for (const int k : options->quick ? std::vector<int>{1} : std::vector<int>{1, 2, 3, 4})
        rows_of("conforming", os::conforming_influence({6 * k, 12 * k, 38 * k}));
      for (const auto& [method, crack_tip] :
           std::vector<std::pair<std::string, std::string>>{{"radius_0.01", R"({"radius": 0.01})"},
                                                            {"default", R"({"enrichment": "branch"})"},
                                                            {"topological", R"({"radius": 0})"}})
        for (const int m : options->quick ? std::vector<int>{1} : std::vector<int>{1, 3, 5, 7})
          rows_of(method, os::xfem_influence({3 * m, 6 * m, 19 * m}, crack_tip));
    }
    os::write_limits(rows, options->out);
    std::printf("\ntotal %.1f s\n", os::seconds_since(start));
  } catch (const std::exception& error) {
    std::cerr << "05_opening_study: " << error.what() << '\n';
    return 1;
  }
  return 0;
}
