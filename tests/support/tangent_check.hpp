// The tangent a QuasiStaticModel assembles, and the derivative of its forces by central
// differences to check it against (chapters 3 and 5's corotational tests).
#pragma once

#include "kerf/corotation/quasi_static_model.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/sparse_assembler.hpp"

#include <Eigen/Core>

namespace support {

// The tangent of `kind` at u on all 3 num_dof_nodes() DOFs, dense; f is set to f_int(u).
inline Eigen::MatrixXd assembled_tangent(const kerf::QuasiStaticModel& model, const Eigen::VectorXd& u, kerf::CorotationalTangent kind,
                                         Eigen::VectorXd& f) {
  const kerf::DofMap all_free = kerf::make_dof_map(model.num_dof_nodes(), {});
  kerf::SparseAssembler assembler(model.assembly_slots(), all_free);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(all_free.num_free);
  model.assemble(u, kerf::RotationMethod::automatic, kind, f, &assembler, &rhs);
  return Eigen::MatrixXd(assembler.matrix());
}

// d f_int / d u by central differences of step h (m), column by column.
inline Eigen::MatrixXd central_difference_tangent(const kerf::QuasiStaticModel& model, const Eigen::VectorXd& u, double h) {
  Eigen::MatrixXd K(u.size(), u.size());
  Eigen::VectorXd f_plus, f_minus;
  for (Eigen::Index j = 0; j < u.size(); ++j) {
    Eigen::VectorXd u_plus = u, u_minus = u;
    u_plus[j] += h;
    u_minus[j] -= h;
    model.assemble(u_plus, kerf::RotationMethod::automatic, kerf::CorotationalTangent::warped, f_plus, nullptr, nullptr);
    model.assemble(u_minus, kerf::RotationMethod::automatic, kerf::CorotationalTangent::warped, f_minus, nullptr, nullptr);
    K.col(j) = (f_plus - f_minus) / (2 * h);
  }
  return K;
}

// How far the consistent and the warped tangents at u are from the central-difference derivative
// of the forces (step h), each relative to the latter's Frobenius norm.
struct TangentErrors {
  double consistent = 0.0, warped = 0.0;
};
inline TangentErrors tangent_errors(const kerf::QuasiStaticModel& model, const Eigen::VectorXd& u, double h) {
  Eigen::VectorXd f;
  const Eigen::MatrixXd K = assembled_tangent(model, u, kerf::CorotationalTangent::consistent, f);
  const Eigen::MatrixXd K_warped = assembled_tangent(model, u, kerf::CorotationalTangent::warped, f);
  const Eigen::MatrixXd K_fd = central_difference_tangent(model, u, h);
  return {(K - K_fd).norm() / K_fd.norm(), (K_warped - K_fd).norm() / K_fd.norm()};
}

} // namespace support
