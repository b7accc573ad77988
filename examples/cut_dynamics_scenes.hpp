// The scenes of chapter 6's validation study (06_cut_dynamics_study.cpp), shared with its tests
// (tests/chapter_06/test_validation_*.cpp): a cut body with its XFEM model, as a nonlinear
// dynamic system (linear or corotated), and the rule that turns XFEM into element duplication.
#pragma once

#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/dynamics/nonlinear_newmark.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/dynamics/lumped_mass.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/five_tet_cube.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"
#include "kerf/quadrature/gauss_piece_rules.hpp"
#include "kerf/xfem/cut_xfem_mass.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"
#include "kerf/xfem/surface_enrichment.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace cut_dynamics {

/// Schoch's beam tissue (section 6.1).
inline const kerf::LinearMaterial beam_material{300e3, 0.35, 1070.0};
/// The hinged cubes: stiff (strain rho g L / E ~ 1e-4 under their weight), so that a slice hangs
/// as a rigid body would.
inline const kerf::LinearMaterial cube_material{1e8, 0.3, 1000.0};

/// XFEM's rule: Gauss points on the sub-tetrahedra of the piece, exact on the piece.
inline kerf::PieceQuadratureRule piece_rule(const Eigen::Matrix<double, 4, 3>&, const kerf::TetPieces& pieces, int piece, int degree) {
  return kerf::subtet_rule(pieces, piece, degree);
}

/// Element duplication (the virtual node algorithm of Molino, Bao and Fedkiw 2004, as Koschier
/// section 7 describes it): every piece gets a full copy of its element, so it is integrated
/// with the whole tet's Gauss rule, weights not scaled by V_piece / V. Each piece
/// then carries the mass, the weight and the stiffness of the whole element.
inline kerf::PieceQuadratureRule duplication_rule(const Eigen::Matrix<double, 4, 3>& X, const kerf::TetPieces& pieces, int piece,
                                                  int degree) {
  kerf::PieceQuadratureRule rule = kerf::volume_ratio_rule(X, pieces, piece, degree);
  const double ratio = pieces.pieces[static_cast<std::size_t>(piece)].volume / pieces.volume;
  for (double& w : rule.weights) w /= ratio;
  return rule;
}

/// The volume of tet t (m^3).
inline double tet_volume(const kerf::TetMesh& mesh, Eigen::Index t) {
  const Eigen::Matrix<double, 4, 3> X = kerf::tet_corners(mesh, t);
  return std::abs(Eigen::Vector3d(X.row(1) - X.row(0)).cross(Eigen::Vector3d(X.row(2) - X.row(0))).dot(Eigen::Vector3d(X.row(3) - X.row(0)))) / 6.0;
}

/// A cut body, its consistent mass and gravity (both from the model's rule), clamped nodes, as
/// M a + f_int(u) = f for Newmark (nonlinear_newmark.hpp): f_int = K u (linear XFEM) or the
/// corotated force (Schoch et al. eq. 40). Lambdas refer to the members: not copyable.
struct CutDynamicBody {
  kerf::TetMesh mesh;
  kerf::CutSurfaces cuts;
  kerf::MeshPieces pieces;
  kerf::SurfaceEnrichment enrichment;
  kerf::CutXfemModel model;
  Eigen::SparseMatrix<double> K; // linear K^X on all DOFs
  kerf::SparseAssembler assembler;
  kerf::NonlinearDynamicSystem system;

  CutDynamicBody(kerf::TetMesh m, std::vector<kerf::TriangleSurface> surfaces, const kerf::LinearMaterial& material,
                 const kerf::PieceRuleFunction& rule, const std::vector<int>& clamped, const Eigen::Vector3d& gravity, bool corotated)
      : mesh(std::move(m)), cuts(std::move(surfaces)), pieces(kerf::cut_mesh_into_pieces(mesh, cuts)),
        enrichment(kerf::make_surface_enrichment(mesh, pieces)), model(mesh, material, pieces, enrichment, rule),
        assembler(model.assembly_slots(), kerf::make_dof_map(model.num_dof_nodes(), {})) {
    Eigen::VectorXd unused = Eigen::VectorXd::Zero(size());
    model.assemble_linear_stiffness(assembler, unused);
    K = assembler.matrix();
    system.M = kerf::assemble_cut_xfem_mass(model, material.density, rule);
    system.dofs = kerf::make_cut_xfem_dof_map(model, {{clamped, Eigen::Vector3d::Zero()}});
    const Eigen::VectorXd f = model.gravity_load(material.density, gravity);
    system.load = [f](double) { return f; };
    const Eigen::Index n = size();
    system.motion = [n](double) {
      return kerf::PrescribedMotion{Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n)};
    };
    if (corotated) {
      system.internal_force = [this](const Eigen::VectorXd& u, kerf::CorotationalTangent tangent, Eigen::VectorXd& f_int,
                                     const Eigen::SparseMatrix<double>** Kt) {
        Eigen::VectorXd scratch = Eigen::VectorXd::Zero(u.size());
        if (Kt) assembler.set_zero();
        model.assemble(u, kerf::RotationMethod::automatic, tangent, f_int, Kt ? &assembler : nullptr, Kt ? &scratch : nullptr);
        if (Kt) *Kt = &assembler.matrix();
      };
      system.elastic_energy = [this](const Eigen::VectorXd& u) { return model.energy(u, true); };
    } else {
      system.internal_force = [this](const Eigen::VectorXd& u, kerf::CorotationalTangent, Eigen::VectorXd& f_int,
                                     const Eigen::SparseMatrix<double>** Kt) {
        f_int = K * u;
        if (Kt) *Kt = &K;
      };
      system.elastic_energy = [this](const Eigen::VectorXd& u) { return 0.5 * u.dot(K * u); };
    }
  }
  CutDynamicBody(const CutDynamicBody&) = delete;
  CutDynamicBody& operator=(const CutDynamicBody&) = delete;

  /// Swaps the consistent mass and gravity for a lumped mass and its own gravity load
  /// (lumped_mass.hpp: each phantom node pulled by its own mass, so a freed piece falls at g).
  void use_lumped_mass(kerf::LumpingScheme scheme, double density, const Eigen::Vector3d& gravity, const kerf::PieceRuleFunction& rule) {
    system.M = kerf::lump_cut_xfem_mass(model, density, scheme, rule);
    const Eigen::VectorXd f = kerf::lumped_gravity_load(model, density, gravity, scheme, rule);
    system.load = [f](double) { return f; };
  }

  Eigen::Index size() const { return 3 * model.num_dof_nodes(); }
  Eigen::VectorXd zero() const { return Eigen::VectorXd::Zero(size()); }
  /// The deformed position of mesh node i (its standard DOFs: the home piece's displacement).
  Eigen::Vector3d position(const Eigen::VectorXd& u, int i) const { return mesh.nodes.row(i).transpose() + u.segment<3>(3 * i); }

  /// The true (not the model's) centre of mass of the material on one side of the cut, deformed by
  /// u: every piece (or uncut tet) whose centroid satisfies `side`, integrated exactly over its own
  /// geometry (sub-tetrahedra), displaced by its own phantom field.
  template <class Side> Eigen::Vector3d centre_of_mass(const Eigen::VectorXd& u, Side side) const {
    Eigen::Vector3d moment = Eigen::Vector3d::Zero();
    double volume = 0.0;
    for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
      const int count = model.num_integrated_pieces(t);
      for (int p = 0; p < count; ++p) {
        kerf::PieceQuadratureRule rule;
        if (model.integrated_by_pieces(t)) {
          rule = kerf::subtet_rule(pieces.tets[static_cast<std::size_t>(pieces.entry[static_cast<std::size_t>(t)])], p, 1);
        } else {
          rule.points = {kerf::tet_corners(mesh, t).colwise().mean().transpose()};
          rule.weights = {tet_volume(mesh, t)};
        }
        double w_total = 0.0;
        Eigen::Vector3d x_mean = Eigen::Vector3d::Zero();
        for (std::size_t q = 0; q < rule.points.size(); ++q) w_total += rule.weights[q], x_mean += rule.weights[q] * rule.points[q];
        if (!side(Eigen::Vector3d(x_mean / w_total))) continue;
        const Eigen::MatrixX3d U = model.phantom_displacements(u, t, model.integrated_by_pieces(t) ? p : 0);
        for (std::size_t q = 0; q < rule.points.size(); ++q) {
          const Eigen::VectorXd N = model.shape_values(t, rule.points[q]);
          moment += rule.weights[q] * (rule.points[q] + U.transpose() * N);
          volume += rule.weights[q];
        }
      }
    }
    return moment / volume;
  }

  /// The centre of mass of the whole body as the model has it, deformed by u: every piece
  /// integrated with `rule` (XFEM's: the true one; element duplication's: each piece a whole
  /// element), moved by its own phantom field. At rest under gravity alone this is the point the
  /// supports' reactions balance.
  Eigen::Vector3d model_centre_of_mass(const Eigen::VectorXd& u, const kerf::PieceRuleFunction& rule) const {
    Eigen::Vector3d moment = Eigen::Vector3d::Zero();
    double volume = 0.0;
    for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
      const Eigen::Matrix<double, 4, 3> X = kerf::tet_corners(mesh, t);
      if (!model.integrated_by_pieces(t)) {
        const double V = tet_volume(mesh, t);
        moment += V * (X.colwise().mean().transpose() + model.phantom_displacements(u, t, 0).colwise().mean().transpose());
        volume += V;
        continue;
      }
      const kerf::TetPieces& cut = pieces.tets[static_cast<std::size_t>(pieces.entry[static_cast<std::size_t>(t)])];
      for (int p = 0; p < pieces.num_pieces(t); ++p) {
        const kerf::PieceQuadratureRule r = rule(X, cut, p, 1); // x + u is linear on a Tet4: degree 1 is exact
        const Eigen::MatrixX3d U = model.phantom_displacements(u, t, p);
        for (std::size_t q = 0; q < r.points.size(); ++q) {
          moment += r.weights[q] * (r.points[q] + U.transpose() * model.shape_values(t, r.points[q]));
          volume += r.weights[q];
        }
      }
    }
    return moment / volume;
  }
};

/// The nodes of `mesh` with predicate(x) true.
template <class Predicate> std::vector<int> nodes_where(const kerf::TetMesh& mesh, Predicate predicate) {
  std::vector<int> nodes;
  for (Eigen::Index i = 0; i < mesh.num_nodes(); ++i)
    if (predicate(Eigen::Vector3d(mesh.nodes.row(i).transpose()))) nodes.push_back(static_cast<int>(i));
  return nodes;
}

/// The node of `mesh` nearest x.
inline int node_at(const kerf::TetMesh& mesh, const Eigen::Vector3d& x) {
  Eigen::Index best = 0;
  (mesh.nodes.rowwise() - x.transpose()).rowwise().squaredNorm().minCoeff(&best);
  return static_cast<int>(best);
}

/// Schoch's beam 0.03 x 0.06 x 0.2 m (section 6.1), Tet4, clamped at z = 0, gravity 9.81 m/s^2
/// along +x, consistent mass, cut at z = cut_z through x in [-0.005, 0.025]: the part above hangs
/// by a strip 5 mm wide at x = 0.03.
inline std::unique_ptr<CutDynamicBody> schoch_beam(const Eigen::Vector3i& cells, double cut_z, bool corotated) {
  kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {0.03, 0.06, 0.2}, cells);
  const std::vector<int> clamped = nodes_where(mesh, [](const Eigen::Vector3d& x) { return x.z() == 0.0; });
  const kerf::TriangleSurface cut = kerf::rectangle_surface(kerf::RectangleCut({-0.005, -0.005, cut_z}, {0.03, 0, 0}, {0, 0.07, 0}));
  return std::make_unique<CutDynamicBody>(std::move(mesh), std::vector<kerf::TriangleSurface>{cut}, beam_material,
                                                        piece_rule, clamped, Eigen::Vector3d(9.81, 0, 0), corotated);
}

/// The shape of the hanging slice of schoch_beam, from three of its nodes: the top edge from
/// (0, 0.03, 0.2) to (0.03, 0.03, 0.2), the side edge from (0, 0.03, 0.18) up to (0, 0.03, 0.2).
struct SliceShape {
  double rotation_deg = 0.0; ///< the angle the top edge turned through
  double stretch_top = 0.0;  ///< its length over its rest length, minus 1
  double stretch_side = 0.0; ///< the side edge's, likewise
};

inline SliceShape slice_shape(const CutDynamicBody& body, const Eigen::VectorXd& u) {
  const int p0 = node_at(body.mesh, {0, 0.03, 0.2}), p1 = node_at(body.mesh, {0.03, 0.03, 0.2}), p2 = node_at(body.mesh, {0, 0.03, 0.18});
  const Eigen::Vector3d top = body.position(u, p1) - body.position(u, p0), side = body.position(u, p0) - body.position(u, p2);
  const Eigen::Vector3d top0 = body.mesh.nodes.row(p1) - body.mesh.nodes.row(p0), side0 = body.mesh.nodes.row(p0) - body.mesh.nodes.row(p2);
  SliceShape shape;
  shape.rotation_deg = std::acos(std::clamp(top.normalized().dot(top0.normalized()), -1.0, 1.0)) * 180.0 / std::numbers::pi;
  shape.stretch_top = top.norm() / top0.norm() - 1.0;
  shape.stretch_side = side.norm() / side0.norm() - 1.0;
  return shape;
}

/// The demo's flap (chapters/06_newmark, 3 x 6 x 19 cells) with the scenes' default lumped mass
/// (per-piece Bernstein, the row sums on Tet4), its gravity and the Rayleigh damping C = 3 M + 0.002 K_R.
inline std::unique_ptr<CutDynamicBody> demo_flap(const Eigen::Vector3i& cells, bool corotated) {
  auto body = schoch_beam(cells, 0.15, corotated);
  body->use_lumped_mass(kerf::LumpingScheme::bernstein, beam_material.density, {9.81, 0, 0}, piece_rule);
  body->system.rayleigh_alpha = 3.0;
  body->system.rayleigh_beta = 0.002;
  return body;
}

/// Koschier's Fig. 10 cube: [0, 1]^3 of five tets, hinged on its top edge {x = 0, z = 1} (both
/// nodes clamped), gravity -z, cut through by the plane x = c into a slice [0, c] (on the hinge)
/// and the rest. A clamped node holds every piece at it (make_cut_xfem_dof_map). Here every tet
/// spans x in [0, 1], so the cut splits all five and the hinge nodes' phantom nodes on the far
/// side hold the rest too: it does not move, and it does not touch the slice. That is this mesh's
/// doing, not the method's: on a finer mesh whose tets at the hinge lie inside the slice, no
/// phantom node holds the rest, and it falls freely.
/// With tet10 the same five tets promoted to Tet10 (their edge nodes on the hinge clamped too).
inline std::unique_ptr<CutDynamicBody> hinged_cube(double c, const kerf::LinearMaterial& material, const kerf::PieceRuleFunction& rule,
                                                   bool tet10 = false) {
  kerf::TetMesh mesh = kerf::make_five_tet_cube({0, 0, 0}, {1, 1, 1});
  if (tet10) mesh = kerf::tet10_from_tet4(mesh);
  const std::vector<int> hinge = nodes_where(mesh, [](const Eigen::Vector3d& x) { return x.x() == 0.0 && x.z() == 1.0; });
  const kerf::TriangleSurface plane = kerf::rectangle_surface(kerf::RectangleCut({c, -0.5, -0.5}, {0, 2, 0}, {0, 0, 2}));
  return std::make_unique<CutDynamicBody>(std::move(mesh), std::vector<kerf::TriangleSurface>{plane}, material, rule, hinge,
                                          Eigen::Vector3d(0, 0, -9.81), true);
}

/// The volume the model gives the material on one side of the cut: XFEM each piece's own, element
/// duplication (every piece a whole copy of its element) the whole tet for every piece.
template <class Side> double model_volume(const CutDynamicBody& body, Side side, bool duplication) {
  double volume = 0.0;
  for (Eigen::Index t = 0; t < body.mesh.num_tets(); ++t) {
    const double V = tet_volume(body.mesh, t);
    if (!body.model.integrated_by_pieces(t)) {
      if (side(Eigen::Vector3d(kerf::tet_corners(body.mesh, t).colwise().mean().transpose()))) volume += V;
      continue;
    }
    const kerf::TetPieces& pieces = body.pieces.tets[static_cast<std::size_t>(body.pieces.entry[static_cast<std::size_t>(t)])];
    for (int p = 0; p < body.pieces.num_pieces(t); ++p) {
      const kerf::PieceQuadratureRule rule = kerf::subtet_rule(pieces, p, 1);
      double w = 0.0;
      Eigen::Vector3d x = Eigen::Vector3d::Zero();
      for (std::size_t q = 0; q < rule.points.size(); ++q) w += rule.weights[q], x += rule.weights[q] * rule.points[q];
      if (side(Eigen::Vector3d(x / w))) volume += duplication ? V : w;
    }
  }
  return volume;
}

/// Damped Newmark (gamma = 0.6, beta = 0.3025, Rayleigh alpha), Newton per step to 1e-8, from rest:
/// the state after `steps` steps; `each` is called with the state after every step.
template <class Each> kerf::DynamicState settle(CutDynamicBody& body, double alpha, double dt, int steps, Each each) {
  body.system.rayleigh_alpha = alpha;
  kerf::NonlinearNewmarkSettings settings;
  settings.update = kerf::RotationUpdate::newton;
  settings.newmark = {0.3025, 0.6};
  settings.tolerance = 1e-8; // the slab's steps stall at ~1e-9 near rest: round-off of its thin slices' stiff rows
  kerf::NonlinearNewmarkIntegrator integrator(body.system, dt, settings);
  kerf::DynamicState state = integrator.initial_state(body.zero(), body.zero(), 0.0);
  for (int n = 1; n <= steps; ++n) {
    const kerf::NonlinearStepReport report = integrator.step(state);
    if (!report.converged)
      throw std::runtime_error("a Newton step did not converge at step " + std::to_string(n) + " (relative residual " +
                               std::to_string(report.relative_residual) + ")");
    each(n, state);
  }
  return state;
}

/// Koschier's Fig. 11 slab, as Kerf reads it (the paper gives no dimensions, material or cut
/// positions): a plate of nx x 1 x nz blocks of h = 1 cm (Kerf's box mesh: six Tet4 a block, not
/// five), sticking out of the wall x = 0 (every node on it clamped) along x, 1 block thick in y,
/// gravity -z, cut along its whole length by the horizontal planes z = cut_z[k] (through the
/// wall, so each slice stays clamped) into slices of their own thickness in z: each slice is a
/// cantilever whose bending stiffness grows like its thickness cubed and its weight like the
/// thickness, so the thin ones fold further.
inline std::unique_ptr<CutDynamicBody> cut_slab(int nx, int nz, const std::vector<double>& cut_z, const kerf::LinearMaterial& material,
                                                const kerf::PieceRuleFunction& rule) {
  const double h = 0.01;
  kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {nx * h, h, nz * h}, {nx, 1, nz});
  const std::vector<int> wall = nodes_where(mesh, [](const Eigen::Vector3d& x) { return x.x() == 0.0; });
  std::vector<kerf::TriangleSurface> cuts;
  for (const double z : cut_z)
    cuts.push_back(kerf::rectangle_surface(kerf::RectangleCut({-h, -h, z}, {(nx + 2) * h, 0, 0}, {0, 3 * h, 0})));
  return std::make_unique<CutDynamicBody>(std::move(mesh), std::move(cuts), material, rule, wall, Eigen::Vector3d(0, 0, -9.81), true);
}

/// Koschier's Fig. 12 block, as Kerf reads it: the block [0, 1] x [0, 0.25] x [0, 1] (Tet4 on
/// 8 x 2 x 8 cells) hanging from the hinge {x = 1/2, z = 1} on its top face (the nodes on it
/// clamped; a line of nodes carries no moment about it), gravity -z, and cut into a zig-zag
/// that unfolds: the plane z = 0.55 through x in [-0.1, 0.78] (its lower part hangs from a neck
/// of 0.22 at x = 1) and z = 0.27 through x in [0.22, 1.1] (the lowest part hangs from a neck of
/// 0.22 at x = 0).
inline std::unique_ptr<CutDynamicBody> unfolding_block(const kerf::LinearMaterial& material, const kerf::PieceRuleFunction& rule) {
  kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 0.25, 1}, {8, 2, 8});
  const std::vector<int> hinge = nodes_where(mesh, [](const Eigen::Vector3d& x) { return x.x() == 0.5 && x.z() == 1.0; });
  const std::vector<kerf::TriangleSurface> cuts{kerf::rectangle_surface(kerf::RectangleCut({-0.1, -0.1, 0.55}, {0.88, 0, 0}, {0, 0.45, 0})),
                                                kerf::rectangle_surface(kerf::RectangleCut({0.22, -0.1, 0.27}, {0.88, 0, 0}, {0, 0.45, 0}))};
  return std::make_unique<CutDynamicBody>(std::move(mesh), cuts, material, rule, hinge, Eigen::Vector3d(0, 0, -9.81), true);
}

} // namespace cut_dynamics
