// Chapter 5's convergence problem, shared by examples/05_convergence_study.cpp and the tests of
// tests/chapter_05/test_convergence_rates.cpp and test_stress_intensity.cpp: Williams's
// plane-strain field (fracture/williams_field.hpp) prescribed on the whole boundary of the slab
// [-0.5, 0.5]^2 x [0, 0.2] (m), cracked by the half-plane y = y_0, x < x_0 through its whole
// thickness, solved by the XFEM of chapters 4 and 5, and measured against the exact field.
//
// The front (x_0, y_0) = (0.2 h, -0.1 h) for the cell size h = 1 / n, n odd: at (0.7, 0.4) of
// its column of cells, so on every mesh of the ladder the front crosses the same tets at the
// same place in them, off every node, edge and face of the box mesh's tets (the planes through
// the z-axis of a cell, x = y and x + y = 1 in cell coordinates, miss (0.7, 0.4)), and the crack
// plane misses every node.
//
// The boundary condition is the XFEM interpolant of the exact field, every DOF of every
// boundary node prescribed:
//   u_v = u(x_v)                       (the field at the node: every enrichment is shifted),
//   a_k = -2 u(x_v)                    (a sign enrichment: the far side's field minus the home
//                                       side's, surface_enrichment.hpp. The far side's field at
//                                       x_v is its continuation across the crack's face, theta
//                                       -+ 2 pi, and every F_l changes sign there:
//                                       sin, cos(theta / 2 -+ pi) = -sin, -cos(theta / 2). On the
//                                       crack itself only F_1 is non-zero, but a node beside it
//                                       needs all four: with -2 F_1 c_1 alone, as this file had
//                                       at first, a boundary node next to the crack was off by
//                                       O(h / sqrt(r)) and the interpolant's energy error fell
//                                       like h^0.5),
//   b_{v,l} = c_l                      (a branch node's four functions),
// where u = sum_l F_l c_l is Williams's field in the branch functions (for
// A = K / (2 mu sqrt(2 pi)) and the frame a, b:
//   mode I:  c_1 = A_I (kappa + 1) b,  c_2 = A_I (kappa - 1) a,  c_3 = A_I a,  c_4 = -A_I b;
//   mode II: c_1 = A_II (kappa + 1) a, c_2 = -A_II (kappa - 1) b, c_3 = A_II b, c_4 = A_II a).
// A scene prescribes the same interpolant with a "williams" Dirichlet entry
// (scene/scene_williams.hpp; examples/05_williams_slab_tet4.json is this slab on n = 9, and
// tests/chapter_05/test_williams_scene.cpp checks the two DOF for DOF). The study keeps its own
// code for what a scene does not give: the errors split by region (measure_errors) and the
// boundary a displacement_file would give, which fixes only u_v and holds the node's
// enrichments at 0 (a gripped node, BoundaryEnrichments::gripped): on the faces the crack
// reaches (x = -0.5 and the two z-faces) that closes the crack's mouth, which the exact field
// opens by 2 A (kappa + 1) sqrt(r), and leaves the interior equations inconsistent with the
// exact field.
#pragma once

#include "kerf/cut/crack_front.hpp"
#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/cut/tet_pieces.hpp"
#include "kerf/fracture/interaction_integral.hpp"
#include "kerf/fracture/williams_field.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"
#include "kerf/quadrature/gauss_piece_rules.hpp"
#include "kerf/xfem/branch_enrichment.hpp"
#include "kerf/xfem/branch_functions.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"
#include "kerf/xfem/surface_enrichment.hpp"

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <memory>
#include <vector>

namespace williams_slab {

inline const Eigen::Vector3d slab_min(-0.5, -0.5, 0.0), slab_max(0.5, 0.5, 0.2);

/// Which enrichment the crack's front gets.
enum class TipEnrichment { none, topological, geometric };
inline const char* name(TipEnrichment e) {
  return e == TipEnrichment::none ? "none" : e == TipEnrichment::topological ? "topological" : "geometric";
}

/// How the boundary nodes' enrichments are prescribed (see the file's comment).
enum class BoundaryEnrichments { interpolated, gripped };

struct Setup {
  int cells = 5;  ///< n, odd: cells in x and y; max(2, round(n / 5)) in z
  int order = 1;  ///< 1 Tet4, 2 Tet10
  TipEnrichment enrichment = TipEnrichment::geometric;
  double radius = 0.1; ///< r_e of the geometric rule (m)
  kerf::StressIntensityFactors K{1.0e4, 0.0, 0.0};
  kerf::FrontRule front_rule = kerf::FrontRule::collapsed;
  int front_points = 0; ///< 0: the model's default
  /// The rule of the other tets with branch nodes (CrackTipFunctions). The model's defaults, 6
  /// and 3, cost 20 s on n = 9 with r_e = 0.2 m; degree 4 without grading costs 1.1 s and
  /// changes no error of the study in its 4 digits (the study's part "rules").
  int blending_degree = 4;
  int blending_depth = 0;
  BoundaryEnrichments boundary = BoundaryEnrichments::interpolated;
  /// Fries's ramp over the blending tets, or not (branch_enrichment.hpp).
  kerf::BlendingCorrection blending = kerf::BlendingCorrection::none;
};

inline double cell_size(const Setup& s) { return (slab_max[0] - slab_min[0]) / s.cells; }

/// The front's frame: origin (0.2 h, -0.1 h, 0), a = +x, b = +y (the rectangle's normal).
inline kerf::StraightFrontFrame front_frame(const Setup& s) {
  const double h = cell_size(s);
  return kerf::make_straight_front_frame({0.2 * h, -0.1 * h, 0.0}, {1, 0, 0}, {0, 1, 0});
}

inline kerf::TetMesh slab_mesh(const Setup& s) {
  const int nz = std::max(2, static_cast<int>(std::lround(s.cells / 5.0)));
  const kerf::TetMesh tet4 = kerf::make_box_mesh(slab_min, slab_max, {s.cells, s.cells, nz});
  return s.order == 1 ? tet4 : kerf::tet10_from_tet4(tet4);
}

/// The crack y = y_0, x < x_0, overhanging the slab on three sides; edge1 x edge2 = +y.
inline kerf::TriangleSurface slab_crack(const Setup& s) {
  const Eigen::Vector3d o = front_frame(s).origin;
  return kerf::rectangle_surface(kerf::RectangleCut({-1.0, o[1], -1.0}, {0.0, 0.0, 2.2}, {1.0 + o[0], 0.0, 0.0}));
}

/// The sub-tets of each piece with the Gauss rule of the model's degree (tests/support/cut_body.hpp).
inline kerf::PieceQuadratureRule subtets(const Eigen::Matrix<double, 4, 3>&, const kerf::TetPieces& pieces, int piece, int degree) {
  return kerf::subtet_rule(pieces, piece, degree);
}

/// The cut slab with its model; everything the model holds by reference lives here.
struct Slab {
  Setup setup;
  kerf::LinearMaterial material{1.0e6, 0.3, 1000.0};
  kerf::StraightFrontFrame front;
  kerf::TetMesh mesh;
  kerf::CutSurfaces cuts;
  kerf::MeshPieces pieces;
  kerf::CrackFronts fronts;
  kerf::SurfaceEnrichment surface;                    // chapter 4's enrichment (TipEnrichment::none)
  std::unique_ptr<kerf::BranchEnrichment> branch;     // chapter 5's, or null
  std::unique_ptr<kerf::CrackTipFunctions> functions; // or null
  std::unique_ptr<kerf::CutXfemModel> model;

  explicit Slab(const Setup& s)
      : setup(s), front(front_frame(s)), mesh(slab_mesh(s)), cuts(std::vector<kerf::TriangleSurface>{slab_crack(s)}),
        pieces(kerf::cut_mesh_into_pieces(mesh, cuts)), fronts(kerf::find_crack_fronts(mesh, cuts)) {
    if (s.enrichment == TipEnrichment::none) {
      surface = kerf::make_surface_enrichment(mesh, pieces);
      model = std::make_unique<kerf::CutXfemModel>(mesh, material, pieces, surface, subtets);
      return;
    }
    const kerf::TipEnrichmentRule rule =
        s.enrichment == TipEnrichment::topological ? kerf::TipEnrichmentRule::topological : kerf::TipEnrichmentRule::geometric;
    branch = std::make_unique<kerf::BranchEnrichment>(kerf::make_branch_enrichment(mesh, pieces, fronts, rule, s.radius, s.blending));
    functions = std::make_unique<kerf::CrackTipFunctions>(kerf::CrackTipFunctions{*branch, fronts, s.front_rule, s.front_points, s.blending_degree, s.blending_depth});
    model = std::make_unique<kerf::CutXfemModel>(mesh, material, pieces, branch->sign, subtets, functions.get());
  }
  Slab(const Slab&) = delete;
  Slab& operator=(const Slab&) = delete;

  Eigen::Vector3d exact(const Eigen::Vector3d& x) const { return kerf::williams_displacement(front, setup.K, material, x); }
  Eigen::Matrix3d exact_gradient(const Eigen::Vector3d& x) const {
    return kerf::williams_displacement_gradient(front, setup.K, material, x);
  }

  /// c_1 .. c_4 of u = sum_l F_l c_l (the file's comment).
  std::array<Eigen::Vector3d, 4> branch_coefficients() const {
    const double kappa = 3.0 - 4.0 * material.poisson;
    const double scale = 1.0 / (2.0 * material.mu() * std::sqrt(2.0 * M_PI));
    const double A_I = setup.K.K_I * scale, A_II = setup.K.K_II * scale;
    const Eigen::Vector3d a = front.R.col(0), b = front.R.col(1);
    return {A_I * (kappa + 1.0) * b + A_II * (kappa + 1.0) * a, A_I * (kappa - 1.0) * a - A_II * (kappa - 1.0) * b, A_I * a + A_II * b,
            -A_I * b + A_II * a};
  }

  static bool on_boundary(const Eigen::Vector3d& x) {
    for (int p = 0; p < 3; ++p)
      if (std::abs(x[p] - slab_min[p]) < 1e-12 || std::abs(x[p] - slab_max[p]) < 1e-12) return true;
    return false;
  }

  /// The XFEM interpolant of the exact field (the file's comment): every DOF of every node, so
  /// that Galerkin's best approximation in energy can be checked against it.
  Eigen::VectorXd interpolant() const {
    const std::array<Eigen::Vector3d, 4> c = branch_coefficients();
    const kerf::SurfaceEnrichment& sign = model->enrichment();
    const Eigen::Index N = mesh.num_nodes();
    Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * model->num_dof_nodes());
    for (Eigen::Index v = 0; v < N; ++v) {
      const Eigen::Vector3d x = mesh.nodes.row(v).transpose();
      u.segment<3>(3 * v) = exact(x);
      for (int k = sign.first_enrichment[static_cast<std::size_t>(v)]; k < sign.first_enrichment[static_cast<std::size_t>(v) + 1]; ++k)
        u.segment<3>(3 * (N + k)) = -2.0 * exact(x);
      if (branch)
        if (const int slot = branch->branch_slot[static_cast<std::size_t>(v)]; slot >= 0)
          for (int l = 0; l < 4; ++l) u.segment<3>(3 * (model->branch_dof_node(slot) + l)) = c[static_cast<std::size_t>(l)];
    }
    return u;
  }

  /// Every DOF of every boundary node at the interpolant's value, or, gripped, the standard DOFs
  /// only (make_cut_xfem_dof_map then holds the node's enrichments at 0).
  std::vector<kerf::DirichletNodes> boundary_conditions() const {
    const Eigen::VectorXd I = interpolant();
    const kerf::SurfaceEnrichment& sign = model->enrichment();
    const auto N = static_cast<int>(mesh.num_nodes());
    std::vector<kerf::DirichletNodes> conditions;
    const auto prescribe = [&](int dof_node) { conditions.push_back({{dof_node}, I.segment<3>(3 * dof_node)}); };
    for (int v = 0; v < N; ++v) {
      if (!on_boundary(mesh.nodes.row(v).transpose())) continue;
      prescribe(v);
      if (setup.boundary == BoundaryEnrichments::gripped) continue;
      for (int k = sign.first_enrichment[static_cast<std::size_t>(v)]; k < sign.first_enrichment[static_cast<std::size_t>(v) + 1]; ++k)
        prescribe(N + k);
      if (branch)
        if (const int slot = branch->branch_slot[static_cast<std::size_t>(v)]; slot >= 0)
          for (int l = 0; l < 4; ++l) prescribe(static_cast<int>(model->branch_dof_node(slot)) + l);
    }
    return conditions;
  }
};

/// The errors of a field against the exact one, over the whole slab.
struct Errors {
  double L2 = 0.0, L2_exact = 0.0;         ///< ||u_h - u||, ||u|| (m sqrt(m^3))
  double energy = 0.0, energy_exact = 0.0; ///< sqrt(int eps(e) : C : eps(e)), the same of u
  double L2_blending = 0.0;                ///< ||u_h - u|| over the tets with some, not all, corners in I* (branch_enrichment.hpp)
  double L2_enriched = 0.0;                ///< ... over the tets with all corners in I*
  double relative_L2() const { return L2 / L2_exact; }
  double relative_energy() const { return energy / energy_exact; }
};

/// ||u_h - u|| and the energy norm by quadrature on every piece of every tet (the pieces of the
/// cut tets, so that no rule straddles the crack): sub-tets with the Gauss rule of degree 4,
/// refined twice in the tets the front crosses and once in those whose centre lies within two
/// cells of it (the error of a field without branch functions grows like 1 / sqrt(r) in its
/// gradient there). The library's kerf::cut_xfem_field_error (xfem/cut_xfem_field_error.hpp),
/// which the chapter's program prints for a scene's "williams" entry, integrates the same norms
/// but refines within two of the tet's longest edges (the cell's diagonal, not its width) and
/// does not split the error by region, which the study's blending tables need. The two are not
/// equal to round-off: on n = 9 and 17 their relative L2 errors differ by at most 1.5e-5 of
/// themselves, the energy errors by 6e-7 (quadrature error: the committed numbers stand).
inline Errors measure_errors(const Slab& slab, const Eigen::VectorXd& u) {
  const kerf::CutXfemModel& model = *slab.model;
  const double mu = slab.material.mu(), lambda = slab.material.lambda();
  const auto energy_density = [&](const Eigen::Matrix3d& H) {
    const Eigen::Matrix3d eps = 0.5 * (H + H.transpose());
    return lambda * eps.trace() * eps.trace() + 2.0 * mu * eps.squaredNorm();
  };
  const double h = cell_size(slab.setup);
  Errors e;
  for (Eigen::Index t = 0; t < slab.mesh.num_tets(); ++t) {
    const Eigen::Matrix<double, 4, 3> X = kerf::tet_corners(slab.mesh, t);
    const int entry = slab.pieces.entry[static_cast<std::size_t>(t)];
    const kerf::TetPieces whole = entry < 0 ? kerf::split_tet_by_triangles(X, {}) : kerf::TetPieces{};
    const kerf::TetPieces& tp = entry < 0 ? whole : slab.pieces.tets[static_cast<std::size_t>(entry)];
    const bool front = !kerf::front_in_tet(slab.fronts, X).empty();
    const int refinements = front ? 2 : (slab.fronts.distance(X.colwise().mean().transpose()) < 2.0 * h ? 1 : 0);
    int branch_corners = 0;
    if (slab.branch)
      for (int a = 0; a < 4; ++a)
        branch_corners += slab.branch->kind[static_cast<std::size_t>(slab.mesh.tets(t, a))] == kerf::NodeEnrichmentKind::branch;
    for (int p = 0; p < tp.num_pieces(); ++p) {
      const kerf::PieceQuadratureRule rule = kerf::refined_subtet_rule(tp, p, 4, refinements);
      for (std::size_t q = 0; q < rule.points.size(); ++q) {
        const Eigen::Vector3d& x = rule.points[q];
        const double w = rule.weights[q];
        const Eigen::Vector3d exact = slab.exact(x);
        const double squared = (model.displacement_at(u, t, x) - exact).squaredNorm();
        e.L2 += w * squared;
        e.L2_exact += w * exact.squaredNorm();
        if (branch_corners == 4) e.L2_enriched += w * squared;
        if (branch_corners > 0 && branch_corners < 4) e.L2_blending += w * squared;
        const Eigen::Matrix3d H = slab.exact_gradient(x);
        e.energy += w * energy_density(model.displacement_gradient_at(u, t, x) - H);
        e.energy_exact += w * energy_density(H);
      }
    }
  }
  for (double* v : {&e.L2, &e.L2_exact, &e.energy, &e.energy_exact, &e.L2_blending, &e.L2_enriched}) *v = std::sqrt(*v);
  return e;
}

/// Solves the slab with its boundary conditions (no body force).
inline Eigen::VectorXd solve(const Slab& slab, int* unknowns = nullptr) {
  const kerf::DofMap dofs = kerf::make_cut_xfem_dof_map(*slab.model, slab.boundary_conditions());
  if (unknowns) *unknowns = dofs.num_free;
  return kerf::solve_linear_cut_xfem(*slab.model, dofs, Eigen::VectorXd::Zero(3 * slab.model->num_dof_nodes()), kerf::SolverSettings{});
}

/// The interaction integral's domain around the slab's front: q = 1 within 0.1 m, 0 beyond
/// 0.3 m (inside the slab's 0.5 m), w falling over 0.05 m at each face z = 0, 0.2.
inline kerf::InteractionDomain interaction_domain(const Slab& slab) {
  kerf::InteractionDomain d;
  d.front = slab.front;
  d.front_begin = slab_min[2];
  d.front_end = slab_max[2];
  d.end_ramp = 0.05;
  d.inner_radius = 0.1;
  d.outer_radius = 0.3;
  return d;
}

/// K of the XFEM field by the interaction integral of its gradient.
inline kerf::StressIntensityFactors interaction_sifs(const Slab& slab, const Eigen::VectorXd& u) {
  const auto gradient = [&](Eigen::Index t, const Eigen::Vector3d& x) { return slab.model->displacement_gradient_at(u, t, x); };
  return kerf::interaction_integral_sifs(slab.mesh, gradient, slab.material, interaction_domain(slab));
}

} // namespace williams_slab
