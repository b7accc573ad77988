#include "kerf/mesh/tet10_from_tet4.hpp"

#include <algorithm>
#include <stdexcept>
#include <unordered_map>
#include <vector>

namespace kerf {

TetMesh tet10_from_tet4(const TetMesh& tet4) {
  if (tet4.nodes_per_tet() != 4) throw std::invalid_argument("tet10_from_tet4: the input mesh must be Tet4");
  // Number the edges once: the key is the sorted pair of corner indices.
  std::unordered_map<std::int64_t, int> edge_node;
  edge_node.reserve(static_cast<std::size_t>(tet4.num_tets()) * 2);
  std::vector<Eigen::Vector3d> mid_points;
  TetMesh tet10;
  tet10.tets.resize(tet4.num_tets(), 10);
  const auto num_corner_nodes = tet4.num_nodes();
  for (Eigen::Index t = 0; t < tet4.num_tets(); ++t) {
    for (int a = 0; a < 4; ++a) tet10.tets(t, a) = tet4.tets(t, a);
    for (int e = 0; e < 6; ++e) {
      int i = tet4.tets(t, tet_edge_corners[e][0]);
      int j = tet4.tets(t, tet_edge_corners[e][1]);
      if (i > j) std::swap(i, j);
      const std::int64_t key = static_cast<std::int64_t>(i) * num_corner_nodes + j;
      auto [it, inserted] = edge_node.try_emplace(key, static_cast<int>(num_corner_nodes + mid_points.size()));
      if (inserted)
        mid_points.push_back(0.5 * (tet4.nodes.row(i) + tet4.nodes.row(j)).transpose());
      tet10.tets(t, 4 + e) = it->second;
    }
  }
  tet10.nodes.resize(num_corner_nodes + static_cast<Eigen::Index>(mid_points.size()), 3);
  tet10.nodes.topRows(num_corner_nodes) = tet4.nodes;
  for (std::size_t m = 0; m < mid_points.size(); ++m)
    tet10.nodes.row(num_corner_nodes + static_cast<Eigen::Index>(m)) = mid_points[m].transpose();
  return tet10;
}

} // namespace kerf
