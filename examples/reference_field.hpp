// What the chapter studies measure their errors with: a reference solution sampled at the
// degree-2 points of its own mesh (4 per tet, all interior, so none on a cut the mesh follows),
// with the weights w |J| that make a sum over the points an integral over the body.
#pragma once

#include "kerf/fem/evaluate_displacement.hpp"
#include "kerf/fem/tet_quadrature.hpp"
#include "kerf/mesh/tet_mesh.hpp"

#include <Eigen/Dense>
#include <cmath>

namespace study {

/// The reference displacement at its mesh's degree-2 points, each evaluated in its own tet: on
/// its own side of any cut the mesh is opened along.
struct ReferenceField {
  Eigen::MatrixXd points;  ///< #P by 3
  Eigen::VectorXd weights; ///< #P
  Eigen::MatrixXd values;  ///< #P by 3
  double norm = 0.0;       ///< ||u_ref||_L2
};

inline ReferenceField sample_reference(const kerf::TetMesh& mesh, const Eigen::VectorXd& u) {
  const kerf::TetQuadratureRule rule = kerf::tet_quadrature_rule(2);
  const Eigen::Index q = static_cast<Eigen::Index>(rule.points.size());
  ReferenceField r;
  r.points.resize(mesh.num_tets() * q, 3);
  r.weights.resize(mesh.num_tets() * q);
  r.values.resize(mesh.num_tets() * q, 3);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const Eigen::Vector3d X0 = mesh.nodes.row(mesh.tets(t, 0)).transpose();
    Eigen::Matrix3d J;
    for (int a = 0; a < 3; ++a) J.col(a) = mesh.nodes.row(mesh.tets(t, a + 1)).transpose() - X0;
    const double det = std::abs(J.determinant());
    for (Eigen::Index k = 0; k < q; ++k) {
      const Eigen::Index p = t * q + k;
      const Eigen::Vector3d& xi = rule.points[static_cast<std::size_t>(k)];
      r.points.row(p) = (X0 + J * xi).transpose();
      r.weights[p] = rule.weights[static_cast<std::size_t>(k)] * det;
      r.values.row(p) = kerf::evaluate_displacement(mesh, u, t, xi).transpose();
    }
  }
  r.norm = std::sqrt((r.weights.array() * r.values.rowwise().squaredNorm().array()).sum());
  return r;
}

/// ||u_h - u_ref||_L2 / ||u_ref||_L2 from u_h at the reference's points.
inline double relative_l2(const ReferenceField& ref, const Eigen::MatrixXd& values) {
  return std::sqrt((ref.weights.array() * (values - ref.values).rowwise().squaredNorm().array()).sum()) / ref.norm;
}

} // namespace study
