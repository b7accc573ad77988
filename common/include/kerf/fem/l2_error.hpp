/// @file l2_error.hpp
/// @brief The L2 norm of the error between the discrete field and a given one (Schoch et al., eq. 83).
#pragma once

#include "kerf/mesh/tet_mesh.hpp"

#include <Eigen/Core>
#include <functional>

namespace kerf {

/// A vector field of position, such as an exact solution or a body force density.
using VectorField = std::function<Eigen::Vector3d(const Eigen::Vector3d&)>;

/// || u_h - u ||_{L2(Omega)} = sqrt( int |u_h - u|^2 dV ), eq. (83), with the tet rule of the
/// given degree on every element. For a smooth u, degree 2 p + 2 makes the quadrature error
/// negligible next to the discretisation error of order p + 1.
/// @param u_h   nodal displacements (3#V, node-major)
/// @param exact the reference field u(x)
double l2_error(const TetMesh& mesh, const Eigen::VectorXd& u_h, const VectorField& exact, int degree);

/// || u ||_{L2(Omega)} of a given field, for relative errors.
double l2_norm(const TetMesh& mesh, const VectorField& field, int degree);

/// Consistent nodal loads of a body force density b(x) (N/m^3): f_a = int b Phi_a dV, with the
/// tet rule of the given degree.
Eigen::VectorXd assemble_body_force(const TetMesh& mesh, const VectorField& body_force, int degree);

} // namespace kerf
