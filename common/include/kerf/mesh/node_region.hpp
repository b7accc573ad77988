/// @file node_region.hpp
/// @brief Select nodes by a box or by a list: the REGION of the scene file.
#pragma once

#include "kerf/mesh/tet_mesh.hpp"

#include <Eigen/Core>
#include <vector>

namespace kerf {

/// A set of nodes named in a scene: either the nodes inside an axis-aligned box, or a list.
struct NodeRegion {
  bool is_box = true;          ///< true: the box below; false: the node list
  Eigen::Vector3d box_min{0, 0, 0}, box_max{0, 0, 0};
  std::vector<int> node_list;  ///< 0-based node indices when is_box is false
};

/// The sorted indices of the nodes in `region`. A box includes its boundary with a tolerance
/// of 1e-9 times the mesh's bounding-box diagonal, so that a box written with the coordinates
/// of a face catches the nodes on it despite round-off in the mesher.
std::vector<int> nodes_in_region(const TetMesh& mesh, const NodeRegion& region);

/// The tolerance of a region's box: 1e-9 times the mesh's bounding-box diagonal (m). A point
/// read from a file (a prescribed displacement's row) matches a node within the same tolerance.
double region_tolerance(const TetMesh& mesh);

/// A boolean mask of length #V: true for the nodes of `region`.
std::vector<char> node_mask(const TetMesh& mesh, const NodeRegion& region);

} // namespace kerf
