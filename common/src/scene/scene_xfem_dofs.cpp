#include "kerf/scene/scene_xfem_dofs.hpp"

#include "kerf/app/input_error.hpp"
#include "kerf/fem/rigid_motion_check.hpp"
#include "kerf/mesh/check_tet_mesh.hpp"
#include "kerf/scene/scene_mesh.hpp"
#include "kerf/scene/scene_williams.hpp"

namespace kerf {

DofMap scene_xfem_dof_map(const Scene& scene, const XfemModel& model, std::ostream* warnings) {
  const std::string file = scene.source.string();
  DofMap dofs = make_xfem_dof_map(model, scene_held_nodes(scene, model.mesh(), warnings));
  if (dofs.num_free == 0) throw InputError(file, "dirichlet", "every DOF is prescribed: nothing to solve");
  if (const std::vector<UnheldPiece> unheld = xfem_unheld_pieces(model, dofs); !unheld.empty())
    throw InputError(file, "dirichlet", describe_unheld_pieces(unheld) + "; does the cut separate it from the held part?");
  return dofs;
}

namespace {

/// The DOF nodes of node v's enrichments: its sign enrichments and its four branch functions.
std::vector<int> enrichment_dof_nodes(const CutXfemModel& model, int v) {
  const SurfaceEnrichment& enrichment = model.enrichment();
  const auto num_nodes = static_cast<int>(model.mesh().num_nodes());
  std::vector<int> dof_nodes;
  for (int k = enrichment.first_enrichment[static_cast<std::size_t>(v)];
       k < enrichment.first_enrichment[static_cast<std::size_t>(v) + 1]; ++k)
    dof_nodes.push_back(num_nodes + k);
  if (const CrackTipFunctions* tip = model.crack_tip())
    if (const int slot = tip->enrichment.branch_slot[static_cast<std::size_t>(v)]; slot >= 0)
      for (int l = 0; l < 4; ++l) dof_nodes.push_back(static_cast<int>(model.branch_dof_node(slot)) + l);
  return dof_nodes;
}

} // namespace

std::vector<DirichletNodes> scene_cut_dirichlet_nodes(const Scene& scene, const CutXfemModel& model,
                                                      const CrackFronts& fronts, double lambda) {
  std::vector<DirichletNodes> conditions;
  bool after_williams = false;
  for (std::size_t i = 0; i < scene.dirichlet.size(); ++i) {
    const DirichletSpec& spec = scene.dirichlet[i];
    const std::string field = "dirichlet[" + std::to_string(i) + "]";
    std::vector<DirichletNodes> entry;
    if (spec.williams) {
      const std::vector<int> nodes = scene_region_nodes(scene, model.mesh(), spec.region, field + ".region");
      const StraightFrontFrame front = williams_front(scene, fronts, field + ".williams");
      entry = williams_dirichlet_nodes(model, front, spec.williams_K, scene.material, nodes, lambda);
      after_williams = true;
    } else {
      entry = scene_dirichlet_entry_nodes(scene, model.mesh(), i, lambda);
      // make_cut_xfem_dof_map holds a gripped node's enrichments at 0 before every condition
      // given to it, so an earlier Williams entry's values would outlive this entry on a node
      // both list: hold them at 0 here, where the later entry must win.
      if (after_williams)
        for (const DirichletNodes& condition : std::vector<DirichletNodes>(entry))
          for (const int v : condition.nodes)
            entry.push_back({enrichment_dof_nodes(model, v), Eigen::Vector3d::Zero()});
    }
    conditions.insert(conditions.end(), entry.begin(), entry.end());
  }
  return conditions;
}

Eigen::VectorXd scene_cut_prescribed_displacements(const Scene& scene, const CutXfemModel& model,
                                                   const CrackFronts& fronts, double lambda) {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * model.num_dof_nodes());
  for (const DirichletNodes& condition : scene_cut_dirichlet_nodes(scene, model, fronts, lambda))
    for (const int v : condition.nodes) u.segment<3>(3 * v) = condition.displacement;
  return u;
}

DofMap scene_cut_xfem_dof_map(const Scene& scene, const CutXfemModel& model, std::ostream* warnings) {
  return scene_cut_xfem_dof_map(scene, model, CrackFronts{}, warnings);
}

DofMap scene_cut_xfem_dof_map(const Scene& scene, const CutXfemModel& model, const CrackFronts& fronts,
                              std::ostream* warnings) {
  const std::string file = scene.source.string();
  std::vector<DirichletNodes> conditions = scene_cut_dirichlet_nodes(scene, model, fronts);
  // As scene_held_nodes: a node that belongs to no tet has no stiffness; holding it changes
  // nothing else.
  if (const std::vector<int> stray = nodes_without_tets(model.mesh()); !stray.empty()) {
    if (warnings) *warnings << "warning: " << stray.size() << " nodes belong to no tetrahedron and are held fixed\n";
    conditions.push_back({stray, Eigen::Vector3d::Zero()});
  }
  DofMap dofs = make_cut_xfem_dof_map(model, conditions);
  if (dofs.num_free == 0) throw InputError(file, "dirichlet", "every DOF is prescribed: nothing to solve");
  if (const std::vector<UnheldPiece> unheld = cut_xfem_unheld_pieces(model, dofs); !unheld.empty())
    throw InputError(file, "dirichlet", describe_unheld_pieces(unheld) + "; does a cut separate it from the held part?");
  return dofs;
}

} // namespace kerf
