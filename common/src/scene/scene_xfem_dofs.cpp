#include "kerf/scene/scene_xfem_dofs.hpp"

#include "kerf/app/input_error.hpp"
#include "kerf/fem/rigid_motion_check.hpp"
#include "kerf/scene/scene_mesh.hpp"

namespace kerf {

DofMap scene_xfem_dof_map(const Scene& scene, const XfemModel& model, std::ostream* warnings) {
  const std::string file = scene.source.string();
  DofMap dofs = make_xfem_dof_map(model, scene_held_nodes(scene, model.mesh(), warnings));
  if (dofs.num_free == 0) throw InputError(file, "dirichlet", "every DOF is prescribed: nothing to solve");
  if (const std::vector<UnheldPiece> unheld = xfem_unheld_pieces(model, dofs); !unheld.empty())
    throw InputError(file, "dirichlet", describe_unheld_pieces(unheld) + "; does the cut separate it from the held part?");
  return dofs;
}

DofMap scene_cut_xfem_dof_map(const Scene& scene, const CutXfemModel& model, std::ostream* warnings) {
  const std::string file = scene.source.string();
  DofMap dofs = make_cut_xfem_dof_map(model, scene_held_nodes(scene, model.mesh(), warnings));
  if (dofs.num_free == 0) throw InputError(file, "dirichlet", "every DOF is prescribed: nothing to solve");
  if (const std::vector<UnheldPiece> unheld = cut_xfem_unheld_pieces(model, dofs); !unheld.empty())
    throw InputError(file, "dirichlet", describe_unheld_pieces(unheld) + "; does a cut separate it from the held part?");
  return dofs;
}

} // namespace kerf
