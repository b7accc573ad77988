/// @file tet_neighbours.hpp
/// @brief Which tet lies across each face of each tet, and which tets hold each node.
#pragma once

#include "kerf/mesh/tet_mesh.hpp"

#include <vector>

namespace kerf {

/// The face and node adjacency of a tet mesh.
struct TetNeighbours {
  /// #T by 4: the tet across the face opposite corner a, -1 on the boundary.
  TetMatrix across;
  /// #T by 4: that tet's local face (the corner opposite the shared face), -1 on the boundary.
  TetMatrix across_face;
  /// For each node (corners and, on a Tet10 mesh, mid-edge nodes), the tets that hold it,
  /// in increasing order: the support of its shape function.
  std::vector<std::vector<int>> node_tets;
};

/// Builds both with one pass over the faces (a hash map keyed by the sorted corner triple).
TetNeighbours tet_neighbours(const TetMesh& mesh);

} // namespace kerf
