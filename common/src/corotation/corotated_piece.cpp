/// @file corotated_piece.cpp
/// @brief One rotation per piece: f = R K d and its tangent on general slots (corotated_piece.hpp).
#include "kerf/corotation/corotated_piece.hpp"

#include <Eigen/Dense>
#include <cmath>

namespace kerf {

Eigen::Matrix3d piece_mean_deformation_gradient(const Eigen::MatrixX3d& mean_gradient, int num_node_slots, const Eigen::MatrixX3d& X,
                                                const Eigen::MatrixX3d& q) {
  Eigen::MatrixX3d x = q;
  x.topRows(num_node_slots) += X.topRows(num_node_slots);
  return x.transpose() * mean_gradient;
}

Eigen::VectorXd corotated_piece_displacement(const Eigen::Matrix3d& R, int num_node_slots, const Eigen::MatrixX3d& X,
                                             const Eigen::MatrixX3d& q) {
  const Eigen::Index S = q.rows();
  Eigen::VectorXd d(3 * S);
  for (Eigen::Index s = 0; s < S; ++s) {
    if (s < num_node_slots) {
      const Eigen::Vector3d X_s0 = (X.row(s) - X.row(0)).transpose();
      d.segment<3>(3 * s) = R.transpose() * (X_s0 + (q.row(s) - q.row(0)).transpose()) - X_s0;
    } else {
      d.segment<3>(3 * s) = R.transpose() * q.row(s).transpose();
    }
  }
  return d;
}

PolarDecomposition add_corotated_piece(const Eigen::MatrixXd& K, const Eigen::MatrixX3d& mean_gradient, int num_node_slots,
                                       const Eigen::MatrixX3d& X, const Eigen::MatrixX3d& q, double volume,
                                       RotationMethod method, CorotationalTangent tangent, Eigen::VectorXd& f,
                                       Eigen::MatrixXd* Kt, CorotationStatistics* statistics) {
  const Eigen::Index S = q.rows();
  const Eigen::Matrix3d F = piece_mean_deformation_gradient(mean_gradient, num_node_slots, X, q);
  const PolarDecomposition polar = element_rotation(F, method);
  if (statistics) statistics->record(polar, F, volume);
  const Eigen::Matrix3d& R = polar.R;
  const Eigen::VectorXd d = corotated_piece_displacement(R, num_node_slots, X, q);
  const Eigen::VectorXd Kd = K * d;
  for (Eigen::Index s = 0; s < S; ++s) f.segment<3>(3 * s) += R * Kd.segment<3>(3 * s);
  if (!Kt) return polar;

  for (Eigen::Index s = 0; s < S; ++s)
    for (Eigen::Index t = 0; t < S; ++t) Kt->block<3, 3>(3 * s, 3 * t) += R * K.block<3, 3>(3 * s, 3 * t) * R.transpose();
  if (tangent == CorotationalTangent::warped) return polar;

  // dR/dx, guarded as in corotated_element.hpp where tr(S) I - S is singular.
  const Eigen::Matrix3d& Sym = polar.S;
  const Eigen::Matrix3d M = Sym.trace() * Eigen::Matrix3d::Identity() - Sym;
  const double size = M.norm();
  if (!(std::abs(M.determinant()) > 1e-6 * size * size * size)) {
    if (statistics) ++statistics->dropped_rotation_terms;
    return polar;
  }
  const Eigen::Matrix3d M_inverse = M.inverse();
  // The rotated positions R^T x_u (node slots relative to node 0, as in d): d_u + (X_u - X_0),
  // and d_u itself on the enriched slots.
  Eigen::MatrixX3d rotated = d.reshaped(3, S).transpose();
  for (Eigen::Index u = 1; u < num_node_slots; ++u) rotated.row(u) += X.row(u) - X.row(0);
  Eigen::VectorXd c(3 * S), column(3 * S);
  for (Eigen::Index s = 0; s < S; ++s)
    for (int e = 0; e < 3; ++e) {
      const Eigen::Vector3d w = M_inverse * mean_gradient.row(s).transpose().cross(R.row(e).transpose());
      for (Eigen::Index u = 0; u < S; ++u) c.segment<3>(3 * u) = rotated.row(u).transpose().cross(w);
      column = K * c;
      for (Eigen::Index t = 0; t < S; ++t)
        Kt->col(3 * s + e).segment<3>(3 * t) += R * (w.cross(Kd.segment<3>(3 * t)) + column.segment<3>(3 * t));
    }
  return polar;
}

} // namespace kerf
