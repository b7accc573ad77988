/// @file evaluate_displacement.hpp
/// @brief The discrete displacement field u(x) = sum_a N_a(x) u_a (eq. 14) at located points.
#pragma once

#include "kerf/mesh/point_locator.hpp"
#include "kerf/mesh/tet_mesh.hpp"

#include <Eigen/Core>

namespace kerf {

/// u at reference point xi of tet t, from the nodal displacements u (3#V, node-major).
Eigen::Vector3d evaluate_displacement(const TetMesh& mesh, const Eigen::VectorXd& u, Eigen::Index t, const Eigen::Vector3d& xi);

/// u at each row of `points` (#P by 3); rows outside the mesh get NaN and are counted.
/// @param[out] num_outside how many points were outside
Eigen::MatrixXd evaluate_displacement_at(const TetMesh& mesh, const Eigen::VectorXd& u, const Eigen::MatrixXd& points,
                                         Eigen::Index& num_outside);

} // namespace kerf
