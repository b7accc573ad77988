/* Kerf, chapter 4 study: where the cut pieces fail. Slivers, cuts along mesh faces, cuts that
   stop a hair short of the body's surface, and the sign of a point near a kink.

   Build:   cmake --preset release && cmake --build --preset release --target 04_failure_study

   Sample runs:
     04_failure_study --quick --out output/failure_study_quick
     04_failure_study --out figures/04_cut_quadrature
     04_failure_study --only kink --out figures/04_cut_quadrature     (one part: fraction, faces, gap, kink)

   Description: chapter 3's beam (0.03 x 0.06 x 0.2 m, E = 300 kPa, nu = 0.35, rho = 1070 kg/m^3)
   clamped at z = 0, cut by triangle meshes, solved with chapter 4's linear XFEM
   (xfem/cut_xfem_model.hpp). Four parts, each writing one CSV file into the --out folder:
     failure_fraction.csv  the half-depth cut [0, 0.015] x [0, 0.06] at z = 0.1 + d, a distance d
                 above a node layer, d / h from 1e-1 to 1e-12 (h the cell height), case "pull"
                 (the top edge x = 0 lifted by 0.02 m); Tet4 on 4x4x10 cells with every rule
                 (subtets, exact, moment_fitting, lattice, volume_ratio), Tet10 on 2x2x6 with the
                 four that take Tet10, each with the sliver guard of eq. 22 off, at Koschier's
                 1e-9 (Kerf's default) and at chapter 3's 1e-4: the smallest piece fraction and V_enr / V_supp,
                 the condition number of K_ff (dense eigenvalues, plain and Jacobi-scaled) and
                 the solution's relative L2 difference from the cut exactly on the layer;
     failure_faces.csv     cuts lying exactly in mesh faces: a half-depth rectangle on a node
                 layer and a height field through the whole section on the layer it was meshed
                 to follow, Tet4 and Tet10, the XFEM solution against the mesh opened along
                 those faces (split_mesh_along_cut, split_box_along_height_field);
     failure_gap.csv       a cut through the whole section at z = 0.1003 that stops a relative
                 gap delta short of the side face x = 0.03 (delta > 0) or runs past it
                 (delta < 0), delta from 1e-3 to 1e-15 and 0: the tets' cut states, the
                 enrichments and the opening of the cut under a pull of the top face;
     failure_kink.csv      points in a band around a kink, classified by Paulus's closest-
                 triangle test and by angle-weighted pseudo-normals (cut/point_side.hpp), against
                 the pieces that hold them (tet_pieces.hpp: pieces_containing): our kinked cut of
                 the unit tet (Table 1's) and ridges and valleys z = 0.5 +- (0.05 - s |x - 0.5|) of
                 slopes s = 0.5 to 4 through a 5x5x5 unit cube.
   --quick runs every part on tiny meshes and few offsets in a few seconds; it is a test.

   Read chapter 4 first. */

#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/height_field_surface.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/cut/point_side.hpp"
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/cut/split_box_along_height_field.hpp"
#include "kerf/cut/split_mesh_along_cut.hpp"
#include "kerf/cut/tet_pieces.hpp"
#include "kerf/fem/assemble_loads.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/linear_material.hpp"
#include "kerf/fem/solve_linear_static.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/fem/tet_quadrature.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"
#include "kerf/quadrature/piece_quadrature_rule.hpp"
#include "kerf/solve/linear_solver.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"
#include "kerf/xfem/enrichment_volumes.hpp"
#include "kerf/xfem/surface_enrichment.hpp"
#include "measure.hpp" // bench/measure.hpp: the command line shared with the benchmarks

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>

namespace failure_study {

const double not_a_number = std::numeric_limits<double>::quiet_NaN();
const kerf::LinearMaterial material{300e3, 0.35, 1070.0};
const Eigen::Vector3d beam_min(0.0, 0.0, 0.0);
const Eigen::Vector3d beam_max(0.03, 0.06, 0.2);
using Corners = Eigen::Matrix<double, 4, 3>;

std::string cells_text(const Eigen::Vector3i& c) { return std::to_string(c[0]) + "x" + std::to_string(c[1]) + "x" + std::to_string(c[2]); }

kerf::TetMesh beam_mesh(const Eigen::Vector3i& cells, int order) {
  const kerf::TetMesh mesh = kerf::make_box_mesh(beam_min, beam_max, cells);
  return order == 1 ? mesh : kerf::tet10_from_tet4(mesh);
}

/// The rectangle [x0, x1] x [y0, y1] at height z as a cut surface, normal +z.
kerf::TriangleSurface horizontal_rectangle(double x0, double x1, double y0, double y1, double z) {
  return kerf::rectangle_surface(kerf::RectangleCut({x0, y0, z}, {x1 - x0, 0, 0}, {0, y1 - y0, 0}));
}

std::vector<int> nodes_where(const kerf::TetMesh& mesh, const std::function<bool(const Eigen::Vector3d&)>& keep) {
  std::vector<int> nodes;
  for (Eigen::Index i = 0; i < mesh.num_nodes(); ++i)
    if (keep(mesh.nodes.row(i).transpose())) nodes.push_back(static_cast<int>(i));
  return nodes;
}

/// Everything one cut XFEM solve keeps alive (the model refers to the others).
struct CutBody {
  kerf::TetMesh mesh;
  kerf::CutSurfaces cuts;
  kerf::MeshPieces pieces;
  kerf::SurfaceEnrichment enrichment;
  CutBody(kerf::TetMesh m, std::vector<kerf::TriangleSurface> surfaces)
      : mesh(std::move(m)), cuts(std::move(surfaces)), pieces(kerf::cut_mesh_into_pieces(mesh, cuts)),
        enrichment(kerf::make_surface_enrichment(mesh, pieces)) {}
};

kerf::PieceRuleFunction rule_of(kerf::QuadratureRuleKind kind) {
  return [kind](const Corners& X, const kerf::TetPieces& pieces, int piece, int degree) {
    kerf::PieceRuleOptions options;
    options.degree = degree;
    return kerf::piece_quadrature_rule(kind, X, pieces.triangles, pieces, piece, options);
  };
}

/// The extreme eigenvalues of a dense symmetric matrix and of its Jacobi scaling D^-1/2 A D^-1/2.
struct Spectrum {
  double lambda_min = not_a_number, lambda_max = not_a_number, jacobi_min = not_a_number, jacobi_max = not_a_number;
  double condition() const { return lambda_max / lambda_min; }
  double jacobi_condition() const { return jacobi_max / jacobi_min; }
};

Spectrum spectrum_of(const Eigen::MatrixXd& K) {
  Spectrum s;
  const Eigen::VectorXd eig = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(K, Eigen::EigenvaluesOnly).eigenvalues();
  // A zero diagonal (an unknown that no quadrature point sees) makes the scaling infinite: the
  // matrix is singular, and we say so with an infinite condition number.
  if (K.diagonal().minCoeff() <= 0.0) return {eig.minCoeff(), eig.maxCoeff(), 0.0, 1.0};
  const Eigen::VectorXd d = K.diagonal().cwiseSqrt().cwiseInverse();
  const Eigen::VectorXd scaled =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(d.asDiagonal() * K * d.asDiagonal(), Eigen::EigenvaluesOnly).eigenvalues();
  s.lambda_min = eig.minCoeff();
  s.lambda_max = eig.maxCoeff();
  s.jacobi_min = scaled.minCoeff();
  s.jacobi_max = scaled.maxCoeff();
  return s;
}

/// Points and weights for an L2 norm over the body: the degree-2 Gauss points of every tet.
struct SamplePoints {
  std::vector<Eigen::Index> tet;
  std::vector<Eigen::Vector3d> x;
  std::vector<double> weight;
};

SamplePoints gauss_points(const kerf::TetMesh& mesh) {
  SamplePoints s;
  const kerf::TetQuadratureRule rule = kerf::tet_quadrature_rule(2);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const Corners X = kerf::tet_corners(mesh, t);
    Eigen::Matrix3d J;
    for (int c = 0; c < 3; ++c) J.col(c) = (X.row(c + 1) - X.row(0)).transpose();
    for (std::size_t q = 0; q < rule.points.size(); ++q) {
      s.tet.push_back(t);
      s.x.push_back(X.row(0).transpose() + J * rule.points[q]);
      s.weight.push_back(rule.weights[q] * std::abs(J.determinant()));
    }
  }
  return s;
}

// @sect3{Part (a): a sliver piece, every rule, with and without the guard}

/// The offsets, meshes and guards of part (a).
struct FractionSizes {
  std::vector<double> offsets;                ///< d / h
  Eigen::Vector3i tet4_cells, tet10_cells;
  std::vector<double> guards;                 ///< sliver_fraction of make_cut_xfem_dof_map; 0 = off
};

FractionSizes fraction_sizes(bool quick) {
  FractionSizes s;
  if (quick) {
    s.offsets = {1e-1, 1e-6, 1e-12};
    s.tet4_cells = {2, 2, 4};
    s.tet10_cells = {2, 2, 4};
  } else {
    for (int k = 1; k <= 12; ++k) s.offsets.push_back(std::pow(10.0, -k));
    s.tet4_cells = {4, 4, 10};
    s.tet10_cells = {2, 2, 6};
  }
  s.guards = {0.0, kerf::koschier_sliver_fraction, kerf::chapter3_sliver_fraction};
  return s;
}

/// The half-depth cut of chapter 3 at height z, as a triangle surface: x from past the face
/// x = 0 to the front x = 0.015 (a node layer of both meshes), y past both side faces.
kerf::TriangleSurface half_depth_cut(double z) { return horizontal_rectangle(-0.01, 0.015, -0.01, 0.07, z); }

/// "pull": clamped at z = 0, the top edge x = 0, z = 0.2 lifted by 0.02 m.
std::vector<kerf::DirichletNodes> pull_conditions(const kerf::TetMesh& mesh) {
  return {{nodes_where(mesh, [](const Eigen::Vector3d& x) { return x.z() < 1e-12; }), {0, 0, 0}},
          {nodes_where(mesh, [](const Eigen::Vector3d& x) { return x.x() < 1e-12 && x.z() > 0.2 - 1e-12; }), {0, 0, 0.02}}};
}

/// The displacement of a solved model at the sample points.
std::vector<Eigen::Vector3d> sampled(const kerf::CutXfemModel& model, const Eigen::VectorXd& u, const SamplePoints& s) {
  std::vector<Eigen::Vector3d> values;
  for (std::size_t p = 0; p < s.x.size(); ++p) values.push_back(model.displacement_at(u, s.tet[p], s.x[p]));
  return values;
}

/// One mesh order: the reference (the cut on the layer; its tets are touched, never split, so no
/// piece rule enters it), then every offset, rule and guard.
void run_fraction(int order, const Eigen::Vector3i& cells, const FractionSizes& sizes, std::ofstream& csv) {
  using Kind = kerf::QuadratureRuleKind;
  std::vector<Kind> rules{Kind::subtets, Kind::exact, Kind::moment_fitting, Kind::lattice};
  if (order == 1) rules.push_back(Kind::volume_ratio);
  const double h = beam_max[2] / cells[2];
  const double layer = 0.1;

  CutBody on_layer(beam_mesh(cells, order), {half_depth_cut(layer)});
  const kerf::CutXfemModel reference(on_layer.mesh, material, on_layer.pieces, on_layer.enrichment, rule_of(Kind::subtets));
  const Eigen::VectorXd f_zero = Eigen::VectorXd::Zero(3 * reference.num_dof_nodes());
  const Eigen::VectorXd u_reference =
      kerf::solve_linear_cut_xfem(reference, kerf::make_cut_xfem_dof_map(reference, pull_conditions(on_layer.mesh), 0.0), f_zero, {});
  const SamplePoints points = gauss_points(on_layer.mesh);
  const std::vector<Eigen::Vector3d> reference_values = sampled(reference, u_reference, points);

  std::printf("\nSliver sweep, Tet%d on %s (h = %.4g m): the cut at z = 0.1 + d, case pull, linear\n", order == 1 ? 4 : 10,
              cells_text(cells).c_str(), h);
  std::printf("%8s %-14s %6s %9s %9s %4s %4s %5s %10s %10s %10s\n", "d/h", "rule", "guard", "min_piece", "min_Venr", "enr", "con",
              "dofs", "cond", "cond_jac", "rel_diff");
  for (double offset : sizes.offsets) {
    const double d = offset * h;
    CutBody body(beam_mesh(cells, order), {half_depth_cut(layer + d)});
    // The smallest piece of a split tet, as a fraction of its tet (exact volumes).
    double min_piece = not_a_number;
    for (const kerf::TetPieces& tp : body.pieces.tets)
      if (tp.state == kerf::SurfaceCutState::completely_cut)
        for (const kerf::TetPiece& piece : tp.pieces) min_piece = std::isnan(min_piece) ? piece.volume / tp.volume : std::min(min_piece, piece.volume / tp.volume);
    for (const Kind kind : rules) {
      const kerf::CutXfemModel model(body.mesh, material, body.pieces, body.enrichment, rule_of(kind));
      const kerf::EnrichmentVolumes volumes = model.enrichment_volumes();
      double min_fraction = not_a_number;
      for (Eigen::Index k = 0; k < body.enrichment.num_enrichments(); ++k)
        min_fraction = std::isnan(min_fraction) ? volumes.fraction(k) : std::min(min_fraction, volumes.fraction(k));
      std::vector<int> previous_constrained{-1};
      Spectrum spectrum;
      for (double guard : sizes.guards) {
        const std::vector<int> constrained = kerf::sliver_enrichments(volumes, guard);
        const kerf::DofMap dofs = kerf::make_cut_xfem_dof_map(model, pull_conditions(body.mesh), guard);
        // The same constrained set gives the same K_ff: its spectrum is computed once.
        if (constrained != previous_constrained) {
          kerf::SparseAssembler assembler(model.assembly_slots(), dofs);
          Eigen::VectorXd rhs = Eigen::VectorXd::Zero(dofs.num_free);
          model.assemble_linear_stiffness(assembler, rhs);
          spectrum = spectrum_of(assembler.matrix().toDense());
          previous_constrained = constrained;
        }
        // The difference from the cut on the layer, leaving out the slab 0.1 <= z <= 0.1 + d
        // where the two cuts put a point on different sides.
        double difference = not_a_number;
        bool ok = true;
        try {
          const Eigen::VectorXd u = kerf::solve_linear_cut_xfem(model, dofs, Eigen::VectorXd::Zero(3 * model.num_dof_nodes()), {});
          const std::vector<Eigen::Vector3d> values = sampled(model, u, points);
          double num = 0.0, den = 0.0;
          for (std::size_t p = 0; p < values.size(); ++p) {
            const double z = points.x[p].z();
            if (z >= layer - 1e-12 && z <= layer + d + 1e-12) continue;
            num += points.weight[p] * (values[p] - reference_values[p]).squaredNorm();
            den += points.weight[p] * reference_values[p].squaredNorm();
          }
          difference = std::sqrt(num / den);
          ok = std::isfinite(difference);
        } catch (const std::exception& error) {
          ok = false;
          std::cerr << "  d/h = " << offset << ", " << kerf::to_string(kind) << ", guard " << guard << ": " << error.what() << '\n';
        }
        csv << (order == 1 ? "tet4" : "tet10") << ',' << cells_text(cells) << ',' << offset << ',' << kerf::to_string(kind) << ',' << guard
            << ',' << min_piece << ',' << min_fraction << ',' << body.pieces.count(kerf::SurfaceCutState::completely_cut) << ','
            << body.enrichment.num_enrichments() << ',' << constrained.size() << ',' << dofs.num_free << ',' << model.num_negative_weights()
            << ',' << spectrum.lambda_min << ',' << spectrum.lambda_max << ',' << spectrum.condition() << ','
            << spectrum.jacobi_condition() << ',' << difference << ',' << ok << '\n';
        std::printf("%8.1e %-14s %6.0e %9.2e %9.2e %4d %4zu %5d %10.3e %10.3e %10.3e%s\n", offset, kerf::to_string(kind), guard, min_piece,
                    min_fraction, static_cast<int>(body.enrichment.num_enrichments()), constrained.size(), dofs.num_free,
                    spectrum.condition(), spectrum.jacobi_condition(), difference, ok ? "" : "  SOLVE FAILED");
      }
    }
  }
}

// @sect3{Part (b): a cut exactly in mesh faces, against the mesh opened along them}

/// The largest difference between the XFEM solution on `mesh` and the split mesh's solution,
/// compared node by node of every tet: the tet's node a has the phantom value u_a (or u_a + a_k
/// where an enrichment acts) in XFEM and the value of node split.tets(t, a) in the split mesh. Every
/// tet is one piece here (the cut lies in faces, no tet is split), and the split mesh keeps the
/// tets' order.
double nodewise_difference(const kerf::CutXfemModel& model, const Eigen::VectorXd& u, const kerf::TetMesh& split, const Eigen::VectorXd& u_split) {
  double worst = 0.0;
  for (Eigen::Index t = 0; t < split.num_tets(); ++t)
    for (int a = 0; a < split.nodes_per_tet(); ++a) {
      const Eigen::Vector3d x = model.phantom_displacements(u, t, 0).row(a).transpose();
      worst = std::max(worst, (x - u_split.segment<3>(3 * split.tets(t, a))).cwiseAbs().maxCoeff());
    }
  return worst;
}

/// Clamped at z = 0, the top face moved by (0.001, 0, 0.002) m, gravity along +x: both parts are
/// held (a cut through the whole section separates them), and the cut opens.
std::vector<kerf::DirichletNodes> both_ends(const kerf::TetMesh& mesh) {
  return {{nodes_where(mesh, [](const Eigen::Vector3d& x) { return x.z() < 1e-12; }), {0, 0, 0}},
          {nodes_where(mesh, [](const Eigen::Vector3d& x) { return x.z() > 0.2 - 1e-12; }), {0.001, 0, 0.002}}};
}

void run_faces(bool quick, std::ofstream& csv) {
  std::printf("\nCuts along mesh faces: XFEM against the mesh opened along them (nodewise max |difference| / max |u|)\n");
  const Eigen::Vector3d g(9.81, 0.0, 0.0);
  for (int order : {1, 2}) {
    // A half-depth rectangle on the node layer z = 0.1 with its front x = 0.015 on a node row.
    {
      const Eigen::Vector3i cells = quick ? Eigen::Vector3i(2, 2, 4) : Eigen::Vector3i(4, 4, 8);
      CutBody body(beam_mesh(cells, order), {horizontal_rectangle(-0.01, 0.015, -0.01, 0.07, 0.1)});
      const kerf::CutXfemModel model(body.mesh, material, body.pieces, body.enrichment, rule_of(kerf::QuadratureRuleKind::subtets));
      const auto clamp = std::vector<kerf::DirichletNodes>{{nodes_where(body.mesh, [](const Eigen::Vector3d& x) { return x.z() < 1e-12; }), {0, 0, 0}}};
      const Eigen::VectorXd u = kerf::solve_linear_cut_xfem(model, kerf::make_cut_xfem_dof_map(model, clamp), model.gravity_load(material.density, g), {});
      const kerf::SplitMesh split = kerf::split_mesh_along_cut(body.mesh, kerf::RectangleCut({0, 0, 0.1}, {0.015, 0, 0}, {0, 0.06, 0}), 1e-9);
      const auto split_clamp = std::vector<kerf::DirichletNodes>{{nodes_where(split.mesh, [](const Eigen::Vector3d& x) { return x.z() < 1e-12; }), {0, 0, 0}}};
      const Eigen::VectorXd u_split = kerf::solve_linear_static(split.mesh, material, kerf::make_dof_map(split.mesh.num_nodes(), split_clamp),
                                                                kerf::assemble_gravity(split.mesh, material.density, g), {});
      const double worst = nodewise_difference(model, u, split.mesh, u_split), scale = u_split.cwiseAbs().maxCoeff();
      csv << "rectangle," << (order == 1 ? "tet4" : "tet10") << ',' << cells_text(cells) << ',' << body.pieces.count(kerf::SurfaceCutState::touched)
          << ',' << body.pieces.count(kerf::SurfaceCutState::completely_cut) << ',' << body.enrichment.num_enrichments() << ','
          << split.duplicated_nodes << ',' << worst << ',' << scale << ',' << worst / scale << '\n';
      std::printf("  rectangle    Tet%-2d %s: %3d touched, %d split, %3d enrichments, %3d duplicates, difference %.2e of %.3e m\n",
                  order == 1 ? 4 : 10, cells_text(cells).c_str(), body.pieces.count(kerf::SurfaceCutState::touched),
                  body.pieces.count(kerf::SurfaceCutState::completely_cut), static_cast<int>(body.enrichment.num_enrichments()),
                  split.duplicated_nodes, worst / scale, scale);
    }
    // A height field through the whole section, on the node layer the box was meshed to follow.
    {
      const Eigen::Vector3i cells = quick ? Eigen::Vector3i(2, 2, 4) : Eigen::Vector3i(3, 6, 8);
      const kerf::HeightField h = [](double x, double y) { return 0.004 * std::sin(std::numbers::pi * x / 0.03) * std::cos(std::numbers::pi * y / 0.06); };
      const kerf::HeightFieldSplitMesh split = kerf::split_box_along_height_field(beam_min, beam_max, cells, 0.1, h, order);
      // The mapped box unopened: every duplicate replaced by its original.
      const Eigen::Index original_nodes = split.split.mesh.num_nodes() - split.split.duplicated_nodes;
      kerf::TetMesh mapped;
      mapped.nodes = split.split.mesh.nodes.topRows(original_nodes);
      mapped.tets = split.split.mesh.tets;
      for (Eigen::Index t = 0; t < mapped.tets.rows(); ++t)
        for (Eigen::Index a = 0; a < mapped.tets.cols(); ++a)
          if (mapped.tets(t, a) >= original_nodes) mapped.tets(t, a) = split.split.duplicate_of[static_cast<std::size_t>(mapped.tets(t, a) - original_nodes)];
      CutBody body(mapped, {split.cut_surface});
      const kerf::CutXfemModel model(body.mesh, material, body.pieces, body.enrichment, rule_of(kerf::QuadratureRuleKind::subtets));
      const Eigen::VectorXd u = kerf::solve_linear_cut_xfem(model, kerf::make_cut_xfem_dof_map(model, both_ends(body.mesh)),
                                                            model.gravity_load(material.density, g), {});
      const Eigen::VectorXd u_split = kerf::solve_linear_static(split.split.mesh, material, kerf::make_dof_map(split.split.mesh.num_nodes(), both_ends(split.split.mesh)),
                                                                kerf::assemble_gravity(split.split.mesh, material.density, g), {});
      const double worst = nodewise_difference(model, u, split.split.mesh, u_split), scale = u_split.cwiseAbs().maxCoeff();
      csv << "height_field," << (order == 1 ? "tet4" : "tet10") << ',' << cells_text(cells) << ',' << body.pieces.count(kerf::SurfaceCutState::touched)
          << ',' << body.pieces.count(kerf::SurfaceCutState::completely_cut) << ',' << body.enrichment.num_enrichments() << ','
          << split.split.duplicated_nodes << ',' << worst << ',' << scale << ',' << worst / scale << '\n';
      std::printf("  height field Tet%-2d %s: %3d touched, %d split, %3d enrichments, %3d duplicates, difference %.2e of %.3e m\n",
                  order == 1 ? 4 : 10, cells_text(cells).c_str(), body.pieces.count(kerf::SurfaceCutState::touched),
                  body.pieces.count(kerf::SurfaceCutState::completely_cut), static_cast<int>(body.enrichment.num_enrichments()),
                  split.split.duplicated_nodes, worst / scale, scale);
    }
  }
}

// @sect3{Part (c): a cut that stops a hair short of the side face, or runs past it}

/// The tet of `mesh` holding x (a brute-force search with a small tolerance; -1 if none).
Eigen::Index tet_holding(const kerf::TetMesh& mesh, const Eigen::Vector3d& x) {
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const Corners X = kerf::tet_corners(mesh, t);
    Eigen::Matrix3d J;
    for (int c = 0; c < 3; ++c) J.col(c) = (X.row(c + 1) - X.row(0)).transpose();
    const Eigen::Vector3d xi = J.inverse() * (x - X.row(0).transpose());
    if (xi.minCoeff() >= -1e-12 && xi.sum() <= 1.0 + 1e-12) return t;
  }
  return -1;
}

void run_gap(bool quick, std::ofstream& csv) {
  const Eigen::Vector3i cells = quick ? Eigen::Vector3i(3, 2, 4) : Eigen::Vector3i(3, 3, 10);
  const double z = 0.1003, lift = 0.002;
  std::vector<double> deltas = quick ? std::vector<double>{1e-3, 1e-12, 0.0, -1e-12}
                                     : std::vector<double>{1e-3, 1e-5, 1e-7, 1e-9, 1e-11, 1e-12, 1e-13, 1e-14, 1e-15, 0.0,
                                                           -1e-15, -1e-13, -1e-12, -1e-9, -1e-6, -1e-3};
  std::printf("\nA cut through the section at z = %.4f, ending a relative gap delta short of the face x = 0.03 (< 0: past it);\n"
              "clamped at z = 0, the top face lifted by %.3f m: the opening u_z(above) - u_z(below) at x = 0.005 and 0.025\n", z, lift);
  std::printf("%-6s %9s %5s %5s %5s %5s %5s %10s %10s %s\n", "order", "delta", "uncut", "touch", "part", "compl", "enr", "open_0.005",
              "open_0.025", "status");
  for (int order : {1, 2})
    for (double delta : deltas) {
      const double x1 = 0.03 * (1.0 - delta);
      CutBody body(beam_mesh(cells, order), {horizontal_rectangle(-0.01, x1, -0.01, 0.07, z)});
      const kerf::CutXfemModel model(body.mesh, material, body.pieces, body.enrichment, rule_of(kerf::QuadratureRuleKind::subtets));
      const std::vector<kerf::DirichletNodes> conditions{
          {nodes_where(body.mesh, [](const Eigen::Vector3d& x) { return x.z() < 1e-12; }), {0, 0, 0}},
          {nodes_where(body.mesh, [](const Eigen::Vector3d& x) { return x.z() > 0.2 - 1e-12; }), {0, 0, lift}}};
      std::string status = "solved";
      double opening[2] = {not_a_number, not_a_number};
      double min_piece = not_a_number;
      for (const kerf::TetPieces& tp : body.pieces.tets)
        for (const kerf::TetPiece& piece : tp.pieces)
          if (tp.num_pieces() > 1) min_piece = std::isnan(min_piece) ? piece.volume / tp.volume : std::min(min_piece, piece.volume / tp.volume);
      try {
        const Eigen::VectorXd u = kerf::solve_linear_cut_xfem(model, kerf::make_cut_xfem_dof_map(model, conditions),
                                                              Eigen::VectorXd::Zero(3 * model.num_dof_nodes()), {});
        for (int k = 0; k < 2; ++k) {
          const double x = k == 0 ? 0.005 : 0.025;
          const Eigen::Vector3d above(x, 0.03, z + 0.002), below(x, 0.03, z - 0.002);
          opening[k] = model.displacement_at(u, tet_holding(body.mesh, above), above).z() - model.displacement_at(u, tet_holding(body.mesh, below), below).z();
        }
        if (!std::isfinite(opening[0]) || !std::isfinite(opening[1])) status = "nan";
      } catch (const std::exception& error) {
        status = "refused";
        std::cerr << "  delta = " << delta << ": " << error.what() << '\n';
      }
      const auto count = [&](kerf::SurfaceCutState s) { return body.pieces.count(s); };
      csv << (order == 1 ? "tet4" : "tet10") << ',' << cells_text(cells) << ',' << delta << ',' << 0.03 - x1 << ',' << count(kerf::SurfaceCutState::uncut)
          << ',' << count(kerf::SurfaceCutState::touched) << ',' << count(kerf::SurfaceCutState::partially_cut) << ','
          << count(kerf::SurfaceCutState::completely_cut) << ',' << body.enrichment.num_enrichments() << ',' << min_piece << ','
          << opening[0] << ',' << opening[1] << ',' << status << '\n';
      std::printf("Tet%-3d %9.1e %5d %5d %5d %5d %5d %10.3e %10.3e %s\n", order == 1 ? 4 : 10, delta, count(kerf::SurfaceCutState::uncut),
                  count(kerf::SurfaceCutState::touched), count(kerf::SurfaceCutState::partially_cut), count(kerf::SurfaceCutState::completely_cut),
                  static_cast<int>(body.enrichment.num_enrichments()), opening[0], opening[1], status.c_str());
    }
}

// @sect3{Part (d): the side of a point near a kink}

/// The side of the piece holding x, from the pieces alone: the cut side of its polygons on the
/// cut (+1 above, -1 below), or 0 if x is in no piece or in several (on the cut).
int side_from_pieces(const kerf::TetPieces& pieces, const Eigen::Vector3d& x) {
  const std::vector<int> found = kerf::pieces_containing(pieces, x, 0.0);
  if (found.size() != 1) return 0;
  for (const kerf::PieceBoundaryPolygon& b : pieces.pieces[static_cast<std::size_t>(found.front())].boundary)
    if (b.on_cut) return b.cut_side;
  return 0;
}

/// The triangle (a, b, c) as surface vertices in the order whose normal has a positive component along `up`.
Eigen::Vector3i oriented(const kerf::TriangleSurface& s, int a, int b, int c, const Eigen::Vector3d& up) {
  const Eigen::Vector3d n = (s.vertices.row(b) - s.vertices.row(a)).cross(s.vertices.row(c) - s.vertices.row(a)).transpose();
  return n.dot(up) > 0.0 ? Eigen::Vector3i(a, b, c) : Eigen::Vector3i(a, c, b);
}

/// Our kinked cut of Table 1 (04_quadrature_study.cpp) as one connected surface: the floor
/// z = 0.3 where x + y <= 0.3 and the slope x + y + z = 0.6 where z <= 0.3, sharing the kink's
/// edge from K1 = (2.3, -2, 0.3) to K2 = (-2, 2.3, 0.3). Normals: +z and (1, 1, 1).
kerf::TriangleSurface table1_kink() {
  kerf::TriangleSurface s;
  s.vertices.resize(5, 3);
  s.vertices << 2.3, -2.0, 0.3, -2.0, 2.3, 0.3, -2.0, -2.0, 0.3, 2.3 + 1.5, -2.0 + 1.5, 0.3 - 3.0, -2.0 + 1.5, 2.3 + 1.5, 0.3 - 3.0;
  s.triangles.resize(3, 3);
  s.triangles.row(0) = oriented(s, 0, 1, 2, {0, 0, 1}).transpose();
  s.triangles.row(1) = oriented(s, 0, 3, 4, {1, 1, 1}).transpose();
  s.triangles.row(2) = oriented(s, 0, 4, 1, {1, 1, 1}).transpose();
  return s;
}

/// Counts of one classification run.
struct SideCounts {
  long points = 0, closest_wrong = 0, pseudo_wrong = 0, analytic_mismatch = 0;
};

void write_kink_row(std::ofstream& csv, const std::string& surface, double slope, double fold_degrees, double band, const SideCounts& c) {
  csv << surface << ',' << slope << ',' << fold_degrees << ',' << band << ',' << c.points << ',' << c.closest_wrong << ',' << c.pseudo_wrong << ','
      << static_cast<double>(c.closest_wrong) / static_cast<double>(c.points) << ','
      << static_cast<double>(c.pseudo_wrong) / static_cast<double>(c.points) << ',' << c.analytic_mismatch << '\n';
  std::printf("  %-8s s = %4.2f, normals %6.1f deg apart: %7ld points, closest triangle wrong %6.2f %%, pseudo-normal wrong %6.2f %%, "
              "pieces vs analytic %ld\n", surface.c_str(), slope, fold_degrees, c.points,
              100.0 * static_cast<double>(c.closest_wrong) / static_cast<double>(c.points),
              100.0 * static_cast<double>(c.pseudo_wrong) / static_cast<double>(c.points), c.analytic_mismatch);
}

void run_kink(bool quick, std::ofstream& csv) {
  std::mt19937 random(4);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const auto random_point_in = [&](const Corners& X) {
    Eigen::Vector4d b(-std::log(uniform(random)), -std::log(uniform(random)), -std::log(uniform(random)), -std::log(uniform(random)));
    b /= b.sum(); // uniform in the tet
    return Eigen::Vector3d((b.transpose() * X).transpose());
  };
  std::printf("\nThe side of a point near a kink, against the pieces that hold it\n");

  // Table 1's kinked cut of the unit tet: every point of the tet within 0.2 of the kink's line.
  {
    const kerf::TriangleSurface surface = table1_kink();
    const kerf::PseudoNormals normals = kerf::angle_weighted_pseudo_normals(surface);
    Corners X;
    X << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
    std::vector<kerf::CutTriangle> triangles;
    for (int f = 0; f < 3; ++f) {
      kerf::CutTriangle t;
      for (int c = 0; c < 3; ++c) t.corners[static_cast<std::size_t>(c)] = surface.vertices.row(surface.triangles(f, c)).transpose();
      t.triangle = f;
      triangles.push_back(t);
    }
    const kerf::TetPieces pieces = kerf::split_tet_by_triangles(X, triangles);
    const Eigen::Vector3d k0(0.3, 0.0, 0.3), direction = Eigen::Vector3d(1, -1, 0).normalized();
    SideCounts c;
    const double band = 0.2;
    for (int n = 0; n < (quick ? 2000 : 200000); ++n) {
      const Eigen::Vector3d x = random_point_in(X);
      const Eigen::Vector3d r = x - k0;
      if ((r - r.dot(direction) * direction).norm() > band) continue;
      const int truth = side_from_pieces(pieces, x);
      if (truth == 0) continue;
      const int analytic = (x.z() > 0.3 || x.x() + x.y() + x.z() > 0.6) ? 1 : -1;
      ++c.points;
      c.closest_wrong += kerf::closest_triangle_side(surface, x) != truth;
      c.pseudo_wrong += kerf::pseudo_normal_side(surface, normals, x) != truth;
      c.analytic_mismatch += analytic != truth;
    }
    // The normals (0, 0, 1) and (1, 1, 1) / sqrt 3 are 54.7 degrees apart.
    write_kink_row(csv, "table1", 0.0, std::acos(1.0 / std::sqrt(3.0)) * 180.0 / std::numbers::pi, band, c);
  }

  // Ridges z = 0.55 - s |x - 0.5| and valleys z = 0.45 + s |x - 0.5| through the unit cube, the
  // kink's line in the middle of a cell in x and off every node layer in z (on a layer, the tets
  // above a ridge's apex would only touch the cut, and hold no piece to judge by); points of the
  // split tets within 0.1 of the kink's line.
  const kerf::TetMesh cube = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, quick ? Eigen::Vector3i(3, 3, 3) : Eigen::Vector3i(5, 5, 5));
  const std::vector<double> slopes = quick ? std::vector<double>{0.5, 3.0} : std::vector<double>{0.5, 0.75, 1.0, 1.25, 1.5, 2.0, 3.0, 4.0};
  for (const int sign : {-1, 1})
    for (const double s : slopes) {
      const double apex = sign < 0 ? 0.55 : 0.45;
      const kerf::HeightField h = [=](double x, double) { return sign * s * std::abs(x - 0.5); };
      const kerf::TriangleSurface surface = kerf::height_field_surface(h, apex, {-0.5, -0.5}, {1.5, 1.5}, {4, 4});
      const kerf::PseudoNormals normals = kerf::angle_weighted_pseudo_normals(surface);
      const kerf::CutSurfaces cuts({surface});
      const kerf::MeshPieces pieces = kerf::cut_mesh_into_pieces(cube, cuts);
      SideCounts c;
      const double band = 0.1;
      for (std::size_t e = 0; e < pieces.tets.size(); ++e) {
        if (pieces.tets[e].num_pieces() < 2) continue;
        const Corners X = kerf::tet_corners(cube, pieces.entry_tet[e]);
        for (int n = 0; n < (quick ? 50 : 2000); ++n) {
          const Eigen::Vector3d x = random_point_in(X);
          if (std::hypot(x.x() - 0.5, x.z() - apex) > band) continue;
          const int truth = side_from_pieces(pieces.tets[e], x);
          if (truth == 0) continue;
          ++c.points;
          c.closest_wrong += kerf::closest_triangle_side(surface, x) != truth;
          c.pseudo_wrong += kerf::pseudo_normal_side(surface, normals, x) != truth;
          c.analytic_mismatch += (x.z() > apex + h(x.x(), x.y()) ? 1 : -1) != truth;
        }
      }
      // Normals (+-s, 0, 1) / sqrt(1 + s^2): 2 atan(s) apart.
      write_kink_row(csv, sign < 0 ? "ridge" : "valley", s, 2.0 * std::atan(s) * 180.0 / std::numbers::pi, band, c);
    }
}

} // namespace failure_study

int main(int argc, char** argv) {
  const auto options = kerf_measure::parse_run_options(argc, argv, "04_failure_study [--quick] [--out DIR] [--only fraction,faces,gap,kink]",
                                                       "output/failure_study", {"fraction", "faces", "gap", "kink"});
  if (!options) return 2;
  try {
    namespace fs = failure_study;
    std::filesystem::create_directories(options->out);
    std::cout << "Kerf chapter 4 failure study" << (options->quick ? " (quick)" : "") << " on " << kerf_measure::cpu_model() << ", "
              << kerf_measure::now_text() << "\n";
    if (options->runs("fraction")) {
      std::ofstream csv(options->out / "failure_fraction.csv");
      csv << "element,cells,offset,rule,guard,min_piece_fraction,min_enrichment_fraction,split_tets,enrichments,constrained,dofs,"
             "negative_weights,lambda_min,lambda_max,condition,jacobi_condition,rel_l2_difference,solve_ok\n";
      const fs::FractionSizes sizes = fs::fraction_sizes(options->quick);
      fs::run_fraction(1, sizes.tet4_cells, sizes, csv);
      fs::run_fraction(2, sizes.tet10_cells, sizes, csv);
    }
    if (options->runs("faces")) {
      std::ofstream csv(options->out / "failure_faces.csv");
      csv << "surface,element,cells,touched_tets,split_tets,enrichments,duplicated_nodes,max_difference_m,max_u_m,relative_difference\n";
      fs::run_faces(options->quick, csv);
    }
    if (options->runs("gap")) {
      std::ofstream csv(options->out / "failure_gap.csv");
      csv << "element,cells,delta,gap_m,uncut,touched,partially_cut,completely_cut,enrichments,min_piece_fraction,opening_x0.005,"
             "opening_x0.025,status\n";
      fs::run_gap(options->quick, csv);
    }
    if (options->runs("kink")) {
      std::ofstream csv(options->out / "failure_kink.csv");
      csv << "surface,slope,normals_angle_deg,band,points,closest_wrong,pseudo_wrong,closest_wrong_fraction,pseudo_wrong_fraction,"
             "pieces_vs_analytic_mismatch\n";
      fs::run_kink(options->quick, csv);
    }
  } catch (const std::exception& error) {
    std::cerr << "04_failure_study: " << error.what() << '\n';
    return 1;
  }
  return 0;
}
