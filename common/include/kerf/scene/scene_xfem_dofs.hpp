/// @file scene_xfem_dofs.hpp
/// @brief The scene's Dirichlet conditions on a cut body's [u; a] unknowns, checked before any solve.
#pragma once

#include "kerf/cut/crack_front.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/scene/scene.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"
#include "kerf/xfem/xfem_model.hpp"

#include <ostream>
#include <vector>

namespace kerf {

/// What scene_dof_map is for chapters 1 and 2, for the cut body: the scene's conditions on the
/// nodes (stray nodes held, with a warning), a_i = 0 on the gripped enriched nodes
/// (make_xfem_dof_map), and then the check that every piece the cut leaves is held, before any
/// factorisation. A piece that nothing holds is an InputError naming the scene file, the field
/// "dirichlet" and the piece (its volume and a point in it): a static solve has no answer then,
/// and whichever solver is chosen would either fail for the wrong reason or return garbage.
DofMap scene_xfem_dof_map(const Scene& scene, const XfemModel& model, std::ostream* warnings);

/// The scene's Dirichlet entries on the cut body of chapters 4 and 5, in order, at load factor
/// lambda: each entry's conditions on the mesh's nodes (scene_dirichlet_entry_nodes), and a
/// "williams" entry's on every DOF of its nodes, [u; a; b] (scene_williams.hpp), measured from
/// the one front of `fronts` (none: such an entry is an InputError naming it). A node listed
/// twice takes the later entry, as make_dof_map does.
std::vector<DirichletNodes> scene_cut_dirichlet_nodes(const Scene& scene, const CutXfemModel& model,
                                                      const CrackFronts& fronts, double lambda = 1.0);

/// The same as one vector of 3 model.num_dof_nodes() values (zero on the DOFs no entry
/// prescribes): the path along which a quasi-static solve ramps them (scene_prescribed_displacements
/// on the mesh's nodes, and a Williams field's enrichments scaled with it).
Eigen::VectorXd scene_cut_prescribed_displacements(const Scene& scene, const CutXfemModel& model,
                                                   const CrackFronts& fronts, double lambda);

/// The same for chapter 4's body cut by triangle meshes: a_i^k = 0 for every enrichment of a
/// gripped node (make_cut_xfem_dof_map), then the check that every piece is held. With `fronts`
/// (chapter 5: the fronts of the cuts), a "williams" entry prescribes the enrichments of its
/// nodes instead of holding them at 0 (scene_cut_dirichlet_nodes).
DofMap scene_cut_xfem_dof_map(const Scene& scene, const CutXfemModel& model, std::ostream* warnings);
DofMap scene_cut_xfem_dof_map(const Scene& scene, const CutXfemModel& model, const CrackFronts& fronts,
                              std::ostream* warnings);

} // namespace kerf
