// What the tests of the nonlinear Newmark step share: the nodes a clamp at z = 0 holds, and
// the internal force of a linear body for kerf::NonlinearDynamicSystem.
#pragma once

#include "kerf/dynamics/nonlinear_newmark.hpp"
#include "kerf/mesh/tet_mesh.hpp"

#include <Eigen/SparseCore>
#include <vector>

namespace clamped_body {

// The nodes of `mesh` on the plane z = 0.
inline std::vector<int> nodes_at_z0(const kerf::TetMesh& mesh) {
  std::vector<int> nodes;
  for (Eigen::Index i = 0; i < mesh.num_nodes(); ++i)
    if (mesh.nodes(i, 2) == 0.0) nodes.push_back(static_cast<int>(i));
  return nodes;
}

// f_int = K u with tangent K, whatever tangent is asked for (K kept by reference).
inline kerf::InternalForce linear_force(const Eigen::SparseMatrix<double>& K) {
  return [&K](const Eigen::VectorXd& u, kerf::CorotationalTangent, Eigen::VectorXd& f_int, const Eigen::SparseMatrix<double>** Kt) {
    f_int = K * u;
    if (Kt) *Kt = &K;
  };
}

} // namespace clamped_body
