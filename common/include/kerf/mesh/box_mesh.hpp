/// @file box_mesh.hpp
/// @brief A conforming Tet4 mesh of an axis-aligned box: each hex cell split into six tetrahedra.
#pragma once

#include "kerf/mesh/tet_mesh.hpp"

#include <Eigen/Core>

namespace kerf {

/// Meshes the box [min, max] with cells[0] x cells[1] x cells[2] hexahedral cells, each split
/// into six Tet4 around its main diagonal (Kuhn's, or Freudenthal's, subdivision).
///
/// Every cell is split around the diagonal from its (0,0,0) corner to its (1,1,1) corner, so
/// two neighbouring cells cut their shared face along the same diagonal and the mesh is
/// conforming without any alternation between cells.
///
/// @param min   lower corner of the box (m)
/// @param max   upper corner of the box (m), componentwise larger than min
/// @param cells number of cells along x, y, z, each at least 1
/// @return a Tet4 mesh with (nx+1)(ny+1)(nz+1) nodes, numbered x fastest, and 6 nx ny nz tets
TetMesh make_box_mesh(const Eigen::Vector3d& min, const Eigen::Vector3d& max, const Eigen::Vector3i& cells);

} // namespace kerf
