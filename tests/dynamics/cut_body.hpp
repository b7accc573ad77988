// What the dynamics tests share: a body cut by one plane (one tet or a box mesh), its full
// [u; a] stiffness and consistent mass, and the DOFs of a field given side by side.
#pragma once

#include "support/cut_body.hpp"
#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/dynamics/linear_dynamic_system.hpp"
#include "kerf/dynamics/newmark.hpp"
#include "kerf/dynamics/nonlinear_newmark.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/quadrature/gauss_piece_rules.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"
#include "kerf/xfem/surface_enrichment.hpp"

#include <Eigen/Geometry>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

namespace cut_body {

using support::subtets;

// The plane n . x = offset as a square of two triangles, 2 half_size wide, centred on the
// plane's point nearest `centre`.
inline kerf::TriangleSurface plane_surface(const Eigen::Vector3d& normal, double offset, const Eigen::Vector3d& centre,
                                           double half_size) {
  const Eigen::Vector3d n = normal.normalized();
  const Eigen::Vector3d c = centre + (offset / normal.norm() - n.dot(centre)) * n;
  const Eigen::Vector3d e1 = n.unitOrthogonal() * half_size, e2 = n.cross(e1.normalized()) * half_size;
  kerf::TriangleSurface s;
  s.vertices.resize(4, 3);
  s.vertices.row(0) = (c - e1 - e2).transpose();
  s.vertices.row(1) = (c + e1 - e2).transpose();
  s.vertices.row(2) = (c + e1 + e2).transpose();
  s.vertices.row(3) = (c - e1 + e2).transpose();
  s.triangles.resize(2, 3);
  s.triangles << 0, 1, 2, 0, 2, 3;
  return s;
}

// The shared cut body (support/cut_body.hpp) with what the dynamics tests ask of it.
struct CutBody : support::CutBody {
  CutBody(kerf::TetMesh m, std::vector<kerf::TriangleSurface> surfaces, const kerf::LinearMaterial& material)
      : support::CutBody(std::move(m), std::move(surfaces), material) {}

  // A point inside piece p of tet t: its centroid (by a degree-1 rule), or the tet's.
  Eigen::Vector3d piece_centroid(Eigen::Index t, int p) const {
    if (!model.integrated_by_pieces(t)) return kerf::tet_corners(mesh, t).colwise().mean().transpose();
    const kerf::TetPieces& tp = pieces.tets[static_cast<std::size_t>(pieces.entry[static_cast<std::size_t>(t)])];
    const kerf::PieceQuadratureRule r = kerf::subtet_rule(tp, p, 1);
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    double w = 0.0;
    for (std::size_t q = 0; q < r.points.size(); ++q) x += r.weights[q] * r.points[q], w += r.weights[q];
    return x / w;
  }
  int num_integrated_pieces(Eigen::Index t) const { return model.num_integrated_pieces(t); }

  // The DOFs [u; a] of the field that is f(x, s) on side s of the cut (s = side of the piece's
  // centroid): u_i the value on node i's home piece, a_k the value where k is active minus u_i.
  Eigen::VectorXd piecewise_field(const std::function<int(const Eigen::Vector3d&)>& side,
                                  const std::function<Eigen::Vector3d(const Eigen::Vector3d&, int)>& f) const {
    Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * model.num_dof_nodes());
    for (int pass = 0; pass < 2; ++pass)
      for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
        for (int p = 0; p < num_integrated_pieces(t); ++p) {
          const int s = side(piece_centroid(t, p));
          for (int a = 0; a < mesh.nodes_per_tet(); ++a) {
            const int i = mesh.tets(t, a);
            const int k = model.phantom_node(t, p, a);
            const Eigen::Vector3d x = mesh.nodes.row(i).transpose();
            if (pass == 0 && k == i) u.segment<3>(3 * i) = f(x, s);
            if (pass == 1 && k != i) u.segment<3>(3 * k) = f(x, s) - u.segment<3>(3 * i);
          }
        }
    return u;
  }

  // The full linear stiffness K^X on all 3 num_dof_nodes() DOFs.
  Eigen::SparseMatrix<double> stiffness() const { return support::full_linear_stiffness(model); }
};

// Undamped Newmark (the average acceleration rule) from rest under the constant load f on all
// DOFs: the state after `steps` steps of dt (the free-fall tests).
inline kerf::DynamicState newmark_from_rest(Eigen::SparseMatrix<double> M, Eigen::SparseMatrix<double> K, kerf::DofMap dofs,
                                            const Eigen::VectorXd& f, double dt, int steps) {
  kerf::LinearDynamicSystem system;
  system.M = std::move(M);
  system.K = std::move(K);
  system.C = Eigen::SparseMatrix<double>(system.M.rows(), system.M.cols());
  system.dofs = std::move(dofs);
  system.load = [f](double) { return f; };
  kerf::NewmarkIntegrator newmark(system, dt);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(f.size());
  kerf::DynamicState state = kerf::consistent_initial_state(newmark.reduced(), zero, zero, 0.0, {});
  for (int n = 0; n < steps; ++n) newmark.step(state);
  return state;
}

// The unit tet (0,0,0), (1,0,0), (0,1,0), (0,0,1).
inline kerf::TetMesh unit_tet() {
  kerf::TetMesh mesh;
  mesh.nodes.resize(4, 3);
  mesh.nodes << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  mesh.tets.resize(1, 4);
  mesh.tets << 0, 1, 2, 3;
  return mesh;
}

// The corotated force of `model` and, when asked, its tangent (on all DOFs, every one free), for
// kerf::NonlinearDynamicSystem: the tangent is assembled into `assembler`, which keeps the matrix
// the integrator reads until the next call (InternalForce).
inline kerf::InternalForce corotated_force(const kerf::CutXfemModel& model, std::shared_ptr<kerf::SparseAssembler> assembler) {
  return [&model, assembler](const Eigen::VectorXd& u, kerf::CorotationalTangent tangent, Eigen::VectorXd& f_int,
                             const Eigen::SparseMatrix<double>** K) {
    Eigen::VectorXd unused = Eigen::VectorXd::Zero(u.size());
    if (K) assembler->set_zero();
    model.assemble(u, kerf::RotationMethod::automatic, tangent, f_int, K ? assembler.get() : nullptr, K ? &unused : nullptr);
    if (K) *K = &assembler->matrix();
  };
}

} // namespace cut_body
