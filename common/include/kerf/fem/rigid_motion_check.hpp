/// @file rigid_motion_check.hpp
/// @brief Does every piece of the body have its six rigid motions held by Dirichlet conditions?
#pragma once

#include "kerf/fem/dof_map.hpp"
#include "kerf/mesh/tet_mesh.hpp"

#include <Eigen/Core>
#include <vector>

namespace kerf {

/// A connected piece of the body that the prescribed DOFs do not hold: it can move rigidly.
struct UnheldPiece {
  int free_motions = 0;                      ///< 1 to 6 rigid motions left free
  double volume = 0.0;                       ///< its volume, m^3
  Eigen::Vector3d point = Eigen::Vector3d::Zero(); ///< a point of the piece (the centroid of its largest tet)
};

/// The connected pieces of the mesh (tets that share a node) whose rigid motions (translations
/// and infinitesimal rotations) the prescribed DOFs leave free.
///
/// For each piece, we evaluate its six rigid modes (three translations, three rotations about
/// its centroid) at the prescribed DOFs and count the rank deficit of that n_c x 6 matrix
/// (singular values below 1e-10 of the largest). A piece with no prescribed DOF has 6 free
/// motions; a piece fixed at two nodes only can still turn about the line through them: 1.
/// Factorisations cannot be relied on for this: a singular K_ff often factorises with pivots
/// of round-off size and yields a huge, finite, wrong answer.
///
/// `tet_volume` and `tet_point`, when given (one entry per tet), say what each tet stands for
/// in the report: chapter 3's phantom tets stand for the piece of a cut tet on one side, whose
/// volume is a fraction of theirs and whose centroid is not theirs. By default a tet stands for
/// itself. Nodes that belong to no tet are left out here (see count_free_rigid_motions).
std::vector<UnheldPiece> unheld_pieces(const TetMesh& mesh, const DofMap& dofs, const std::vector<double>& tet_volume = {},
                                       const std::vector<Eigen::Vector3d>& tet_point = {});

/// The number of rigid motions the prescribed DOFs leave free: those of every unheld piece,
/// plus one for every free DOF of a node that belongs to no tet (it has no stiffness at all).
/// Zero means K_ff is positive definite; anything else means K_ff is singular and no solver may
/// be trusted with it.
int count_free_rigid_motions(const TetMesh& mesh, const DofMap& dofs);

} // namespace kerf
