/* Kerf, chapter 2 study: ghost forces, accuracy under large loads, and where corotation fails.

   Build:   cmake --preset release && cmake --build --preset release --target 02_corotation_study

   Sample runs:
     02_corotation_study --quick --out output/corotation_study_quick
     02_corotation_study --out figures/02_corotation

   Description: the beam of chapters 1 and 2 (0.03 x 0.06 x 0.2 m, E = 300 kPa, nu = 0.35) and
   a single tetrahedron. The program writes, into the --out folder:
     ghost.csv      the beam turned rigidly (its two end faces prescribed on a rigid rotation
                    about the long axis z or about the y axis through the centre, 0..180 degrees):
                    the strain energy, volume change and distance from the rigid motion that
                    linear FEM (chapter 1) and corotated FEM (chapter 2) give. Exact: all zero.
     load.csv       the beam clamped at z = 0 under a growing dead load along +x on its top
                    face, up to a tip deflection of about 40 % of the length: linear FEM,
                    corotated Tet4 and Tet10, CalculiX with NLGEOM (C3D10, same mesh) and the
                    elastica of a slender cantilever, with errors and wall times;
     inversion.csv  one Tet4 squeezed through zero volume (det F from 1 to -0.5): the force on
                    the moving node and the element's energy with Higham's rotation and with
                    the SVD rotation;
     block.csv      what a simulation does with it: a block whose top centre node is pushed
                    deep into it, solved with each rotation method.
   --quick runs every code path on tiny meshes in a few seconds; it is a test.

   Read chapter 2 first. */

#include "kerf/corotation/corotational_model.hpp"
#include "kerf/corotation/quasi_static_solver.hpp"
#include "kerf/fem/assemble_loads.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/linear_material.hpp"
#include "kerf/fem/solve_linear_static.hpp"
#include "kerf/fem/tet_quadrature.hpp"
#include "kerf/fem/tet_shape_functions.hpp"
#include "kerf/fem/tet_stiffness.hpp"
#include "kerf/io/calculix_deck.hpp"
#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/node_region.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"
#include "kerf/solve/linear_solver.hpp"
#include "measure.hpp" // bench/measure.hpp: the command line shared with the benchmarks

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace corotation_study {

using clock = std::chrono::steady_clock;

/// Seconds elapsed since `start`.
double seconds_since(clock::time_point start) { return std::chrono::duration<double>(clock::now() - start).count(); }

const double not_a_number = std::numeric_limits<double>::quiet_NaN();

// The beam of chapter 1 and the centre about which the ghost-force study turns it.
const Eigen::Vector3d beam_min(0.0, 0.0, 0.0);
const Eigen::Vector3d beam_max(0.03, 0.06, 0.2);
const Eigen::Vector3d beam_centre(0.015, 0.03, 0.1);

const char* element_name(int order) { return order == 1 ? "Tet4" : "Tet10"; }

/// printf into a std::string, for the closing summary.
template <class... Args>
std::string format(const char* pattern, Args... args) {
  char text[512];
  std::snprintf(text, sizeof text, pattern, args...);
  return text;
}

std::string cells_text(const Eigen::Vector3i& cells) {
  return std::to_string(cells[0]) + "x" + std::to_string(cells[1]) + "x" + std::to_string(cells[2]);
}

/// The box mesh of the beam, promoted to Tet10 (straight edges) for order 2.
kerf::TetMesh make_beam_mesh(const Eigen::Vector3i& cells, int order) {
  const kerf::TetMesh tet4 = kerf::make_box_mesh(beam_min, beam_max, cells);
  return order == 1 ? tet4 : kerf::tet10_from_tet4(tet4);
}

/// The nodes of the end face at height z (z = 0 or z = 0.2).
std::vector<int> end_face_nodes(const kerf::TetMesh& mesh, double z) {
  kerf::NodeRegion face;
  face.box_min = Eigen::Vector3d(beam_min[0], beam_min[1], z);
  face.box_max = Eigen::Vector3d(beam_max[0], beam_max[1], z);
  return kerf::nodes_in_region(mesh, face);
}

/// The volume of the deformed mesh, sum over tets of int det(dx/dxi) dxi. For a Tet10 the map
/// is quadratic in xi, so det(dx/dxi) is a cubic: a degree-3 rule integrates it exactly.
double deformed_volume(const kerf::TetMesh& mesh, const Eigen::VectorXd& u) {
  const kerf::TetQuadratureRule rule = kerf::tet_quadrature_rule(3);
  double volume = 0.0;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    if (mesh.order() == 1) {
      Eigen::Matrix<double, 4, 3> x;
      for (int a = 0; a < 4; ++a) x.row(a) = mesh.nodes.row(mesh.tets(t, a)) + u.segment<3>(3 * mesh.tets(t, a)).transpose();
      volume += (x.transpose() * kerf::tet4_shape_gradients()).determinant() / 6.0;
    } else {
      Eigen::Matrix<double, 10, 3> x;
      for (int a = 0; a < 10; ++a) x.row(a) = mesh.nodes.row(mesh.tets(t, a)) + u.segment<3>(3 * mesh.tets(t, a)).transpose();
      for (std::size_t q = 0; q < rule.points.size(); ++q)
        volume += rule.weights[q] * (x.transpose() * kerf::tet10_shape_gradients(rule.points[q])).determinant();
    }
  }
  return volume;
}

/// The linear strain energy 1/2 u^T K u, element by element (chapter 1's K, eq. 30).
double linear_strain_energy(const kerf::TetMesh& mesh, const kerf::LinearMaterial& material, const Eigen::VectorXd& u) {
  double energy = 0.0;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const int n = mesh.nodes_per_tet();
    Eigen::VectorXd u_e(3 * n);
    for (int a = 0; a < n; ++a) u_e.segment<3>(3 * a) = u.segment<3>(3 * mesh.tets(t, a));
    if (n == 4) {
      Eigen::Matrix<double, 4, 3> X;
      for (int a = 0; a < 4; ++a) X.row(a) = mesh.nodes.row(mesh.tets(t, a));
      energy += 0.5 * u_e.dot(kerf::tet4_stiffness(X, material) * u_e);
    } else {
      Eigen::Matrix<double, 10, 3> X;
      for (int a = 0; a < 10; ++a) X.row(a) = mesh.nodes.row(mesh.tets(t, a));
      energy += 0.5 * u_e.dot(kerf::tet10_stiffness(X, material) * u_e);
    }
  }
  return energy;
}

// @sect3{(a) Ghost forces: the beam turned rigidly}

/// The displacement of a rigid rotation R about `centre`: u(X) = R (X - c) + c - X, for all nodes (3#V).
Eigen::VectorXd rigid_rotation_displacement(const kerf::TetMesh& mesh, const Eigen::Matrix3d& R, const Eigen::Vector3d& centre) {
  Eigen::VectorXd u(3 * mesh.num_nodes());
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) {
    const Eigen::Vector3d X = mesh.nodes.row(v).transpose();
    u.segment<3>(3 * v) = R * (X - centre) + centre - X;
  }
  return u;
}

/// Both end faces prescribed on the rigid rotation: one DirichletNodes per node, because each
/// node of a turned face moves differently.
kerf::DofMap rotated_ends(const kerf::TetMesh& mesh, const Eigen::VectorXd& u_rigid) {
  std::vector<kerf::DirichletNodes> conditions;
  for (double z : {beam_min[2], beam_max[2]})
    for (int v : end_face_nodes(mesh, z)) conditions.push_back({{v}, u_rigid.segment<3>(3 * v)});
  return kerf::make_dof_map(mesh.num_nodes(), conditions);
}

/// max over nodes of |u(v) - u_rigid(v)|.
double max_nodal_deviation(const Eigen::VectorXd& u, const Eigen::VectorXd& u_rigid) {
  return (u - u_rigid).reshaped(3, u.size() / 3).colwise().norm().maxCoeff();
}

/// One row of ghost.csv.
struct GhostRow {
  int order = 1;
  char axis = 'z';
  double degrees = 0.0;
  double linear_energy = 0, linear_volume_change = 0, linear_deviation = 0, linear_seconds = 0;
  double corotated_energy = 0, corotated_volume_change = 0, corotated_deviation = 0, corotated_seconds = 0;
  int newton_iterations = 0;
  bool converged = false;
};

/// Turns the beam by `degrees` about `axis` (through its centre) with linear and corotated FEM.
///
/// The corotated run takes a single load step on purpose. Its first Newton iterate linearises
/// about u = 0 with the whole prescribed turn: that is exactly chapter 1's linear solution.
/// The following iterations are what corotation adds. (More load steps would not help here: the
/// solver ramps the prescribed displacements linearly, and the straight chord from X to R X
/// squeezes a face turned by 180 degrees through a line at half the load.)
GhostRow ghost_forces(const kerf::TetMesh& mesh, int order, char axis, double degrees) {
  const kerf::LinearMaterial material;
  const Eigen::Vector3d axis_vector = axis == 'z' ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitY();
  const Eigen::Matrix3d R = Eigen::AngleAxisd(degrees * std::numbers::pi / 180.0, axis_vector).toRotationMatrix();
  const Eigen::VectorXd u_rigid = rigid_rotation_displacement(mesh, R, beam_centre);
  const kerf::DofMap dofs = rotated_ends(mesh, u_rigid);
  const double volume = deformed_volume(mesh, Eigen::VectorXd::Zero(3 * mesh.num_nodes()));

  GhostRow row;
  row.order = order;
  row.axis = axis;
  row.degrees = degrees;
  auto start = clock::now();
  const Eigen::VectorXd u_linear =
      kerf::solve_linear_static(mesh, material, dofs, Eigen::VectorXd::Zero(3 * mesh.num_nodes()), kerf::SolverSettings{});
  row.linear_seconds = seconds_since(start);
  row.linear_energy = linear_strain_energy(mesh, material, u_linear);
  row.linear_volume_change = deformed_volume(mesh, u_linear) / volume - 1.0;
  row.linear_deviation = max_nodal_deviation(u_linear, u_rigid);

  const kerf::CorotationalModel model(mesh, material);
  kerf::QuasiStaticSettings settings;
  settings.load_steps = 1;
  settings.tangent = kerf::CorotationalTangent::consistent;
  start = clock::now();
  const kerf::QuasiStaticResult result =
      kerf::solve_quasi_static(model, dofs, Eigen::VectorXd::Zero(3 * mesh.num_nodes()), settings);
  row.corotated_seconds = seconds_since(start);
  row.corotated_energy = model.energy(result.u, settings.rotation);
  row.corotated_volume_change = deformed_volume(mesh, result.u) / volume - 1.0;
  row.corotated_deviation = max_nodal_deviation(result.u, u_rigid);
  row.newton_iterations = result.total_iterations;
  row.converged = result.converged;
  return row;
}

/// Runs ghost_forces for Tet4 and Tet10, both axes and every angle; writes ghost.csv and
/// returns one line for the summary.
std::string run_ghost_study(const Eigen::Vector3i& cells, const std::vector<double>& angles, const std::filesystem::path& out) {
  double linear_energy = 0, linear_volume = 0, corotated_energy = 0, corotated_volume = 0;
  bool all_converged = true;
  std::ofstream csv(out / "ghost.csv");
  csv << "element,axis,degrees,linear_energy_J,linear_volume_change,linear_max_deviation_m,linear_s,"
         "corotated_energy_J,corotated_volume_change,corotated_max_deviation_m,corotated_s,newton_iterations,converged\n";
  std::cout << "\n(a) Ghost forces: beam " << cells_text(cells) << " cells, both end faces turned rigidly\n";
  std::printf("%-6s %4s %6s | %11s %11s %11s | %11s %11s %11s %5s\n", "elem", "axis", "deg", "lin_E_J", "lin_dV/V",
              "lin_dev_m", "corot_E_J", "corot_dV/V", "corot_dev_m", "iters");
  for (int order : {1, 2}) {
    const kerf::TetMesh mesh = make_beam_mesh(cells, order);
    for (char axis : {'z', 'y'})
      for (double degrees : angles) {
        const GhostRow r = ghost_forces(mesh, order, axis, degrees);
        csv << element_name(order) << ',' << axis << ',' << degrees << ',' << r.linear_energy << ',' << r.linear_volume_change
            << ',' << r.linear_deviation << ',' << r.linear_seconds << ',' << r.corotated_energy << ','
            << r.corotated_volume_change << ',' << r.corotated_deviation << ',' << r.corotated_seconds << ','
            << r.newton_iterations << ',' << (r.converged ? 1 : 0) << '\n';
        std::printf("%-6s %4c %6.0f | %11.3e %11.3e %11.3e | %11.3e %11.3e %11.3e %5d%s\n", element_name(order), axis,
                    degrees, r.linear_energy, r.linear_volume_change, r.linear_deviation, r.corotated_energy,
                    r.corotated_volume_change, r.corotated_deviation, r.newton_iterations,
                    r.converged ? "" : " NOT CONVERGED");
        linear_energy = std::max(linear_energy, r.linear_energy);
        linear_volume = std::max(linear_volume, std::abs(r.linear_volume_change));
        corotated_energy = std::max(corotated_energy, std::abs(r.corotated_energy));
        corotated_volume = std::max(corotated_volume, std::abs(r.corotated_volume_change));
        all_converged = all_converged && r.converged;
      }
  }
  return format("(a) rigid turns up to %.0f deg: linear FEM stores up to %.3g J and changes the volume by up to %.0f %%; "
                "corotated FEM at most %.1e J and %.1e (%s)",
                angles.back(), linear_energy, 100.0 * linear_volume, corotated_energy, corotated_volume,
                all_converged ? "every solve converged" : "NOT every solve converged");
}

// @sect3{(b) Accuracy against load: the cantilever}

/// The elastica of a slender, inextensible cantilever (Euler-Bernoulli, no shear) of length L
/// under a dead tip load P perpendicular to its axis. With theta(s) the angle of the tangent
/// from the undeformed axis, the moment balance M = EI theta' and M(s) = P (z(L) - z(s)) give
///   theta'' = -(P / EI) cos(theta),  theta(0) = 0 (clamped),  theta'(L) = 0 (no tip moment).
/// We shoot on kappa_0 = theta'(0): integrate with RK4 and bisect until theta'(L) = 0. kappa_0 =
/// P L / EI (the small-deflection root curvature) overshoots, kappa_0 = 0 undershoots.
/// @return the tip displacement (along the load, along the axis), in m
Eigen::Vector2d elastica_tip_displacement(double P, double EI, double L) {
  constexpr int steps = 2000;
  const double ds = L / steps, k = P / EI;
  // State (theta, theta', x, z); x along the load, z along the undeformed axis.
  using State = Eigen::Vector4d;
  const auto rate = [k](const State& y) { return State(y[1], -k * std::cos(y[0]), std::sin(y[0]), std::cos(y[0])); };
  const auto shoot = [&](double kappa_0) {
    State y(0.0, kappa_0, 0.0, 0.0);
    for (int i = 0; i < steps; ++i) {
      const State k1 = rate(y), k2 = rate(y + 0.5 * ds * k1), k3 = rate(y + 0.5 * ds * k2), k4 = rate(y + ds * k3);
      y += ds / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    }
    return y;
  };
  double low = 0.0, high = k * L;
  for (int i = 0; i < 100; ++i) {
    const double middle = 0.5 * (low + high);
    (shoot(middle)[1] < 0.0 ? low : high) = middle;
  }
  const State tip = shoot(0.5 * (low + high));
  return Eigen::Vector2d(tip[2], tip[3] - L);
}

/// The mean displacement of the nodes on the top face z = 0.2, as (u_x, u_z).
Eigen::Vector2d mean_tip_displacement(const std::vector<int>& top, const Eigen::VectorXd& u) {
  Eigen::Vector2d sum(0.0, 0.0);
  for (int v : top) sum += Eigen::Vector2d(u[3 * v], u[3 * v + 2]);
  return sum / static_cast<double>(top.size());
}

/// CalculiX with NLGEOM (CalculixJob::nlgeom): ccx solves the total-Lagrangian large-deformation
/// problem of the same linear material, read as St. Venant-Kirchhoff, with automatic increments
/// of at most 10 % of the load. Returns the displacements (#V by 3) and the ccx process's wall time.
Eigen::MatrixXd solve_calculix_nlgeom(const std::string& ccx, const std::filesystem::path& work, const std::string& jobname,
                                      const kerf::TetMesh& mesh, kerf::CalculixJob job, double& seconds) {
  job.nlgeom = true;
  const std::filesystem::path inp = work / (jobname + ".inp");
  kerf::write_calculix_deck(inp, mesh, job);
  seconds = kerf::run_calculix(ccx, work, jobname);
  return kerf::read_calculix_displacements(work / (jobname + ".dat"), mesh.num_nodes());
}

/// One corotated solve of the clamped beam under the load `f`: tip displacement, time, iterations.
struct CorotatedTip {
  Eigen::Vector2d tip{0.0, 0.0};
  double seconds = 0.0;
  int iterations = 0;
  bool converged = false;
};

/// Solves with `load_steps` load steps and the consistent tangent; the model is built before the clock starts.
CorotatedTip corotated_tip(const kerf::TetMesh& mesh, const kerf::DofMap& dofs, const Eigen::VectorXd& f,
                           const std::vector<int>& top, int load_steps) {
  const kerf::CorotationalModel model(mesh, kerf::LinearMaterial{});
  kerf::QuasiStaticSettings settings;
  settings.load_steps = load_steps;
  settings.tangent = kerf::CorotationalTangent::consistent;
  CorotatedTip r;
  const auto start = clock::now();
  const kerf::QuasiStaticResult result = kerf::solve_quasi_static(model, dofs, f, settings);
  r.seconds = seconds_since(start);
  r.tip = mean_tip_displacement(top, result.u);
  r.iterations = result.total_iterations;
  r.converged = result.converged;
  return r;
}

/// |a - b| / |b| for tip displacement vectors (u_x, u_z).
double relative_difference(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return (a - b).norm() / b.norm(); }

/// The cantilever under each load of `loads` with every method; writes load.csv. The corotated
/// solves are timed without the model's one-time precomputation, the linear solve with its
/// assembly (chapter 1's whole solve), CalculiX as the whole ccx process. Returns one line for
/// the summary.
std::string run_load_study(const Eigen::Vector3i& cells, const std::vector<double>& loads, int load_steps, const std::string& ccx,
                    const std::filesystem::path& out) {
  const kerf::LinearMaterial material;
  const double L = beam_max[2], b = beam_max[1], h = beam_max[0];
  const double EI = material.young * b * h * h * h / 12.0; // bending about y: the thin direction x
  const kerf::TetMesh tet4 = make_beam_mesh(cells, 1), tet10 = make_beam_mesh(cells, 2);
  const auto clamp = [](const kerf::TetMesh& mesh) {
    return kerf::make_dof_map(mesh.num_nodes(), {{end_face_nodes(mesh, beam_min[2]), {0, 0, 0}}});
  };
  const kerf::DofMap dofs4 = clamp(tet4), dofs10 = clamp(tet10);
  const std::vector<int> top4 = end_face_nodes(tet4, beam_max[2]), top10 = end_face_nodes(tet10, beam_max[2]);
  const kerf::BoundaryFaces boundary4 = kerf::boundary_faces(tet4), boundary10 = kerf::boundary_faces(tet10);
  kerf::NodeRegion top_face;
  top_face.box_min = Eigen::Vector3d(beam_min[0], beam_min[1], beam_max[2]);
  top_face.box_max = beam_max;
  const std::vector<char> top_mask4 = kerf::node_mask(tet4, top_face), top_mask10 = kerf::node_mask(tet10, top_face);
  const std::filesystem::path work = out / "calculix_nlgeom_work";
  if (!ccx.empty()) std::filesystem::create_directories(work);

  std::ofstream csv(out / "load.csv");
  csv << "load_N,elastica_ux,elastica_uz,linear_ux,linear_uz,corot10_ux,corot10_uz,corot4_ux,corot4_uz,ccx_ux,ccx_uz,"
         "err_linear_vs_ccx,err_corot10_vs_ccx,err_corot4_vs_ccx,err_elastica_vs_ccx,err_linear_vs_elastica,"
         "err_corot10_vs_elastica,linear_s,corot10_s,corot4_s,ccx_s,corot10_iterations,corot4_iterations,"
         "err_ux_linear_vs_ccx,err_ux_corot10_vs_ccx\n";
  std::cout << "\n(b) Cantilever " << cells_text(cells) << " cells, dead load along +x on the top face; tip = mean of "
            << "the top-face nodes; corotated: " << load_steps << " load steps, consistent tangent; EI = " << EI
            << " N m^2\n";
  std::printf("%6s %9s | %9s %9s %9s %9s %9s | %8s %8s %8s %8s | %7s %7s %7s %7s\n", "P_N", "elast_ux", "lin_ux",
              "cr10_ux", "cr10_uz", "ccx_ux", "ccx_uz", "e_lin", "e_cr10", "e_cr4", "e_elast", "lin_s", "cr10_s", "cr4_s",
              "ccx_s");
  std::string summary;
  double linear_within_1_percent = 0.0; // the largest load up to which linear FEM stays within 1 %
  bool linear_good = true;
  for (double P : loads) {
    const Eigen::Vector3d total_force(P, 0.0, 0.0);
    Eigen::VectorXd f4 = Eigen::VectorXd::Zero(3 * tet4.num_nodes()), f10 = Eigen::VectorXd::Zero(3 * tet10.num_nodes());
    kerf::add_uniform_traction(tet4, boundary4, top_mask4, total_force, f4);
    kerf::add_uniform_traction(tet10, boundary10, top_mask10, total_force, f10);

    const Eigen::Vector2d elastica = elastica_tip_displacement(P, EI, L);
    auto start = clock::now();
    const Eigen::VectorXd u_linear = kerf::solve_linear_static(tet10, material, dofs10, f10, kerf::SolverSettings{});
    const double linear_seconds = seconds_since(start);
    const Eigen::Vector2d linear = mean_tip_displacement(top10, u_linear);
    const CorotatedTip corot10 = corotated_tip(tet10, dofs10, f10, top10, load_steps);
    const CorotatedTip corot4 = corotated_tip(tet4, dofs4, f4, top4, load_steps);

    Eigen::Vector2d calculix(not_a_number, not_a_number);
    double ccx_seconds = not_a_number;
    if (!ccx.empty()) {
      kerf::CalculixJob job;
      job.material = material;
      job.dirichlet = {{end_face_nodes(tet10, beam_min[2]), {0, 0, 0}}};
      job.nodal_loads = f10;
      std::ostringstream jobname;
      jobname << "nlgeom_P" << static_cast<int>(std::lround(P * 1000)) << "mN";
      try {
        const Eigen::MatrixXd u = solve_calculix_nlgeom(ccx, work, jobname.str(), tet10, job, ccx_seconds);
        calculix = mean_tip_displacement(top10, Eigen::VectorXd(u.transpose().reshaped()));
      } catch (const std::runtime_error& e) {
        std::cout << "CalculiX NLGEOM failed at P = " << P << " N: " << e.what() << '\n';
      }
    }
    const double e_linear = relative_difference(linear, calculix), e_corot10 = relative_difference(corot10.tip, calculix),
                 e_corot4 = relative_difference(corot4.tip, calculix), e_elastica = relative_difference(elastica, calculix);
    csv << P << ',' << elastica[0] << ',' << elastica[1] << ',' << linear[0] << ',' << linear[1] << ',' << corot10.tip[0]
        << ',' << corot10.tip[1] << ',' << corot4.tip[0] << ',' << corot4.tip[1] << ',' << calculix[0] << ',' << calculix[1]
        << ',' << e_linear << ',' << e_corot10 << ',' << e_corot4 << ',' << e_elastica << ','
        << relative_difference(linear, elastica) << ',' << relative_difference(corot10.tip, elastica) << ','
        << linear_seconds << ',' << corot10.seconds << ',' << corot4.seconds << ',' << ccx_seconds << ','
        << corot10.iterations << ',' << corot4.iterations << ',' << std::abs(linear[0] / calculix[0] - 1.0) << ','
        << std::abs(corot10.tip[0] / calculix[0] - 1.0) << '\n';
    std::printf("%6.3f %9.5f | %9.5f %9.5f %9.5f %9.5f %9.5f | %8.2e %8.2e %8.2e %8.2e | %7.3f %7.3f %7.3f %7.3f%s\n", P,
                elastica[0], linear[0], corot10.tip[0], corot10.tip[1], calculix[0], calculix[1], e_linear, e_corot10,
                e_corot4, e_elastica, linear_seconds, corot10.seconds, corot4.seconds, ccx_seconds,
                corot10.converged && corot4.converged ? "" : " (corotated: NOT CONVERGED)");
    linear_good = linear_good && e_linear < 0.01;
    if (linear_good) linear_within_1_percent = P;
    summary = format("(b) cantilever at P = %.2f N (NLGEOM tip deflection %.1f %% of L): error against CalculiX NLGEOM: "
                     "linear %.2e, corotated Tet10 %.2e, corotated Tet4 %.2e, elastica %.2e; ",
                     P, 100.0 * calculix[0] / L, e_linear, e_corot10, e_corot4, e_elastica) +
              (linear_within_1_percent > 0.0 ? format("linear FEM within 1 %% up to P = %.2f N", linear_within_1_percent)
                                             : std::string("linear FEM off by more than 1 % at every load"));
  }
  if (!ccx.empty()) std::filesystem::remove_all(work);
  return summary;
}

// @sect3{(c) Inversion: one element squeezed through zero volume}

/// The reference tet with corners 0, h e_x, h e_y, h e_z.
kerf::TetMesh single_tet(double h) {
  kerf::TetMesh mesh;
  mesh.nodes.resize(4, 3);
  mesh.nodes << 0, 0, 0, h, 0, 0, 0, h, 0, 0, 0, h;
  mesh.tets.resize(1, 4);
  mesh.tets << 0, 1, 2, 3;
  return mesh;
}

/// What one rotation method makes of the squeezed element at one point of the path.
struct SqueezeResponse {
  double det_R = 0.0;
  bool rotation_converged = false;
  double force_normal = 0.0; ///< force of the element on node 3 along +z (> 0 pushes it back out)
  double force_norm = 0.0;
  double energy = 0.0;
};

SqueezeResponse squeeze_response(const kerf::CorotationalModel& model, const Eigen::VectorXd& u, const Eigen::Matrix3d& F,
                                 kerf::RotationMethod method) {
  SqueezeResponse r;
  const kerf::PolarDecomposition polar = kerf::element_rotation(F, method);
  r.det_R = polar.R.determinant();
  r.rotation_converged = polar.converged;
  Eigen::VectorXd f_int;
  model.assemble(u, method, kerf::CorotationalTangent::warped, f_int, nullptr, nullptr);
  // f_int is the force the node exerts on the element; the element pushes on the node with -f_int.
  r.force_normal = -f_int[3 * 3 + 2];
  r.force_norm = f_int.segment<3>(3 * 3).norm();
  r.energy = model.energy(u, method);
  return r;
}

/// Moves corner 3 of one Tet4 on the straight line through the centroid c of the opposite face:
/// x_3(s) = c + s (X_3 - c). The height over that face is s h, so det F = s exactly: from 1
/// (undeformed) through 0 (flat) to -0.5 (inverted, the corner half a height past the face).
/// Writes inversion.csv and returns one line for the summary.
std::string run_inversion_study(const std::filesystem::path& out) {
  const double h = 0.01;
  const kerf::TetMesh mesh = single_tet(h);
  const kerf::LinearMaterial material;
  const kerf::CorotationalModel model(mesh, material);
  Eigen::Matrix<double, 4, 3> X = mesh.nodes;
  const Eigen::Vector3d X3 = X.row(3).transpose();
  const Eigen::Vector3d c = (X.row(0) + X.row(1) + X.row(2)).transpose() / 3.0;
  double det_J = 0.0;
  const Eigen::Matrix<double, 4, 3> G = kerf::physical_shape_gradients<4>(X, kerf::tet4_shape_gradients(), det_J);
  const Eigen::Matrix<double, 12, 12> K = kerf::tet4_stiffness(X, material);

  std::ofstream csv(out / "inversion.csv");
  csv << "det_F,linear_force_z_N,linear_energy_J,higham_det_R,higham_converged,higham_force_z_N,higham_force_norm_N,"
         "higham_energy_J,svd_det_R,svd_force_z_N,svd_force_norm_N,svd_energy_J\n";
  std::cout << "\n(c) One Tet4 (h = " << h << " m) squeezed through zero volume: force of the element on the moving "
            << "corner along +z (> 0 pushes it back) and energy\n";
  std::printf("%6s | %10s | %6s %4s %10s %10s | %6s %10s %10s\n", "det_F", "lin_f_z", "detR_H", "conv", "f_z_H", "E_H",
              "detR_S", "f_z_S", "E_S");
  std::string summary;
  for (int i = 0; i <= 60; ++i) {
    const double s = 1.0 - 0.025 * i;
    Eigen::VectorXd u = Eigen::VectorXd::Zero(12);
    u.segment<3>(9) = c + s * (X3 - c) - X3;
    Eigen::Matrix<double, 4, 3> x = X;
    x.row(3) += u.segment<3>(9).transpose();
    const Eigen::Matrix3d F = x.transpose() * G;
    const double linear_force_z = -(K * u)[11];
    const double linear_energy = 0.5 * u.dot(K * u);
    const SqueezeResponse higham = squeeze_response(model, u, F, kerf::RotationMethod::higham);
    const SqueezeResponse svd = squeeze_response(model, u, F, kerf::RotationMethod::svd);
    csv << F.determinant() << ',' << linear_force_z << ',' << linear_energy << ',' << higham.det_R << ','
        << (higham.rotation_converged ? 1 : 0) << ',' << higham.force_normal << ',' << higham.force_norm << ','
        << higham.energy << ',' << svd.det_R << ',' << svd.force_normal << ',' << svd.force_norm << ',' << svd.energy << '\n';
    if (i % 4 == 0)
      std::printf("%6.3f | %10.3e | %6.2f %4d %10.3e %10.3e | %6.2f %10.3e %10.3e\n", F.determinant(), linear_force_z,
                  higham.det_R, higham.rotation_converged ? 1 : 0, higham.force_normal, higham.energy, svd.det_R,
                  svd.force_normal, svd.energy);
    summary = format("(c) one Tet4 at det F = %.2f: force along +z with Higham's R (det R = %.0f) %+.2f N, with the SVD "
                     "rotation (det R = %.0f) %+.2f N (> 0 pushes back)",
                     F.determinant(), higham.det_R, higham.force_normal, svd.det_R, svd.force_normal);
  }
  return summary;
}

/// The smallest det F over the Tet4 elements of `mesh` displaced by u: negative if any is inverted.
double min_det_F(const kerf::TetMesh& mesh, const Eigen::VectorXd& u) {
  double smallest = std::numeric_limits<double>::infinity();
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    Eigen::Matrix<double, 4, 3> X, x;
    for (int k = 0; k < 4; ++k) {
      X.row(k) = mesh.nodes.row(mesh.tets(t, k));
      x.row(k) = X.row(k) + u.segment<3>(3 * mesh.tets(t, k)).transpose();
    }
    double det_J = 0.0;
    const Eigen::Matrix<double, 4, 3> G = kerf::physical_shape_gradients<4>(X, kerf::tet4_shape_gradients(), det_J);
    smallest = std::min(smallest, (x.transpose() * G).determinant());
  }
  return smallest;
}

/// A block 2 x 2 x 2 cm (cells^3 cells, Tet4) clamped at the bottom; its top centre node is
/// pushed down by a few element heights, so the tets around it are squeezed flat and some may
/// invert. We solve with each rotation method and each tangent and report what happens.
/// Returns one line for the summary.
std::string run_block_study(int cells, const std::vector<double>& depths_in_cells, const std::filesystem::path& out) {
  const double a = 0.02, cell = a / cells;
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {a, a, a}, Eigen::Vector3i::Constant(cells));
  kerf::NodeRegion bottom;
  bottom.box_max = Eigen::Vector3d(a, a, 0.0);
  kerf::NodeRegion punch;
  punch.box_min = Eigen::Vector3d(a / 2, a / 2, a);
  punch.box_max = punch.box_min;
  const std::vector<int> punched = kerf::nodes_in_region(mesh, punch);
  const kerf::CorotationalModel model(mesh, kerf::LinearMaterial{});
  const std::pair<kerf::RotationMethod, const char*> rotations[] = {
      {kerf::RotationMethod::higham, "higham"}, {kerf::RotationMethod::svd, "svd"}, {kerf::RotationMethod::automatic, "automatic"}};
  const std::pair<kerf::CorotationalTangent, const char*> tangents[] = {{kerf::CorotationalTangent::consistent, "consistent"},
                                                                      {kerf::CorotationalTangent::warped, "warped"}};

  std::ofstream csv(out / "block.csv");
  csv << "rotation,tangent,depth_in_cells,depth_m,load_steps,converged,newton_iterations,inverted_points,higham_failures,"
         "warped_fallbacks,dropped_rotation_terms,min_det_F,seconds,error\n";
  std::cout << "\n(c') Block " << a << " m, " << cells << "^3 cells (" << mesh.num_tets() << " Tet4), bottom clamped, top "
            << "centre node pushed down by d cells (cell " << cell << " m), 20 load steps\n";
  std::printf("%5s %-9s %-10s %5s %6s %8s %8s %10s %7s %s\n", "d", "rotation", "tangent", "conv", "iters", "inverted",
              "higham_f", "min_det_F", "s", "error");
  int runs = 0, converged_runs = 0, runs_ending_inverted = 0;
  for (double depth_in_cells : depths_in_cells) {
    const double depth = depth_in_cells * cell;
    const kerf::DofMap dofs =
        kerf::make_dof_map(mesh.num_nodes(), {{kerf::nodes_in_region(mesh, bottom), {0, 0, 0}}, {punched, {0, 0, -depth}}});
    for (const auto& [rotation, rotation_name] : rotations)
      for (const auto& [tangent, tangent_name] : tangents) {
        kerf::QuasiStaticSettings settings;
        settings.load_steps = 20;
        settings.rotation = rotation;
        settings.tangent = tangent;
        kerf::QuasiStaticResult result;
        std::string error;
        const auto start = clock::now();
        // A failing solve is a result here, not an error of the study: we record its message.
        try {
          result = kerf::solve_quasi_static(model, dofs, Eigen::VectorXd::Zero(3 * mesh.num_nodes()), settings);
        } catch (const std::exception& e) {
          error = e.what();
          result.converged = false;
        }
        const double seconds = seconds_since(start);
        const double smallest_det_F = error.empty() ? min_det_F(mesh, result.u) : not_a_number;
        std::replace(error.begin(), error.end(), ',', ';');
        int warped_fallbacks = 0;
        for (const kerf::NewtonIteration& iteration : result.history) warped_fallbacks += iteration.warped_fallback;
        csv << rotation_name << ',' << tangent_name << ',' << depth_in_cells << ',' << depth << ',' << settings.load_steps
            << ',' << (result.converged ? 1 : 0) << ',' << result.total_iterations << ','
            << result.last_statistics.inverted_points << ',' << result.last_statistics.higham_failures << ','
            << warped_fallbacks << ',' << result.last_statistics.dropped_rotation_terms << ',' << smallest_det_F << ',' << seconds << ',' << error << '\n';
        std::printf("%5.1f %-9s %-10s %5s %6d %8d %8d %10.3f %7.3f %s\n", depth_in_cells, rotation_name, tangent_name,
                    result.converged ? "yes" : "no", result.total_iterations, result.last_statistics.inverted_points,
                    result.last_statistics.higham_failures, smallest_det_F, seconds, error.c_str());
        ++runs;
        converged_runs += result.converged ? 1 : 0;
        runs_ending_inverted += !(smallest_det_F > 0.0) ? 1 : 0;
      }
  }
  return format("(c') punched block: %d of %d runs converged, %d ended with inverted elements", converged_runs, runs,
                runs_ending_inverted);
}

} // namespace corotation_study

/// `02_corotation_study [--quick] [--out DIR]`: see the header comment.
int main(int argc, char** argv) {
  try {
    const std::optional<kerf_measure::RunOptions> options =
        kerf_measure::parse_run_options(argc, argv, "02_corotation_study [--quick] [--out DIR]", "output/corotation_study");
    if (!options) return 2;
    const bool quick = options->quick;
    const std::filesystem::path& out = options->out;
    std::filesystem::create_directories(out);
    namespace study = corotation_study;
    const auto start = study::clock::now();
    const Eigen::Vector3i cells = quick ? Eigen::Vector3i(1, 2, 6) : Eigen::Vector3i(3, 6, 20);
    std::vector<double> angles;
    // From 10 degrees: at 0 there is nothing to solve, and the solver's relative tolerance has
    // no force scale to measure against (every force is round-off).
    for (int degrees = quick ? 90 : 10; degrees <= 180; degrees += quick ? 90 : 10) angles.push_back(degrees);
    std::vector<std::string> summary;
    summary.push_back(study::run_ghost_study(cells, angles, out));
    const std::vector<double> loads = quick ? std::vector<double>{0.1, 1.4}
                                            : std::vector<double>{0.01, 0.02, 0.05, 0.1, 0.15, 0.2, 0.3, 0.4, 0.5, 0.6,
                                                                  0.7, 0.8, 0.9, 1.0, 1.1, 1.2, 1.3, 1.4, 1.5};
    summary.push_back(study::run_load_study(cells, loads, 5, KERF_CCX, out));
    summary.push_back(study::run_inversion_study(out));
    summary.push_back(study::run_block_study(4, quick ? std::vector<double>{2.5} : std::vector<double>{1.5, 2.5, 3.5}, out));
    std::cout << "\nSummary\n";
    for (const std::string& line : summary) std::cout << "  " << line << '\n';
    std::cout << "\nwrote " << out.string() << "/*.csv in " << study::seconds_since(start) << " s\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "02_corotation_study: " << e.what() << '\n';
    return 3;
  }
}
