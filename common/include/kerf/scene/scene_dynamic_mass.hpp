/// @file scene_dynamic_mass.hpp
/// @brief The mass a scene's "time.mass" names for a cut body, and the loads that go with it.
#pragma once

#include "kerf/dynamics/lumped_mass.hpp"
#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/scene/scene.hpp"
#include "kerf/xfem/split_tet_masses.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <optional>

namespace kerf {

/// The lumping scheme of "time.mass" ("lumped" is the per-piece Bernstein scheme), or none for "consistent".
std::optional<LumpingScheme> scene_lumping_scheme(const Scene& scene);

/// The mass on all 3 num_dof_nodes() DOFs: the consistent XFEM mass (cut_xfem_mass.hpp) or the
/// lumped one (lumped_mass.hpp), with the scene's density. `rule` is the scene's piece rule.
Eigen::SparseMatrix<double> scene_cut_xfem_mass(const Scene& scene, const CutXfemModel& model, const PieceRuleFunction& rule);
/// The same with the split tets' piece masses from `masses` (made for this model; chapter 7).
Eigen::SparseMatrix<double> scene_cut_xfem_mass(const Scene& scene, const CutXfemModel& model, const SplitTetMasses& masses);

/// The scene's loads (cut_xfem_loads.hpp) with the body force that belongs to the mass: the
/// consistent rho g for the consistent mass, the lumped one (lumped_gravity_load) for a lumped
/// scheme, so that M a = f has "every phantom node falls at g" as its solution where nothing
/// holds the body (the free fall the chapter's tests check).
Eigen::VectorXd scene_cut_xfem_dynamic_loads(const Scene& scene, const CutXfemModel& model, const BoundaryFaces& boundary,
                                             const PieceRuleFunction& rule);

} // namespace kerf
