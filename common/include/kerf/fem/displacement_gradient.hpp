/// @file displacement_gradient.hpp
/// @brief The gradient of a Tet4 or Tet10 displacement field at a point of a tet: what a post-processor such as the interaction integral reads.
#pragma once

#include "kerf/mesh/tet_mesh.hpp"

#include <Eigen/Core>

namespace kerf {

/// H_ij = du_i/dx_j (3x3) of the field u (3#V, node-major) at the physical point x of tet t:
/// H = sum_a u_a (grad N_a)^T, with grad N_a = dN_a/dxi J^-1 at the reference point xi of x.
/// The reference point is found by the corners' affine map, so a Tet10 must have straight edges
/// (as every Tet10 Kerf makes has). x may lie outside the tet: the element's polynomial is
/// then extrapolated.
Eigen::Matrix3d displacement_gradient_at(const TetMesh& mesh, const Eigen::VectorXd& u, Eigen::Index t, const Eigen::Vector3d& x);

} // namespace kerf
