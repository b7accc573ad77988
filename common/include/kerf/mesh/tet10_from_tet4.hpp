/// @file tet10_from_tet4.hpp
/// @brief Promote a Tet4 mesh to Tet10 by adding one node at the midpoint of every edge.
#pragma once

#include "kerf/mesh/tet_mesh.hpp"

namespace kerf {

/// Adds a node at the midpoint of every edge of a Tet4 mesh, shared by all tets around
/// the edge, so the Tet10 mesh is conforming. The edges stay straight, so the geometry map of
/// each Tet10 is still affine: its Jacobian is constant, which the quadrature rules rely on.
///
/// @param tet4 a Tet4 mesh
/// @return the Tet10 mesh: the Tet4 nodes first (same indices), then one node per edge
TetMesh tet10_from_tet4(const TetMesh& tet4);

} // namespace kerf
