/// @file tet_loads.hpp
/// @brief Consistent nodal loads: a body force over a tet and a uniform traction over a boundary face.
#pragma once

#include <Eigen/Core>

namespace kerf {

/// int_T N_a dV for the n nodes of a straight-edged tet of volume V (n = 4 or 10).
/// Tet4: V/4 at every corner. Tet10: -V/20 at the corners and V/5 at the mid-edge nodes; the
/// negative corner share is what the quadratic shape functions integrate to, not an error.
Eigen::VectorXd tet_shape_integrals(int nodes_per_tet, double volume);

/// int_F N_a dA for the nodes of a flat boundary face of area A (3 or 6 nodes).
/// Three-node face: A/3 each. Six-node face: 0 at the corners and A/3 at the mid-edge nodes.
/// A uniform traction t gives the nodal forces t times these integrals (eq. 22's surface term).
Eigen::VectorXd face_shape_integrals(int nodes_per_face, double area);

} // namespace kerf
