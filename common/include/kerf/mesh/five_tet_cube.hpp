/// @file five_tet_cube.hpp
/// @brief A box split into five tetrahedra: one central tet and four corner tets (Koschier's cube of Figs. 10 and 14).
#pragma once

#include "kerf/mesh/tet_mesh.hpp"

#include <Eigen/Core>

namespace kerf {

/// The box [min, max] as five Tet4, the split Koschier et al. use for their cube experiments
/// (Koschier et al., section 7, Figs. 10 and 14; which of the two five-tet splits is not stated,
/// so we take the one below).
///
/// Corner c of the box has the offsets (c & 1, (c >> 1) & 1, (c >> 2) & 1) from min, in units
/// of the box's edges; node c is corner c (8 nodes). The corners of even parity, 0, 3, 5 and 6,
/// span the central tet (a third of the box); each odd corner, 1, 2, 4 and 7, cuts off a corner
/// tet with its three neighbours (a sixth each). Every tet is listed with positive orientation.
///
/// @param min lower corner of the box (m)
/// @param max upper corner of the box (m), componentwise larger than min
/// @return a Tet4 mesh with 8 nodes and 5 tets, the central tet first
TetMesh make_five_tet_cube(const Eigen::Vector3d& min, const Eigen::Vector3d& max);

} // namespace kerf
