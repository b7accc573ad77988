#include "kerf/corotation/corotational_model.hpp"

#include "kerf/fem/positive_jacobian.hpp"
#include "kerf/fem/tet_quadrature.hpp"
#include "kerf/fem/tet_shape_functions.hpp"
#include "kerf/fem/tet_stiffness.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <type_traits>

namespace kerf {

namespace {

template <int n>
Eigen::Matrix<double, n, 3> element_rows(const NodeMatrix& nodes, const TetMatrix& tets, Eigen::Index t) {
  Eigen::Matrix<double, n, 3> X;
  for (int a = 0; a < n; ++a) X.row(a) = nodes.row(tets(t, a));
  return X;
}

} // namespace

CorotationalModel::CorotationalModel(const TetMesh& mesh, const LinearMaterial& material) : mesh_(mesh), material_(material) {
  if (mesh.order() == 1) {
    tet4_stiffness_.resize(static_cast<std::size_t>(mesh.num_tets()));
    tet4_gradients_.resize(static_cast<std::size_t>(mesh.num_tets()));
    tet4_volumes_.resize(static_cast<std::size_t>(mesh.num_tets()));
    for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
      const Eigen::Matrix<double, 4, 3> X = element_rows<4>(mesh.nodes, mesh.tets, t);
      double det_J = 0.0;
      tet4_gradients_[static_cast<std::size_t>(t)] = physical_shape_gradients<4>(X, tet4_shape_gradients(), det_J);
      require_positive_jacobian(det_J, "CorotationalModel", t);
      tet4_volumes_[static_cast<std::size_t>(t)] = det_J / 6.0;
      tet4_stiffness_[static_cast<std::size_t>(t)] = tet4_stiffness(X, material);
      const Eigen::Matrix<double, 3, 4> X_columns = X.transpose(); // node-major: x0, y0, z0, x1, ...
      position_force_norm_ +=
          (tet4_stiffness_[static_cast<std::size_t>(t)] * Eigen::Map<const Eigen::Matrix<double, 12, 1>>(X_columns.data())).squaredNorm();
    }
  } else {
    const TetQuadratureRule rule = tet_quadrature_rule(2);
    for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
      const Eigen::Matrix<double, 10, 3> X = element_rows<10>(mesh.nodes, mesh.tets, t);
      for (std::size_t q = 0; q < rule.points.size(); ++q) {
        double det_J = 0.0;
        tet10_gradients_.push_back(physical_shape_gradients<10>(X, tet10_shape_gradients(rule.points[q]), det_J));
        require_positive_jacobian(det_J, "CorotationalModel", t);
        tet10_weights_.push_back(rule.weights[q] * det_J);
      }
      const Eigen::Matrix<double, 30, 30> K = tet10_stiffness(X, material);
      const Eigen::Matrix<double, 3, 10> X_columns = X.transpose();
      position_force_norm_ += (K * Eigen::Map<const Eigen::Matrix<double, 30, 1>>(X_columns.data())).squaredNorm();
    }
  }
  position_force_norm_ = std::sqrt(position_force_norm_);
}

CorotationStatistics CorotationalModel::assemble(const Eigen::VectorXd& u, RotationMethod rotation, CorotationalTangent tangent,
                                                 Eigen::VectorXd& f_int, SparseAssembler* assembler, Eigen::VectorXd* rhs_free) const {
  CorotationStatistics stats;
  f_int = Eigen::VectorXd::Zero(3 * mesh_.num_nodes());
  const double mu = material_.mu(), lambda = material_.lambda();
  for (Eigen::Index t = 0; t < mesh_.num_tets(); ++t) {
    if (mesh_.order() == 1) {
      const auto e = static_cast<std::size_t>(t);
      const Eigen::Matrix<double, 4, 3> X = element_rows<4>(mesh_.nodes, mesh_.tets, t);
      const Eigen::Matrix<double, 4, 3> u_e = tet_node_displacements<4>(mesh_, u, t);
      Eigen::Matrix<double, 12, 1> f = Eigen::Matrix<double, 12, 1>::Zero();
      Eigen::Matrix<double, 12, 12> Kt = Eigen::Matrix<double, 12, 12>::Zero();
      add_corotated_point<4>(tet4_stiffness_[e], tet4_gradients_[e], X, u_e, tet4_volumes_[e], mu, lambda, rotation, tangent, f,
                             assembler ? &Kt : nullptr, &stats);
      for (int a = 0; a < 4; ++a) f_int.segment<3>(3 * mesh_.tets(t, a)) += f.segment<3>(3 * a);
      if (assembler) assembler->add_element<12>(t, Kt, *rhs_free);
    } else {
      const Eigen::Matrix<double, 10, 3> X = element_rows<10>(mesh_.nodes, mesh_.tets, t);
      const Eigen::Matrix<double, 10, 3> u_e = tet_node_displacements<10>(mesh_, u, t);
      Eigen::Matrix<double, 30, 1> f = Eigen::Matrix<double, 30, 1>::Zero();
      Eigen::Matrix<double, 30, 30> Kt = Eigen::Matrix<double, 30, 30>::Zero();
      for (int q = 0; q < 4; ++q) {
        const auto p = static_cast<std::size_t>(4 * t + q);
        // This point's share of the element stiffness (eq. 30 times its weight).
        Eigen::Matrix<double, 30, 30> K_q = Eigen::Matrix<double, 30, 30>::Zero();
        add_stiffness_integrand<10>(tet10_gradients_[p], tet10_weights_[p], mu, lambda, K_q);
        add_corotated_point<10>(K_q, tet10_gradients_[p], X, u_e, tet10_weights_[p], mu, lambda, rotation, tangent, f,
                                assembler ? &Kt : nullptr, &stats);
      }
      for (int a = 0; a < 10; ++a) f_int.segment<3>(3 * mesh_.tets(t, a)) += f.segment<3>(3 * a);
      if (assembler) assembler->add_element<30>(t, Kt, *rhs_free);
    }
  }
  return stats;
}

double CorotationalModel::energy(const Eigen::VectorXd& u, RotationMethod rotation) const {
  // With f = K_R d the element force in the unrotated frame, the energy is 1/2 d^T K d.
  double energy = 0.0;
  const double mu = material_.mu(), lambda = material_.lambda();
  const auto add = [&](const auto& K, const auto& G, const auto& X, const auto& u_e) {
    constexpr int n = std::decay_t<decltype(X)>::RowsAtCompileTime;
    const Eigen::Matrix3d F = Eigen::Matrix3d::Identity() + u_e.transpose() * G;
    const auto d = corotated_displacement<n>(element_rotation(F, rotation).R, X, u_e);
    energy += 0.5 * d.dot(K * d);
  };
  for (Eigen::Index t = 0; t < mesh_.num_tets(); ++t) {
    if (mesh_.order() == 1) {
      const auto e = static_cast<std::size_t>(t);
      add(tet4_stiffness_[e], tet4_gradients_[e], element_rows<4>(mesh_.nodes, mesh_.tets, t), tet_node_displacements<4>(mesh_, u, t));
    } else {
      for (int q = 0; q < 4; ++q) {
        const auto p = static_cast<std::size_t>(4 * t + q);
        Eigen::Matrix<double, 30, 30> K_q = Eigen::Matrix<double, 30, 30>::Zero();
        add_stiffness_integrand<10>(tet10_gradients_[p], tet10_weights_[p], mu, lambda, K_q);
        add(K_q, tet10_gradients_[p], element_rows<10>(mesh_.nodes, mesh_.tets, t), tet_node_displacements<10>(mesh_, u, t));
      }
    }
  }
  return energy;
}

} // namespace kerf
