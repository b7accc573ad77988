#include "kerf/xfem/xfem_mass.hpp"

#include <Eigen/Dense>

#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/fem/tet_mass.hpp"
#include "kerf/fem/tet_quadrature.hpp"
#include "kerf/xfem/xfem_element.hpp"

#include <cmath>

namespace kerf {

namespace {

/// rho int_piece Phi_i Phi_j dV over the sub-tets of one side of a cut tet (degree-2 rule).
Eigen::Matrix4d piece_mass(const XfemModel& model, Eigen::Index t, int side, double density) {
  const Enrichment& e = model.enrichment();
  const auto k = static_cast<std::size_t>(t);
  const TetQuadratureRule rule = tet_quadrature_rule(2);
  Eigen::Matrix4d M = Eigen::Matrix4d::Zero();
  for (const Eigen::Matrix<double, 4, 3>& sub : side > 0 ? e.pieces[k].above : e.pieces[k].below) {
    Eigen::Matrix3d J;
    for (int c = 0; c < 3; ++c) J.col(c) = (sub.row(c + 1) - sub.row(0)).transpose();
    const double det_J = std::abs(J.determinant());
    for (std::size_t q = 0; q < rule.points.size(); ++q) {
      const Eigen::Vector3d x = sub.row(0).transpose() + J * rule.points[q];
      const Eigen::Vector4d phi = model.shape_values(t, x);
      M += density * rule.weights[q] * det_J * phi * phi.transpose();
    }
  }
  return M;
}

} // namespace

Eigen::SparseMatrix<double> assemble_xfem_mass(const XfemModel& model, double density) {
  const TetMesh& mesh = model.mesh();
  const Enrichment& e = model.enrichment();
  const DofMap all_free = make_dof_map(model.num_dof_nodes(), {});
  SparseAssembler assembler(model.assembly_slots(), all_free);
  Eigen::VectorXd unused = Eigen::VectorXd::Zero(all_free.num_free);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const auto k = static_cast<std::size_t>(t);
    const Eigen::Matrix4d M_whole = tet4_mass(tet_corners(mesh, t), density);
    if (!model.has_enriched_corner(t)) {
      // A tet with no enriched corner is chapter 1's (also one beyond the front: it has no sides).
      Eigen::Matrix<double, 12, 12> M_plain = Eigen::Matrix<double, 12, 12>::Zero();
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) M_plain.block<3, 3>(3 * a, 3 * b) = M_whole(a, b) * Eigen::Matrix3d::Identity();
      assembler.add_element<12>(t, M_plain, unused);
      continue;
    }
    Eigen::Matrix<double, 24, 24> M = Eigen::Matrix<double, 24, 24>::Zero();
    for (const int side : {+1, -1}) {
      Eigen::Matrix4d M_side = Eigen::Matrix4d::Zero();
      if (e.tet_side[k] == TetSide::cut)
        M_side = piece_mass(model, t, side, density);
      else if (e.piece_fraction(t, side) > 0.0)
        M_side = M_whole;
      const Eigen::Matrix<double, 12, 24> T = side_operator(model.psi(t, side));
      Eigen::Matrix<double, 12, 12> M_side_3 = Eigen::Matrix<double, 12, 12>::Zero();
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) M_side_3.block<3, 3>(3 * a, 3 * b) = M_side(a, b) * Eigen::Matrix3d::Identity();
      M += T.transpose() * M_side_3 * T;
    }
    const int m = 3 * assembler.slots_used(t);
    assembler.add_element_matrix(t, M.topLeftCorner(m, m), unused);
  }
  return assembler.matrix();
}

Eigen::VectorXd xfem_lumped_mass(const XfemModel& model, double density) {
  const TetMesh& mesh = model.mesh();
  const Enrichment& e = model.enrichment();
  Eigen::VectorXd diagonal = Eigen::VectorXd::Zero(3 * model.num_dof_nodes());
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const double corner_mass = density * model.element_volume(t) / 4.0; // eq. 81: m / n
    for (int a = 0; a < 4; ++a) diagonal.segment<3>(3 * mesh.tets(t, a)).array() += corner_mass;
    if (!model.has_enriched_corner(t)) continue;
    const double fraction_above = e.piece_fraction(t, +1), fraction_below = e.piece_fraction(t, -1);
    const Eigen::Vector4d psi_above = model.psi(t, +1), psi_below = model.psi(t, -1);
    for (int a = 0; a < 4; ++a)
      if (const int a_node = model.assembly_slots()(t, 4 + a); a_node >= 0) // eq. 82
        diagonal.segment<3>(3 * a_node).array() +=
            (fraction_above * psi_above[a] * psi_above[a] + fraction_below * psi_below[a] * psi_below[a]) * corner_mass;
  }
  return diagonal;
}

} // namespace kerf
