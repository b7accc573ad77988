#include "kerf/xfem/xfem_model.hpp"

#include <Eigen/Dense>

#include "kerf/fem/positive_jacobian.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/fem/tet_shape_functions.hpp"
#include "kerf/fem/tet_stiffness.hpp"
#include "kerf/xfem/xfem_element.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace kerf {

namespace {

/// The element's DOFs [u_1..u_4, a_1..a_4] gathered from the global vector (zeros in empty slots).
Eigen::Matrix<double, 24, 1> gather(const TetMatrix& slots, const Eigen::VectorXd& u, Eigen::Index t) {
  Eigen::Matrix<double, 24, 1> ue = Eigen::Matrix<double, 24, 1>::Zero();
  for (int s = 0; s < 8; ++s)
    if (slots(t, s) >= 0) ue.segment<3>(3 * s) = u.segment<3>(3 * slots(t, s));
  return ue;
}

/// A side's 12 corner displacements (node-major) as 4 rows, the layout add_corotated_point takes.
Eigen::Matrix<double, 4, 3> corner_rows(const Eigen::Matrix<double, 12, 1>& u_side) {
  return Eigen::Map<const Eigen::Matrix<double, 3, 4>>(u_side.data()).transpose();
}

void scatter_add(const TetMatrix& slots, Eigen::Index t, const Eigen::Matrix<double, 24, 1>& fe, Eigen::VectorXd& f) {
  for (int s = 0; s < 8; ++s)
    if (slots(t, s) >= 0) f.segment<3>(3 * slots(t, s)) += fe.segment<3>(3 * s);
}

} // namespace

XfemModel::XfemModel(const TetMesh& mesh, const LinearMaterial& material, const Enrichment& enrichment)
    : mesh_(mesh), material_(material), enrichment_(enrichment) {
  if (mesh.order() != 1) throw std::invalid_argument("XfemModel: chapter 3's XFEM is for Tet4 meshes");
  if (enrichment.enriched_index.size() != static_cast<std::size_t>(mesh.num_nodes()))
    throw std::invalid_argument("XfemModel: the enrichment was made for another mesh");
  const auto num_tets = static_cast<std::size_t>(mesh.num_tets());
  slots_.setConstant(mesh.num_tets(), 8, -1);
  slots_used_.assign(num_tets, 4);
  stiffness_.resize(num_tets);
  gradients_.resize(num_tets);
  volumes_.resize(num_tets);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const auto k = static_cast<std::size_t>(t);
    for (int a = 0; a < 4; ++a) {
      const int v = mesh.tets(t, a);
      slots_(t, a) = v;
      const int enriched = enrichment.enriched_index[static_cast<std::size_t>(v)];
      if (enriched >= 0) {
        slots_(t, 4 + a) = static_cast<int>(mesh.num_nodes()) + enriched;
        slots_used_[k] = 5 + a;
      }
    }
    if (slots_used_[k] > 4 && enrichment.tet_side[k] == TetSide::beyond)
      throw std::logic_error("XfemModel: tet " + std::to_string(t) + " lies beyond the cut's front but has an enriched corner");
    const Eigen::Matrix<double, 4, 3> X = tet_corners(mesh, t);
    double det_J = 0.0;
    gradients_[k] = physical_shape_gradients<4>(X, tet4_shape_gradients(), det_J);
    require_positive_jacobian(det_J, "XfemModel", t); // V = det J / 6 is an integration weight below
    volumes_[k] = det_J / 6.0;
    stiffness_[k] = tet4_stiffness(X, material);
    const Eigen::Matrix<double, 3, 4> X_columns = X.transpose();
    position_force_norm_ += (stiffness_[k] * Eigen::Map<const Eigen::Matrix<double, 12, 1>>(X_columns.data())).squaredNorm();
  }
  position_force_norm_ = std::sqrt(position_force_norm_);
}

Eigen::Vector4d XfemModel::psi(Eigen::Index t, int side) const {
  Eigen::Vector4d values = Eigen::Vector4d::Zero();
  for (int a = 0; a < 4; ++a)
    if (slots_(t, 4 + a) >= 0) values[a] = shifted_enrichment(side, enrichment_.node_sign[static_cast<std::size_t>(mesh_.tets(t, a))]);
  return values;
}

Eigen::Vector4d XfemModel::shape_values(Eigen::Index t, const Eigen::Vector3d& x) const {
  const Eigen::Vector3d offset = x - mesh_.nodes.row(mesh_.tets(t, 0)).transpose();
  Eigen::Vector4d phi = gradients_[static_cast<std::size_t>(t)] * offset;
  phi[0] += 1.0;
  return phi;
}

Eigen::Vector3d XfemModel::side_displacement(const Eigen::VectorXd& u, Eigen::Index t, int corner, int side) const {
  const int v = mesh_.tets(t, corner);
  Eigen::Vector3d value = u.segment<3>(3 * v);
  if (const int a_node = slots_(t, 4 + corner); a_node >= 0)
    value += shifted_enrichment(side, enrichment_.node_sign[static_cast<std::size_t>(v)]) * u.segment<3>(3 * a_node);
  return value;
}

void XfemModel::assemble_linear_stiffness(SparseAssembler& assembler, Eigen::VectorXd& rhs_free) const {
  for (Eigen::Index t = 0; t < mesh_.num_tets(); ++t) {
    const auto k = static_cast<std::size_t>(t);
    if (!has_enriched_corner(t)) {
      assembler.add_element<12>(t, stiffness_[k], rhs_free);
      continue;
    }
    const Eigen::Matrix<double, 24, 24> K_X =
        xfem_tet4_stiffness(stiffness_[k], enrichment_.piece_fraction(t, +1), psi(t, +1), psi(t, -1));
    const int m = 3 * slots_used_[k];
    assembler.add_element_matrix(t, K_X.topLeftCorner(m, m), rhs_free);
  }
}

CorotationStatistics XfemModel::assemble(const Eigen::VectorXd& u, RotationMethod rotation, CorotationalTangent tangent,
                                         Eigen::VectorXd& f_int, SparseAssembler* assembler, Eigen::VectorXd* rhs_free) const {
  CorotationStatistics stats;
  f_int = Eigen::VectorXd::Zero(3 * num_dof_nodes());
  const double mu = material_.mu(), lambda = material_.lambda();
  for (Eigen::Index t = 0; t < mesh_.num_tets(); ++t) {
    const auto k = static_cast<std::size_t>(t);
    const Eigen::Matrix<double, 4, 3> X = tet_corners(mesh_, t);
    if (!has_enriched_corner(t)) {
      // Most tets: chapter 2's corotated Tet4, with no enriched DOFs to carry along.
      const Eigen::Matrix<double, 4, 3> u_e = tet_node_displacements<4>(mesh_, u, t);
      Eigen::Matrix<double, 12, 1> f = Eigen::Matrix<double, 12, 1>::Zero();
      Eigen::Matrix<double, 12, 12> Kt = Eigen::Matrix<double, 12, 12>::Zero();
      add_corotated_point<4>(stiffness_[k], gradients_[k], X, u_e, volumes_[k], mu, lambda, rotation, tangent, f,
                             assembler ? &Kt : nullptr, &stats);
      for (int a = 0; a < 4; ++a) f_int.segment<3>(3 * mesh_.tets(t, a)) += f.segment<3>(3 * a);
      if (assembler) assembler->add_element<12>(t, Kt, *rhs_free);
      continue;
    }
    const Eigen::Matrix<double, 24, 1> ue = gather(slots_, u, t);
    Eigen::Matrix<double, 24, 1> fe = Eigen::Matrix<double, 24, 1>::Zero();
    Eigen::Matrix<double, 24, 24> Ke = Eigen::Matrix<double, 24, 24>::Zero();
    // Eq. 64: each side's piece is a corotated Tet4 of the side's corner positions, weighted by
    // its volume fraction (eq. 65/68 for the u rows, eq. 67/71 for the a rows via T^T).
    for (const int side : {+1, -1}) {
      const double fraction = enrichment_.piece_fraction(t, side);
      if (fraction <= 0.0) continue;
      const Eigen::Matrix<double, 12, 24> T = side_operator(psi(t, side));
      const Eigen::Matrix<double, 12, 1> u_side = T * ue;
      const Eigen::Matrix<double, 4, 3> u_rows = corner_rows(u_side);
      Eigen::Matrix<double, 12, 1> f_side = Eigen::Matrix<double, 12, 1>::Zero();
      Eigen::Matrix<double, 12, 12> K_side = Eigen::Matrix<double, 12, 12>::Zero();
      const Eigen::Matrix<double, 12, 12> K_fraction = fraction * stiffness_[k];
      add_corotated_point<4>(K_fraction, gradients_[k], X, u_rows, fraction * volumes_[k], mu, lambda, rotation, tangent, f_side,
                             assembler ? &K_side : nullptr, &stats);
      fe += T.transpose() * f_side;
      if (assembler) Ke += T.transpose() * K_side * T;
    }
    scatter_add(slots_, t, fe, f_int);
    if (assembler) {
      const int m = 3 * slots_used_[k];
      assembler->add_element_matrix(t, Ke.topLeftCorner(m, m), *rhs_free);
    }
  }
  return stats;
}

double XfemModel::energy(const Eigen::VectorXd& u, bool corotated, RotationMethod rotation) const {
  double energy = 0.0;
  for (Eigen::Index t = 0; t < mesh_.num_tets(); ++t) {
    const auto k = static_cast<std::size_t>(t);
    const Eigen::Matrix<double, 4, 3> X = tet_corners(mesh_, t);
    const Eigen::Matrix<double, 24, 1> ue = gather(slots_, u, t);
    // A tet without enriched corners is one piece, on whichever side (or beyond the front).
    for (const int side : {+1, -1}) {
      const double fraction = has_enriched_corner(t) ? enrichment_.piece_fraction(t, side) : (side > 0 ? 1.0 : 0.0);
      if (fraction <= 0.0) continue;
      const Eigen::Matrix<double, 12, 1> u_side = side_operator(psi(t, side)) * ue;
      const Eigen::Matrix<double, 4, 3> u_rows = corner_rows(u_side);
      Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
      if (corotated) R = element_rotation(Eigen::Matrix3d::Identity() + u_rows.transpose() * gradients_[k], rotation).R;
      const Eigen::Matrix<double, 12, 1> d = corotated_displacement<4>(R, X, u_rows);
      energy += 0.5 * fraction * d.dot(stiffness_[k] * d);
    }
  }
  return energy;
}

DofMap make_xfem_dof_map(const XfemModel& model, const std::vector<DirichletNodes>& conditions) {
  const std::vector<int>& enriched_index = model.enrichment().enriched_index;
  const auto num_nodes = static_cast<int>(model.mesh().num_nodes());
  DirichletNodes enriched_of_gripped; // a_i = 0 for the gripped enriched nodes
  for (const DirichletNodes& condition : conditions)
    for (int v : condition.nodes)
      if (v < num_nodes && enriched_index[static_cast<std::size_t>(v)] >= 0)
        enriched_of_gripped.nodes.push_back(num_nodes + enriched_index[static_cast<std::size_t>(v)]);
  // First, so that a caller who prescribes some a_i itself (a field that jumps across the cut,
  // as the patch tests do) has the last word: make_dof_map lets the last listing win.
  std::vector<DirichletNodes> with_enriched{enriched_of_gripped};
  with_enriched.insert(with_enriched.end(), conditions.begin(), conditions.end());
  return make_dof_map(model.num_dof_nodes(), with_enriched);
}

PhantomMesh xfem_phantom_mesh(const XfemModel& model) {
  const TetMesh& mesh = model.mesh();
  const Enrichment& enrichment = model.enrichment();
  const Eigen::Index N = mesh.num_nodes();
  PhantomMesh phantom;
  phantom.mesh.nodes.resize(N + enrichment.num_enriched(), 3);
  phantom.mesh.nodes.topRows(N) = mesh.nodes;
  for (Eigen::Index k = 0; k < enrichment.num_enriched(); ++k)
    phantom.mesh.nodes.row(N + k) = mesh.nodes.row(enrichment.enriched_nodes[static_cast<std::size_t>(k)]);

  std::vector<Eigen::Vector4i> tets;
  const auto add = [&](const Eigen::Vector4i& corners, double volume, const Eigen::Vector3d& point) {
    tets.push_back(corners);
    phantom.piece_volume.push_back(volume);
    phantom.piece_point.push_back(point);
  };
  const TetMatrix& slots = model.assembly_slots();
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const auto k = static_cast<std::size_t>(t);
    const Eigen::Matrix<double, 4, 3> X = tet_corners(mesh, t);
    if (!model.has_enriched_corner(t)) {
      add(mesh.tets.row(t).head<4>().transpose(), model.element_volume(t), X.colwise().mean().transpose());
      continue;
    }
    for (const int side : {+1, -1}) {
      const double fraction = enrichment.piece_fraction(t, side);
      if (!(fraction > 0.0)) continue;
      // A corner whose value on this side is u_i + Psi a_i with Psi != 0 is the phantom node.
      const Eigen::Vector4d psi = model.psi(t, side);
      Eigen::Vector4i corners;
      for (int a = 0; a < 4; ++a) corners[a] = psi[a] != 0.0 ? slots(t, 4 + a) : mesh.tets(t, a);
      Eigen::Vector3d point = X.colwise().mean().transpose();
      if (enrichment.tet_side[k] == TetSide::cut) {
        const auto& sub_tets = side > 0 ? enrichment.pieces[k].above : enrichment.pieces[k].below;
        double largest = -1.0;
        for (const auto& sub : sub_tets)
          if (const double v = std::abs(signed_tet_volume(sub)); v > largest) {
            largest = v;
            point = sub.colwise().mean().transpose();
          }
      }
      add(corners, fraction * model.element_volume(t), point);
    }
  }
  phantom.mesh.tets.resize(static_cast<Eigen::Index>(tets.size()), 4);
  for (std::size_t i = 0; i < tets.size(); ++i) phantom.mesh.tets.row(static_cast<Eigen::Index>(i)) = tets[i].transpose();
  return phantom;
}

std::vector<UnheldPiece> xfem_unheld_pieces(const XfemModel& model, const DofMap& dofs) {
  const PhantomMesh phantom = xfem_phantom_mesh(model);
  // A phantom node's value u_i + Psi a_i is held when both u_i and a_i are prescribed.
  DofMap phantom_dofs = dofs;
  const Eigen::Index N = model.mesh().num_nodes();
  for (Eigen::Index k = 0; k < model.enrichment().num_enriched(); ++k) {
    const Eigen::Index node = model.enrichment().enriched_nodes[static_cast<std::size_t>(k)];
    for (int p = 0; p < 3; ++p) {
      int& index = phantom_dofs.free_index[static_cast<std::size_t>(3 * (N + k) + p)];
      if (dofs.free_index[static_cast<std::size_t>(3 * node + p)] >= 0) index = 0; // only "free or not" matters here
    }
  }
  return unheld_pieces(phantom.mesh, phantom_dofs, phantom.piece_volume, phantom.piece_point);
}

std::string describe_unheld_pieces(const std::vector<UnheldPiece>& pieces) {
  if (pieces.empty()) return "every piece is held";
  const UnheldPiece& piece = pieces.front();
  char text[256];
  std::snprintf(text, sizeof text, "a piece of %.3g m^3 around (%.4g, %.4g, %.4g) m is held by no Dirichlet condition (%d rigid motions free)",
                piece.volume, piece.point.x(), piece.point.y(), piece.point.z(), piece.free_motions);
  std::string line = text;
  if (pieces.size() > 1) line += ", and " + std::to_string(pieces.size() - 1) + " more such pieces";
  return line;
}

Eigen::VectorXd solve_linear_xfem(const XfemModel& model, const DofMap& dofs, const Eigen::VectorXd& f_ext,
                                  const SolverSettings& solver_settings) {
  if (const std::vector<UnheldPiece> unheld = xfem_unheld_pieces(model, dofs); !unheld.empty())
    throw std::runtime_error("the XFEM stiffness is singular: " + describe_unheld_pieces(unheld));
  SparseAssembler assembler(model.assembly_slots(), dofs);
  Eigen::VectorXd rhs = dofs.restrict_to_free(f_ext);
  model.assemble_linear_stiffness(assembler, rhs);
  return dofs.expand(solve_once(assembler.matrix(), rhs, solver_settings));
}

} // namespace kerf
