/// @file xfem_loads.hpp
/// @brief Loads on the [u; a] unknowns: gravity and tractions, with their enriched parts rho g int Phi_i Psi_i dV
///        and t int Phi_i Psi_i dA integrated piece by piece.
#pragma once

#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/scene/scene.hpp"
#include "kerf/xfem/xfem_model.hpp"

#include <Eigen/Core>

namespace kerf {

/// int over the piece of tet t on side `side` of Phi_i dV, for its four corners (m^3): V/4
/// each for a tet wholly on that side, 0 for a tet wholly on the other, and for a cut tet the
/// sum over the piece's sub-tets of their volume times Phi_i at their centroid (exact: Phi_i
/// is linear).
Eigen::Vector4d piece_shape_integrals(const XfemModel& model, Eigen::Index t, int side);

/// The scene's gravity and tractions on all 3 (N + N_enr) DOFs.
///
/// The u rows are chapter 1's loads (the enrichment does not change int Phi_i). The a rows are
/// the enriched load f^a_i = int Phi_i Psi_i (rho g) dV + int Phi_i Psi_i t dA (eq. 46 with
/// eq. 42's enriched basis): on each side Psi_i is the constant Psi_side,i, so each piece of a
/// cut tet, and each piece of a cut boundary triangle, contributes its own integral of Phi_i.
/// @throws InputError as scene_external_loads does for a traction region without faces
Eigen::VectorXd xfem_scene_loads(const Scene& scene, const XfemModel& model, const BoundaryFaces& boundary);

} // namespace kerf
