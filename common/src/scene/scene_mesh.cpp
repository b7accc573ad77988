#include "kerf/scene/scene_mesh.hpp"

#include "kerf/app/input_error.hpp"
#include "kerf/fem/assemble_loads.hpp"
#include "kerf/fem/rigid_motion_check.hpp"
#include "kerf/mesh/check_tet_mesh.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/liver_mesh.hpp"
#include "kerf/mesh/read_mesh.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"

#include <filesystem>
#include <stdexcept>

namespace kerf {

TetMesh make_scene_mesh(const Scene& scene, std::ostream* warnings) {
  TetMesh mesh;
  if (scene.mesh.is_liver) {
    // The range was checked with the scene; Mesh_3 failing on a valid size is a failure of the
    // mesher, said in one line.
    try {
      mesh = make_liver_mesh(scene.mesh.liver_tets, scene.mesh.liver_shape);
    } catch (const std::exception& error) {
      throw InputError(scene.source.string(), "mesh.liver.tets", std::string("Mesh_3 could not make the liver: ") + error.what());
    }
  } else if (scene.mesh.is_box) {
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
  // Linear tets lock: a constant-strain element cannot change shape without changing volume,
  // and near incompressibility every volume change costs lambda, which grows without bound.
  if (mesh.order() == 1 && scene.material.poisson > near_incompressible_poisson && warnings)
    *warnings << "warning: " << scene.source.string() << ": material.poisson = " << scene.material.poisson
              << " with Tet4 elements, which lock in nearly incompressible material (chapter 1's locking study: at 0.4999 "
                 "a Tet4 beam bends 3% as far as it should); use \"order\": 2\n";
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

std::vector<DirichletNodes> scene_dirichlet_entry_nodes(const Scene& scene, const TetMesh& mesh, std::size_t i, double lambda) {
  const DirichletSpec& spec = scene.dirichlet[i];
  if (spec.williams)
    throw std::logic_error("scene_dirichlet_entry_nodes: dirichlet[" + std::to_string(i) +
                           "] is Williams's field, which acts on the cut body's enrichments too (scene_cut_dirichlet_nodes)");
  const std::vector<int> nodes = scene_region_nodes(scene, mesh, spec.region, "dirichlet[" + std::to_string(i) + "].region");
  std::vector<DirichletNodes> conditions;
  if (spec.from_file) {
    const std::string entry = "dirichlet[" + std::to_string(i) + "] of " + scene.source.string();
    const std::vector<Eigen::Vector3d> values = displacements_from_file(spec.file, mesh, nodes, entry);
    for (std::size_t k = 0; k < nodes.size(); ++k) conditions.push_back({{nodes[k]}, lambda * values[k]});
    return conditions;
  }
  if (!spec.has_rotation) return {{nodes, lambda * spec.displacement}};
  DirichletSpec partial = spec;
  partial.degrees *= lambda;
  partial.displacement *= lambda;
  for (int v : nodes) conditions.push_back({{v}, partial.displacement_at(mesh.nodes.row(v).transpose())});
  return conditions;
}

std::vector<DirichletNodes> scene_dirichlet_nodes(const Scene& scene, const TetMesh& mesh, double lambda) {
  std::vector<DirichletNodes> conditions;
  for (std::size_t i = 0; i < scene.dirichlet.size(); ++i) {
    std::vector<DirichletNodes> entry = scene_dirichlet_entry_nodes(scene, mesh, i, lambda);
    conditions.insert(conditions.end(), entry.begin(), entry.end());
  }
  return conditions;
}

std::vector<DirichletNodes> scene_held_nodes(const Scene& scene, const TetMesh& mesh, std::ostream* warnings) {
  std::vector<DirichletNodes> conditions = scene_dirichlet_nodes(scene, mesh);
  if (const auto stray = nodes_without_tets(mesh); !stray.empty()) {
    if (warnings) *warnings << "warning: " << stray.size() << " nodes belong to no tetrahedron and are held fixed\n";
    conditions.push_back({stray, Eigen::Vector3d::Zero()});
  }
  return conditions;
}

DofMap scene_dof_map(const Scene& scene, const TetMesh& mesh, std::ostream* warnings) {
  const std::string file = scene.source.string();
  DofMap dofs = make_dof_map(mesh.num_nodes(), scene_held_nodes(scene, mesh, warnings));
  if (dofs.num_free == 0) throw InputError(file, "dirichlet", "every DOF is prescribed: nothing to solve");
  if (const int free_motions = count_free_rigid_motions(mesh, dofs); free_motions > 0)
    throw InputError(file, "dirichlet",
                     "the conditions leave " + std::to_string(free_motions) +
                         " rigid motions of the body free; fix at least three non-collinear nodes of every piece");
  return dofs;
}

Eigen::VectorXd scene_external_loads(const Scene& scene, const TetMesh& mesh, const BoundaryFaces& boundary) {
  // JSON has no inf or NaN, but finite numbers can multiply to infinity (density 1e5 times
  // gravity 1e305): say so here, by field, rather than as a solver failure later.
  const std::string file = scene.source.string();
  Eigen::VectorXd f = assemble_gravity(mesh, scene.material.density, scene.gravity);
  if (!f.allFinite()) throw InputError(file, "gravity", "the body force density * gravity is too large to represent (not finite)");
  for (std::size_t i = 0; i < scene.traction.size(); ++i) {
    const std::string field = "traction[" + std::to_string(i) + "].region";
    std::vector<char> in_region(static_cast<std::size_t>(mesh.num_nodes()), 0);
    for (int v : scene_region_nodes(scene, mesh, scene.traction[i].region, field)) in_region[static_cast<std::size_t>(v)] = 1;
    if (add_uniform_traction(mesh, boundary, in_region, scene.traction[i].total_force, f) == 0.0)
      throw InputError(file, field, "no boundary face has all its nodes in the region");
    if (!f.allFinite())
      throw InputError(file, "traction[" + std::to_string(i) + "].total_force", "the nodal forces are too large to represent (not finite)");
  }
  return f;
}

Eigen::VectorXd scene_prescribed_displacements(const Scene& scene, const TetMesh& mesh, double lambda) {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * mesh.num_nodes());
  for (const DirichletNodes& condition : scene_dirichlet_nodes(scene, mesh, lambda))
    for (int v : condition.nodes) u.segment<3>(3 * v) = condition.displacement;
  return u;
}

} // namespace kerf
