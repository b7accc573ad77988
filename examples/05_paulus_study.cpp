/* Kerf, chapter 5 study: Paulus's beam (Fig. 9) with the cut kept partial, chapter 3's front
   sweep again, and partial cuts with curved fronts.

   Build:   cmake --preset release && cmake --build --preset release --target 05_paulus_study

   Sample runs:
     05_paulus_study --quick --out output/paulus_study_quick
     05_paulus_study --out figures/05_crack_tip                   (all three parts)
     05_paulus_study --only sweep --out figures/05_crack_tip      (one part: fig9, sweep, partial)

   Description: Paulus's beam (Paulus et al., section 5.1): [0, 0.03] x [0, 0.06] x [0, 0.2] m, E = 300 kPa,
   nu = 0.35, rho = 1070 kg/m^3, clamped at z = 0, linear. The program writes, into --out:
     paulus.csv   Fig. 9 again: the half-depth cut [0, 0.015] x [0, 0.06] x {0.1}, whose front
                  x = 0.015 runs through the middle of the XFEM meshes' elements, under two
                  loads: gravity 9.81 m/s^2 along +x, and a tip traction, 1 N along +z spread
                  uniformly over the face z = 0.2 (Paulus pulls the EDGE x = 0, z = 0.2 up by
                  2 cm, a singular condition no mesh converges for; the uniform pull opens the
                  cut the same way). Error against unknowns for XFEM (Tet4 box meshes that ignore
                  the cut) Heaviside-only (chapter 4: the cut ends at the last enriched row),
                  with topological and with geometric branch enrichment, and for conforming
                  Tet4 and Tet10 (box meshes with node layers on x = 0.015 and z = 0.1, opened
                  along the cut by duplicated nodes, chapter 3's split_mesh_along_cut). Errors
                  against a fine conforming Tet10: the relative L2 error (at the reference's
                  degree-2 points) and Paulus's RMS over the reference's nodes (m);
     sweep.csv    chapter 3's front sweep with branch functions: gravity, the tip u_x at
                  (0.03, 0.03, 0.2) against the front x1 of the cut [0, x1] x [0, 0.06] x {0.1003}
                  on chapter 3's 3x6x19 mesh, 1 mm steps from 1.5 to 24.5 mm and 0.1 mm steps
                  across the node row x = 0.01;
     partial.csv  partial cuts on the beam: a half disc (a planar cut ending on a circle), a
                  planar cut whose front is a sine, and a declining sine surface (Paulus's
                  sinusoidal blade, its amplitude falling towards the front); gravity, geometric
                  branch enrichment: the front found and its length against the curve's, and the
                  opening [u] across the cut along a line through the front.
   --quick runs every part on tiny meshes in a few seconds; it is a test.

   Read chapter 5 first. */

#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/height_field_surface.hpp"
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/cut/split_mesh_along_cut.hpp"
#include "kerf/fem/assemble_loads.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/evaluate_displacement.hpp"
#include "kerf/fem/linear_material.hpp"
#include "kerf/fem/solve_linear_static.hpp"
#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/node_region.hpp"
#include "kerf/mesh/point_locator.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"
#include "kerf/scene/cut_xfem_loads.hpp"
#include "kerf/scene/scene.hpp"
#include "kerf/solve/linear_solver.hpp"
#include "kerf/xfem/crack_tip_body.hpp"
#include "measure.hpp" // bench/measure.hpp: the command line shared with the benchmarks
#include "reference_field.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

namespace paulus_study {

using clock = std::chrono::steady_clock;
double seconds_since(clock::time_point start) { return std::chrono::duration<double>(clock::now() - start).count(); }
const double not_a_number = std::numeric_limits<double>::quiet_NaN();

const Eigen::Vector3d beam_min(0.0, 0.0, 0.0), beam_max(0.03, 0.06, 0.2);
const kerf::LinearMaterial material{}; // E = 300 kPa, nu = 0.35, rho = 1070 kg/m^3
const double cut_z = 0.1, front_x = 0.015;

/// The rules of the tets with branch nodes, cheaper than the model's defaults: Gauss of degree
/// 3 on the front tets' sub-tets refined once, degree 3 unrefined on the other branch tets. The
/// defaults (collapsed rule, 4 points per direction, 22k points per front tet; degree 6 graded
/// three times) took over 100 s for one 3x6x19 model on the loaded study machine, against 1 s
/// with these; paulus.md shows what the cheaper rules change in the answer on a small mesh.
const kerf::BranchRules study_rules{kerf::FrontRule::refined_subtets, 2, 3, 0};
/// The sweep's rules: the same, but the blending tets' sub-tets refined once towards the front
/// where they are larger than their distance to it. Without that grading the answer jumps by
/// 1.5 % where the front crosses a node row (the tets that blend change), with it by 0.24 %
/// (tests/chapter_05/test_front_sweep.cpp's mesh; the collapsed front rule with degree 4 graded
/// once gives 0.23 %, and tip deflections within 0.3 % of these). Five times dearer than
/// study_rules on the branch tets, so only the sweep pays for it.
const kerf::BranchRules sweep_rules{kerf::FrontRule::refined_subtets, 2, 3, 1};

std::string cells_text(const Eigen::Vector3i& c) { return std::to_string(c[0]) + "x" + std::to_string(c[1]) + "x" + std::to_string(c[2]); }

// @sect3{Loads and the clamp}

struct Load {
  std::string name;
  Eigen::Vector3d gravity{0, 0, 0};    ///< m/s^2
  Eigen::Vector3d tip_force{0, 0, 0};  ///< N, spread uniformly over the face z = 0.2
};

std::vector<Load> loads() { return {{"gravity", {9.81, 0, 0}, {0, 0, 0}}, {"tip_traction", {0, 0, 0}, {0, 0, 1.0}}}; }

kerf::NodeRegion box_region(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  kerf::NodeRegion region;
  region.box_min = lo;
  region.box_max = hi;
  return region;
}
const kerf::NodeRegion base = box_region(beam_min, {beam_max[0], beam_max[1], 0.0});
const kerf::NodeRegion tip_face = box_region({0.0, 0.0, beam_max[2]}, beam_max);

std::vector<kerf::DirichletNodes> clamp(const kerf::TetMesh& mesh) { return {{kerf::nodes_in_region(mesh, base), {0, 0, 0}}}; }

/// The load on [u; a; b] of an XFEM body: gravity and the traction, both integrated on the
/// enriched rows too (cut_xfem_loads.hpp).
Eigen::VectorXd xfem_load(const kerf::CrackTipBody& body, const Load& load) {
  kerf::Scene scene;
  scene.material = material;
  scene.gravity = load.gravity;
  if (load.tip_force.norm() > 0.0) scene.traction.push_back({tip_face, load.tip_force});
  return kerf::cut_xfem_scene_loads(scene, body.model(), kerf::boundary_faces(body.mesh()));
}

Eigen::VectorXd conforming_load(const kerf::TetMesh& mesh, const Load& load) {
  Eigen::VectorXd f = kerf::assemble_gravity(mesh, material.density, load.gravity);
  if (load.tip_force.norm() > 0.0)
    kerf::add_uniform_traction(mesh, kerf::boundary_faces(mesh), kerf::node_mask(mesh, tip_face), load.tip_force, f);
  return f;
}

/// One solve and what it cost.
struct Solution {
  Eigen::VectorXd u;
  int dofs = 0;
  double seconds = 0.0; ///< model, loads, assembly and solve (for XFEM also the cut processing)
};

Solution solve_xfem(const kerf::CrackTipBody& body, const Load& load) {
  Solution s;
  const auto start = clock::now();
  const kerf::DofMap dofs = kerf::make_cut_xfem_dof_map(body.model(), clamp(body.mesh()));
  s.u = kerf::solve_linear_cut_xfem(body.model(), dofs, xfem_load(body, load), kerf::SolverSettings{});
  s.seconds = seconds_since(start);
  s.dofs = dofs.num_free;
  return s;
}

Solution solve_conforming(const kerf::TetMesh& mesh, const Load& load) {
  Solution s;
  const auto start = clock::now();
  const kerf::DofMap dofs = kerf::make_dof_map(mesh.num_nodes(), clamp(mesh));
  s.u = kerf::solve_linear_static(mesh, material, dofs, conforming_load(mesh, load), kerf::SolverSettings{});
  s.seconds = seconds_since(start);
  s.dofs = dofs.num_free;
  return s;
}

/// The XFEM field at each row of `points`: the tet that holds it, then the piece that holds it
/// there (cut_xfem_model.hpp); NaN outside the mesh.
Eigen::MatrixXd xfem_values(const kerf::CrackTipBody& body, const Eigen::VectorXd& u, const Eigen::MatrixXd& points) {
  const kerf::PointLocator locator(body.mesh());
  Eigen::MatrixXd values(points.rows(), 3);
  for (Eigen::Index p = 0; p < points.rows(); ++p) {
    const Eigen::Vector3d x = points.row(p).transpose();
    const kerf::PointLocation where = locator.locate(x);
    const Eigen::Vector3d value =
        where.tet < 0 ? Eigen::Vector3d::Constant(not_a_number) : body.model().displacement_at(u, where.tet, x);
    values.row(p) = value.transpose();
  }
  return values;
}

// @sect3{The meshes}

/// The cut as a triangle surface for XFEM: the authors' CutHorizontal (from their public code), the
/// rectangle [-0.01, x1] x [-0.01, 0.07] at height z, overhanging the beam on three sides so
/// that its only edge inside the beam is the front x = x1. Normal +z: "above" is +z.
kerf::TriangleSurface half_depth_cut(double x1, double z) {
  return kerf::rectangle_surface(kerf::RectangleCut({-0.01, -0.01, z}, {x1 + 0.01, 0.0, 0.0}, {0.0, 0.08, 0.0}));
}

/// An XFEM box mesh with `cells`, nx odd so that x = 0.015 is a cell middle, and its node layers
/// moved in z so that z = 0.1 lies 0.35 of a cell above a layer: the front then crosses the
/// tets away from their faces (with z = 0.1 also at a cell middle, the front x = 0.015, z = 0.1
/// would run inside the tets' diagonal faces x = z of the box's cells). The layer k = nz / 2 is
/// put at 0.1 - 0.35 h and the layers below and above it are spaced evenly again.
kerf::TetMesh xfem_box_mesh(const Eigen::Vector3i& cells) {
  kerf::TetMesh mesh = kerf::make_box_mesh(beam_min, beam_max, cells);
  const int n = cells[2], layer = n / 2;
  const double length = beam_max[2], h = length / n, target = cut_z - 0.35 * h;
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) {
    double& z = mesh.nodes(v, 2);
    const long k = std::lround(z / h);
    z = k <= layer ? target * static_cast<double>(k) / layer : target + (length - target) * static_cast<double>(k - layer) / (n - layer);
  }
  return mesh;
}

/// A conforming box mesh (nx and nz even: node layers on x = 0.015 and z = 0.1), Tet10 for
/// order 2, opened along Paulus's cut.
kerf::SplitMesh conforming_mesh(const Eigen::Vector3i& cells, int order) {
  kerf::TetMesh mesh = kerf::make_box_mesh(beam_min, beam_max, cells);
  if (order == 2) mesh = kerf::tet10_from_tet4(mesh);
  return kerf::split_mesh_along_cut(mesh, kerf::RectangleCut({0.0, 0.0, cut_z}, {front_x, 0.0, 0.0}, {0.0, 0.06, 0.0}), 1e-9);
}

// @sect3{Paulus's error measure}

/// The reference's nodes as points on their own side of the cut: a node on the cut and its
/// duplicate are moved 1e-9 m up and down (a duplicate belongs to the tets below), so that a
/// solution that does not conform to the cut is read on the right side (nodes on the front stay).
Eigen::MatrixXd reference_node_points(const kerf::SplitMesh& reference) {
  Eigen::MatrixXd points = reference.mesh.nodes;
  const Eigen::Index originals = reference.mesh.num_nodes() - reference.duplicated_nodes;
  for (int k = 0; k < reference.duplicated_nodes; ++k) {
    points(reference.duplicate_of[static_cast<std::size_t>(k)], 2) += 1e-9;
    points(originals + k, 2) -= 1e-9;
  }
  return points;
}

/// Paulus section 5.1: RMS = sqrt(sum_k |u_ref(P_k) - u_h(P_k)|^2 / (3 N)) over the N reference
/// nodes (m, per component).
double paulus_rms(const Eigen::MatrixXd& reference_values, const Eigen::MatrixXd& values) {
  return std::sqrt((values - reference_values).squaredNorm() / (3.0 * static_cast<double>(values.rows())));
}

/// The reference: the conforming Tet10 solution, at its degree-2 points and at its nodes.
struct Reference {
  kerf::SplitMesh mesh;
  study::ReferenceField field;
  Eigen::MatrixXd node_points, node_values;
  int dofs = 0;
};

// @sect3{Fig. 9: error against unknowns}

struct Fig9Sizes {
  Eigen::Vector3i reference, reference_check;
  std::vector<Eigen::Vector3i> xfem, conforming, conforming10;
};

Fig9Sizes fig9_sizes(bool quick) {
  if (quick) return {{2, 4, 10}, {2, 2, 4}, {{1, 2, 7}}, {{2, 2, 4}}, {{2, 2, 4}}};
  return {{6, 12, 40},
          {4, 8, 26},
          {{1, 2, 7}, {3, 6, 19}, {5, 10, 33}, {7, 14, 47}, {9, 18, 61}},
          {{2, 2, 4}, {2, 4, 10}, {4, 6, 16}, {4, 8, 20}, {6, 12, 30}, {8, 16, 40}},
          {{2, 2, 4}, {2, 4, 10}, {4, 6, 16}}};
}

void run_fig9(bool quick, const std::filesystem::path& out) {
  const Fig9Sizes sizes = fig9_sizes(quick);
  std::ofstream csv(out / "paulus.csv");
  csv << "load,method,cells,dofs,seconds,rel_l2,rms_m,branch_nodes,sign_nodes,radius_m\n";
  std::printf("\nFig. 9: cut [0, 0.015] x [0, 0.06] x {0.1}; reference conforming Tet10 %s\n", cells_text(sizes.reference).c_str());
  std::printf("%-12s %-12s %-9s %7s %8s %10s %10s %5s %5s\n", "load", "method", "cells", "dofs", "time_s", "rel_L2", "RMS_m", "branch",
              "sign");
  for (const Load& load : loads()) {
    Reference ref{conforming_mesh(sizes.reference, 2), {}, {}, {}, 0};
    const Solution r = solve_conforming(ref.mesh.mesh, load);
    ref.dofs = r.dofs;
    ref.field = study::sample_reference(ref.mesh.mesh, r.u);
    ref.node_points = reference_node_points(ref.mesh);
    Eigen::Index outside = 0;
    ref.node_values = kerf::evaluate_displacement_at(ref.mesh.mesh, r.u, ref.node_points, outside);
    const auto row = [&](const std::string& method, const Eigen::Vector3i& cells, const Solution& s, const Eigen::MatrixXd& at_points,
                         const Eigen::MatrixXd& at_nodes, int branch, int sign, double radius) {
      const double l2 = study::relative_l2(ref.field, at_points), rms = paulus_rms(ref.node_values, at_nodes);
      csv << load.name << ',' << method << ',' << cells_text(cells) << ',' << s.dofs << ',' << s.seconds << ',' << l2 << ',' << rms << ','
          << branch << ',' << sign << ',' << radius << '\n';
      std::printf("%-12s %-12s %-9s %7d %8.3f %10.3e %10.3e %5d %5d\n", load.name.c_str(), method.c_str(), cells_text(cells).c_str(),
                  s.dofs, s.seconds, l2, rms, branch, sign);
    };
    row("reference", sizes.reference, r, ref.field.values, ref.node_values, 0, 0, 0.0);
    for (int order : {1, 2})
      for (const Eigen::Vector3i& cells : order == 1 ? sizes.conforming : sizes.conforming10) {
        const kerf::SplitMesh mesh = conforming_mesh(cells, order);
        const Solution s = solve_conforming(mesh.mesh, load);
        Eigen::Index off = 0;
        const Eigen::MatrixXd p = kerf::evaluate_displacement_at(mesh.mesh, s.u, ref.field.points, off);
        const Eigen::MatrixXd n = kerf::evaluate_displacement_at(mesh.mesh, s.u, ref.node_points, off);
        row(order == 1 ? "conforming4" : "conforming10", cells, s, p, n, 0, mesh.duplicated_nodes, 0.0);
      }
    {
      // The next coarser conforming Tet10: how far the reference itself is from converged.
      const kerf::SplitMesh mesh = conforming_mesh(sizes.reference_check, 2);
      const Solution s = solve_conforming(mesh.mesh, load);
      Eigen::Index off = 0;
      row("check10", sizes.reference_check, s, kerf::evaluate_displacement_at(mesh.mesh, s.u, ref.field.points, off),
          kerf::evaluate_displacement_at(mesh.mesh, s.u, ref.node_points, off), 0, mesh.duplicated_nodes, 0.0);
    }
    for (const Eigen::Vector3i& cells : sizes.xfem)
      for (const kerf::TipTreatment treatment : {kerf::TipTreatment::heaviside_only, kerf::TipTreatment::topological,
                                                 kerf::TipTreatment::geometric}) {
        const auto start = clock::now();
        const kerf::CrackTipBody body(xfem_box_mesh(cells), {half_depth_cut(front_x, cut_z)}, material, treatment, 0.0, study_rules);
        Solution s = solve_xfem(body, load);
        s.seconds = seconds_since(start);
        const kerf::BranchEnrichment* branch = body.branch();
        const int sign = branch ? branch->count(kerf::NodeEnrichmentKind::sign)
                                : static_cast<int>(body.model().enrichment().num_enrichments());
        row(std::string("xfem_") + kerf::to_string(treatment), cells, s, xfem_values(body, s.u, ref.field.points),
            xfem_values(body, s.u, ref.node_points), branch ? branch->num_branch_nodes() : 0, sign, body.radius());
      }
  }
}

// @sect3{Chapter 3's front sweep with branch functions}

std::vector<double> sweep_positions(bool quick) {
  if (quick) return {0.01005};
  std::vector<double> x1;
  // 1 mm steps half a millimetre off the node rows x = 0.01, 0.02 (a front on a node row lies
  // in the mesh's faces: the failure study's case, not this one's), and 0.1 mm steps across
  // the node row x = 0.01, never on it.
  for (int k = 0; k <= 23; ++k) x1.push_back(0.0015 + 0.001 * k);
  for (int k = -10; k < 10; ++k) x1.push_back(0.01 + 0.0001 * (k + 0.5));
  std::sort(x1.begin(), x1.end());
  return x1;
}

void run_sweep(bool quick, const std::filesystem::path& out) {
  const Eigen::Vector3i cells(3, 6, 19);
  const double plane_z = 0.1003; // chapter 3's: off every node layer and cell middle
  const Load gravity = loads()[0];
  Eigen::MatrixXd tip(1, 3);
  tip << 0.03, 0.03, 0.2;
  std::ofstream csv(out / "sweep.csv");
  csv << "x1,treatment,status,dofs,branch_nodes,tip_ux_m\n";
  std::printf("\nFront sweep: gravity, tip u_x at (0.03, 0.03, 0.2), mesh %s, plane z = %g\n", cells_text(cells).c_str(), plane_z);
  const kerf::TetMesh mesh = kerf::make_box_mesh(beam_min, beam_max, cells);
  for (const double x1 : sweep_positions(quick))
    for (const kerf::TipTreatment treatment : {kerf::TipTreatment::heaviside_only, kerf::TipTreatment::topological,
                                               kerf::TipTreatment::geometric}) {
      const kerf::CrackTipBody body(mesh, {half_depth_cut(x1, plane_z)}, material, treatment, 0.0, sweep_rules);
      std::string status = "solved";
      double ux = not_a_number;
      int dofs = 0;
      try {
        const Solution s = solve_xfem(body, gravity);
        dofs = s.dofs;
        ux = xfem_values(body, s.u, tip)(0, 0);
      } catch (const std::runtime_error& error) {
        // A simulated cut through the whole depth frees the top: the library refuses it by name.
        status = "separated";
      }
      const int branch = body.branch() ? body.branch()->num_branch_nodes() : 0;
      csv << x1 << ',' << kerf::to_string(treatment) << ',' << status << ',' << dofs << ',' << branch << ',' << std::setprecision(12) << ux
          << std::setprecision(6) << '\n';
      std::printf("x1 = %8.5f %-12s %-9s %6d %4d %.8g\n", x1, kerf::to_string(treatment), status.c_str(), dofs, branch, ux);
    }
}

// @sect3{Partial cuts with curved fronts}

/// One partial cut: its surface, the length its front must have, and the line the opening is
/// read along (points on the cut surface continued beyond the front, and its normal there).
struct PartialCut {
  std::string name;
  kerf::TriangleSurface surface;
  double front_length = 0.0; ///< of the curve the surface's front interpolates (m)
  double polygon_length = 0.0; ///< of the front polyline the triangulation puts inside the beam (m), NaN if not known in closed form
  double front_at = 0.0;     ///< where the line crosses the front (m, the line's parameter)
  std::function<Eigen::Vector3d(double)> line; ///< the point at parameter s (m) on the surface or its continuation
};

/// A disc of radius R in the plane z about (0, 0.03): its half inside the beam ends on a half
/// circle, the front, of length pi R. The disc is a fan of n triangles; the rim's vertices lie
/// half a step off the beam's face x = 0, so the front inside is n / 2 chords, n R sin(pi / n).
PartialCut half_disc(double R, int n, double z) {
  PartialCut cut;
  cut.name = "half_disc";
  cut.surface.vertices.resize(n + 1, 3);
  cut.surface.triangles.resize(n, 3);
  cut.surface.vertices.row(0) << 0.0, 0.03, z;
  for (int k = 0; k < n; ++k) {
    const double phi = 2.0 * M_PI * (k + 0.5) / n;
    cut.surface.vertices.row(k + 1) << R * std::cos(phi), 0.03 + R * std::sin(phi), z;
    cut.surface.triangles.row(k) << 0, k + 1, (k + 1) % n + 1; // counter-clockwise seen from above: normal +z
  }
  cut.front_length = M_PI * R;
  cut.polygon_length = n * R * std::sin(M_PI / n);
  cut.front_at = R * std::cos(M_PI / n); // the chord through y = 0.03 is half a step from its ends
  cut.line = [z](double s) { return Eigen::Vector3d(s, 0.03, z); };
  return cut;
}

/// The arc length of the curve (s, f(s)) for s in [a, b], by composite Simpson on 2000 intervals
/// (the curves here are smooth: the error is far below the tolerances it is compared with).
double arc_length(const std::function<double(double)>& derivative, double a, double b) {
  const int n = 2000;
  double sum = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double s = a + (b - a) * i / n, g = std::sqrt(1.0 + std::pow(derivative(s), 2));
    sum += g * (i == 0 || i == n ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0));
  }
  return sum * (b - a) / (3.0 * n);
}

/// The plane z ended by the curved front x = x_f(y) = x0 + A sin(2 pi y / 0.06): a grid over
/// [-0.01, 1] x [-0.01, 0.07] whose x is then stretched onto [-0.01, x_f(y)].
PartialCut sine_front(double x0, double A, double z, const Eigen::Vector2i& cells) {
  const auto x_f = [=](double y) { return x0 + A * std::sin(2.0 * M_PI * y / 0.06); };
  PartialCut cut;
  cut.name = "sine_front";
  cut.surface = kerf::height_field_surface([](double, double) { return 0.0; }, z, {0.0, -0.01}, {1.0, 0.07}, cells);
  for (Eigen::Index v = 0; v < cut.surface.vertices.rows(); ++v) {
    const double s = cut.surface.vertices(v, 0), y = cut.surface.vertices(v, 1);
    cut.surface.vertices(v, 0) = -0.01 + s * (x_f(y) + 0.01);
  }
  cut.front_length = arc_length([=](double y) { return A * 2.0 * M_PI / 0.06 * std::cos(2.0 * M_PI * y / 0.06); }, 0.0, 0.06);
  cut.polygon_length = not_a_number;
  const double y_line = 0.015; // where the front is furthest ahead
  cut.front_at = x_f(y_line);
  cut.line = [=](double s) { return Eigen::Vector3d(s, y_line, z); };
  return cut;
}

/// Paulus's sinusoidal blade with a declining amplitude: z = z_c + A (1 - x / 0.03) sin(2 pi y /
/// 0.06) over [-0.01, x0] x [-0.01, 0.07]; its front is the curve x = x0, z = z_c + A (1 - x0 /
/// 0.03) sin(2 pi y / 0.06) inside the beam.
PartialCut declining_sine(double x0, double A, double z_c, const Eigen::Vector2i& cells) {
  const auto h = [=](double x, double y) { return A * (1.0 - x / 0.03) * std::sin(2.0 * M_PI * y / 0.06); };
  PartialCut cut;
  cut.name = "declining_sine";
  cut.surface = kerf::height_field_surface(h, z_c, {-0.01, -0.01}, {x0, 0.07}, cells);
  const double amplitude = A * (1.0 - x0 / 0.03);
  cut.front_length = arc_length([=](double y) { return amplitude * 2.0 * M_PI / 0.06 * std::cos(2.0 * M_PI * y / 0.06); }, 0.0, 0.06);
  cut.polygon_length = not_a_number;
  const double y_line = 0.015;
  cut.front_at = x0;
  cut.line = [=](double s) { return Eigen::Vector3d(s, y_line, z_c + h(s, y_line)); };
  return cut;
}

void run_partial(bool quick, const std::filesystem::path& out) {
  const Eigen::Vector3i cells = quick ? Eigen::Vector3i(1, 2, 7) : Eigen::Vector3i(5, 10, 33);
  const Load gravity = loads()[0];
  std::vector<PartialCut> cuts;
  cuts.push_back(half_disc(0.012, 64, cut_z));
  cuts.push_back(sine_front(0.015, 0.004, cut_z, {25, 80}));
  cuts.push_back(declining_sine(0.015, 0.004, cut_z, {25, 80}));
  std::ofstream csv(out / "partial.csv"), fronts_csv(out / "partial_fronts.csv");
  csv << "cut,treatment,s_m,ahead_of_front_m,opening_m,opening_x_m,opening_z_m\n";
  fronts_csv << "cut,polyline,x,y,z\n";
  std::printf("\nPartial cuts on the beam, mesh %s, gravity, opening [u] = u(+) - u(-) along the line through the front\n",
              cells_text(cells).c_str());
  for (const PartialCut& cut : cuts)
    for (const kerf::TipTreatment treatment : {kerf::TipTreatment::heaviside_only, kerf::TipTreatment::geometric}) {
      const kerf::CrackTipBody body(xfem_box_mesh(cells), {cut.surface}, material, treatment, 0.0, study_rules);
      const Solution s = solve_xfem(body, gravity);
      const double length = body.fronts().length();
      std::printf("%-15s %-10s %zu front(s), length %.6g m (curve %.6g, polygon %.6g: rel. %.2e), %d DOFs, max |u_i| %.4g m\n",
                  cut.name.c_str(), kerf::to_string(treatment), body.fronts().polylines.size(), length, cut.front_length,
                  cut.polygon_length, length / cut.front_length - 1.0, s.dofs, s.u.head(3 * body.mesh().num_nodes()).cwiseAbs().maxCoeff());
      if (treatment == kerf::TipTreatment::geometric)
        for (std::size_t p = 0; p < body.fronts().polylines.size(); ++p)
          for (const Eigen::Vector3d& x : body.fronts().polylines[p].points)
            fronts_csv << cut.name << ',' << p << ',' << x[0] << ',' << x[1] << ',' << x[2] << '\n';
      // The opening: the field a hair above and below the surface (1e-7 m along z), from the
      // beam's face x = 0 to 8 mm beyond the front.
      const int n = quick ? 20 : 200;
      Eigen::MatrixXd above(n, 3), below(n, 3);
      for (int i = 0; i < n; ++i) {
        const double s_i = (cut.front_at + 0.008) * (i + 0.5) / n;
        const Eigen::Vector3d x = cut.line(s_i);
        above.row(i) = (x + Eigen::Vector3d(0, 0, 1e-7)).transpose();
        below.row(i) = (x - Eigen::Vector3d(0, 0, 1e-7)).transpose();
      }
      const Eigen::MatrixXd jump = xfem_values(body, s.u, above) - xfem_values(body, s.u, below);
      for (int i = 0; i < n; ++i) {
        const double s_i = (cut.front_at + 0.008) * (i + 0.5) / n;
        csv << cut.name << ',' << kerf::to_string(treatment) << ',' << s_i << ',' << s_i - cut.front_at << ',' << jump.row(i).norm() << ','
            << jump(i, 0) << ',' << jump(i, 2) << '\n';
      }
    }
}

} // namespace paulus_study

int main(int argc, char** argv) {
  const auto options = kerf_measure::parse_run_options(argc, argv, "05_paulus_study [--quick] [--out DIR] [--only fig9,sweep,partial]",
                                                       "output/paulus_study", {"fig9", "sweep", "partial"});
  if (!options) return 2;
  try {
    std::filesystem::create_directories(options->out);
    std::cout << "Kerf chapter 5 Paulus study" << (options->quick ? " (quick)" : "") << " on " << kerf_measure::cpu_model() << "\n";
    const auto start = paulus_study::clock::now();
    if (options->runs("fig9")) paulus_study::run_fig9(options->quick, options->out);
    if (options->runs("sweep")) paulus_study::run_sweep(options->quick, options->out);
    if (options->runs("partial")) paulus_study::run_partial(options->quick, options->out);
    std::printf("\ntotal %.1f s\n", paulus_study::seconds_since(start));
  } catch (const std::exception& error) {
    std::cerr << "05_paulus_study: " << error.what() << '\n';
    return 1;
  }
  return 0;
}
