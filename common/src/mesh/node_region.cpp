#include "kerf/mesh/node_region.hpp"

#include <algorithm>

namespace kerf {

std::vector<int> nodes_in_region(const TetMesh& mesh, const NodeRegion& region) {
  std::vector<int> nodes;
  if (!region.is_box) {
    nodes = region.node_list;
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    return nodes;
  }
  const double tolerance = region_tolerance(mesh);
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) {
    const Eigen::Vector3d x = mesh.nodes.row(v).transpose();
    if (((x.array() >= region.box_min.array() - tolerance) && (x.array() <= region.box_max.array() + tolerance)).all())
      nodes.push_back(static_cast<int>(v));
  }
  return nodes;
}

double region_tolerance(const TetMesh& mesh) {
  return 1e-9 * (mesh.nodes.colwise().maxCoeff() - mesh.nodes.colwise().minCoeff()).norm();
}

std::vector<char> node_mask(const TetMesh& mesh, const NodeRegion& region) {
  std::vector<char> mask(static_cast<std::size_t>(mesh.num_nodes()), 0);
  for (int v : nodes_in_region(mesh, region)) mask[static_cast<std::size_t>(v)] = 1;
  return mask;
}

} // namespace kerf
