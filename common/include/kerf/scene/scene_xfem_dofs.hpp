/// @file scene_xfem_dofs.hpp
/// @brief The scene's Dirichlet conditions on a cut body's [u; a] unknowns, checked before any solve.
#pragma once

#include "kerf/fem/dof_map.hpp"
#include "kerf/scene/scene.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"
#include "kerf/xfem/xfem_model.hpp"

#include <ostream>

namespace kerf {

/// What scene_dof_map is for chapters 1 and 2, for the cut body: the scene's conditions on the
/// nodes (stray nodes held, with a warning), a_i = 0 on the gripped enriched nodes
/// (make_xfem_dof_map), and then the check that every piece the cut leaves is held, before any
/// factorisation. A piece that nothing holds is an InputError naming the scene file, the field
/// "dirichlet" and the piece (its volume and a point in it): a static solve has no answer then,
/// and whichever solver is chosen would either fail for the wrong reason or return garbage.
DofMap scene_xfem_dof_map(const Scene& scene, const XfemModel& model, std::ostream* warnings);

/// The same for chapter 4's body cut by triangle meshes: a_i^k = 0 for every enrichment of a
/// gripped node (make_cut_xfem_dof_map), then the check that every piece is held.
DofMap scene_cut_xfem_dof_map(const Scene& scene, const CutXfemModel& model, std::ostream* warnings);

} // namespace kerf
