#include "kerf/mesh/tet_neighbours.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <stdexcept>
#include <unordered_map>

namespace kerf {

TetNeighbours tet_neighbours(const TetMesh& mesh) {
  TetNeighbours result;
  const Eigen::Index T = mesh.num_tets();
  result.across = TetMatrix::Constant(T, 4, -1);
  result.across_face = TetMatrix::Constant(T, 4, -1);
  result.node_tets.assign(static_cast<std::size_t>(mesh.num_nodes()), {});
  for (Eigen::Index t = 0; t < T; ++t)
    for (int a = 0; a < mesh.nodes_per_tet(); ++a) result.node_tets[static_cast<std::size_t>(mesh.tets(t, a))].push_back(static_cast<int>(t));

  // A face's key: its three corner indices sorted, packed into 64 bits, 21 bits each.
  if (mesh.num_nodes() >= (Eigen::Index{1} << 21))
    throw std::invalid_argument("tet_neighbours: meshes of more than two million nodes are not supported");
  const auto key_of = [](std::array<int, 3> c) {
    std::sort(c.begin(), c.end());
    return (static_cast<std::uint64_t>(c[0]) << 42) | (static_cast<std::uint64_t>(c[1]) << 21) | static_cast<std::uint64_t>(c[2]);
  };
  std::unordered_map<std::uint64_t, std::pair<int, int>> open; // key -> (tet, local face) seen once
  open.reserve(static_cast<std::size_t>(2 * T));
  for (Eigen::Index t = 0; t < T; ++t)
    for (int a = 0; a < 4; ++a) {
      std::array<int, 3> corners{};
      for (int k = 0, m = 0; k < 4; ++k)
        if (k != a) corners[static_cast<std::size_t>(m++)] = mesh.tets(t, k);
      const std::uint64_t key = key_of(corners);
      const auto found = open.find(key);
      if (found == open.end()) {
        open.emplace(key, std::make_pair(static_cast<int>(t), a));
        continue;
      }
      const auto [s, b] = found->second;
      result.across(t, a) = s;
      result.across_face(t, a) = b;
      result.across(s, b) = static_cast<int>(t);
      result.across_face(s, b) = a;
      open.erase(found);
    }
  return result;
}

} // namespace kerf
