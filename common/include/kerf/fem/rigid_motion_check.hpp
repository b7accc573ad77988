/// @file rigid_motion_check.hpp
/// @brief Does every piece of the body have its six rigid motions held by Dirichlet conditions?
#pragma once

#include "kerf/fem/dof_map.hpp"
#include "kerf/mesh/tet_mesh.hpp"

namespace kerf {

/// The number of rigid motions (translations and infinitesimal rotations) that the prescribed
/// DOFs leave free, summed over the connected pieces of the mesh. Zero means K_ff is positive
/// definite; anything else means K_ff is singular and no solver may be trusted with it.
///
/// For each piece, we evaluate its six rigid modes (three translations, three rotations about
/// its centroid) at the prescribed DOFs and count the rank deficit of that n_c x 6 matrix
/// (singular values below 1e-10 of the largest). A piece with no prescribed DOF has 6 free
/// motions; a piece fixed at two nodes only can still turn about the line through them: 1.
/// Factorisations cannot be relied on for this: a singular K_ff often factorises with pivots
/// of round-off size and yields a huge, finite, wrong answer. Every free DOF of a node that
/// belongs to no tet counts as one free motion too.
int count_free_rigid_motions(const TetMesh& mesh, const DofMap& dofs);

} // namespace kerf
