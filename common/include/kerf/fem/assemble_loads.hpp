/// @file assemble_loads.hpp
/// @brief Global load vectors: gravity over the volume and a total force spread over boundary faces.
#pragma once

#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/mesh/tet_mesh.hpp"

#include <Eigen/Core>
#include <vector>

namespace kerf {

/// Consistent body-force vector (3#V) of the gravity acceleration g: f_a = rho g int N_a dV
/// summed over the tets (the volume-force term of eq. 22). Each tet's corner volume is its
/// weight, so it must be positive: std::invalid_argument names the first tet that is inverted
/// or flat (see positive_jacobian.hpp).
Eigen::VectorXd assemble_gravity(const TetMesh& mesh, double density, const Eigen::Vector3d& gravity);

/// The boundary faces all of whose nodes are in a region, and their total area A (m^2): where a
/// uniform traction total_force / A acts.
struct RegionFaces {
  std::vector<Eigen::Index> faces; ///< rows of BoundaryFaces::faces
  double area = 0.0;               ///< their total area A (m^2)
};
RegionFaces faces_in_region(const TetMesh& mesh, const BoundaryFaces& boundary, const std::vector<char>& in_region);

/// The traction t = total_force / A spread uniformly over the boundary faces all of whose
/// nodes are in `in_region` (A is their total area): f_a = t int_F N_a dA (eq. 22's surface
/// term). Adds to `f` (3#V) and returns A; A == 0 means no face was found, and nothing is added.
double add_uniform_traction(const TetMesh& mesh, const BoundaryFaces& boundary, const std::vector<char>& in_region,
                            const Eigen::Vector3d& total_force, Eigen::VectorXd& f);

} // namespace kerf
