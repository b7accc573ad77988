#include "kerf/scene/scene_mesh.hpp"

#include "kerf/app/input_error.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/read_mesh.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"

#include <filesystem>

namespace kerf {

TetMesh make_scene_mesh(const Scene& scene, std::ostream* warnings) {
  TetMesh mesh;
  if (scene.mesh.is_box) {
    mesh = make_box_mesh(scene.mesh.box_min, scene.mesh.box_max, scene.mesh.box_cells);
  } else {
    if (!std::filesystem::exists(scene.mesh.file))
      throw InputError(scene.source.string(), "mesh.file", "no such file: " + scene.mesh.file.string());
    mesh = read_mesh(scene.mesh.file, warnings);
    mesh.nodes *= scene.mesh.scale;
  }
  if (scene.mesh.order == 2 && mesh.order() == 1) mesh = tet10_from_tet4(mesh);
  if (scene.mesh.order == 1 && mesh.order() == 2)
    throw InputError(scene.source.string(), "mesh.order", "the file holds Tet10 elements; set \"order\": 2");
  return mesh;
}

std::vector<int> scene_region_nodes(const Scene& scene, const TetMesh& mesh, const NodeRegion& region,
                                    const std::string& field) {
  for (int v : region.node_list)
    if (v >= mesh.num_nodes())
      throw InputError(scene.source.string(), field + ".nodes",
                       "node index " + std::to_string(v) + " is past the mesh's " + std::to_string(mesh.num_nodes()) + " nodes");
  std::vector<int> nodes = nodes_in_region(mesh, region);
  if (nodes.empty()) throw InputError(scene.source.string(), field, "the region contains no node of the mesh");
  return nodes;
}

std::vector<DirichletNodes> scene_dirichlet_nodes(const Scene& scene, const TetMesh& mesh) {
  std::vector<DirichletNodes> conditions;
  for (std::size_t i = 0; i < scene.dirichlet.size(); ++i) {
    const DirichletSpec& spec = scene.dirichlet[i];
    const std::vector<int> nodes = scene_region_nodes(scene, mesh, spec.region, "dirichlet[" + std::to_string(i) + "].region");
    if (!spec.has_rotation) {
      conditions.push_back({nodes, spec.displacement});
      continue;
    }
    for (int v : nodes) conditions.push_back({{v}, spec.displacement_at(mesh.nodes.row(v).transpose())});
  }
  return conditions;
}

} // namespace kerf
