/// @file cut_xfem_loads.hpp
/// @brief The scene's loads on a body cut by triangle meshes: gravity and tractions on [u; a], integrated piece by piece.
#pragma once

#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/scene/scene.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"

#include <Eigen/Core>

namespace kerf {

/// f = sum_p T_p^T (int_p N^T rho g dV + int_{F cap p} N^T t dA) over the pieces p of every
/// tet (cut_xfem_model.hpp's phantom elements): the u rows are chapter 1's loads, the a rows the
/// same integrals over the pieces on which each enrichment is 1. Gravity uses the model's piece
/// rules (so an inexact rule is inexact here too, consistently with its stiffness); a traction
/// on a boundary face of a split tet is integrated over each piece's polygons on that face with
/// a rule exact for the quadratic shape functions of a Tet10 (the edge-midpoint rule).
/// A traction region with no boundary face is an InputError, as in chapter 1.
Eigen::VectorXd cut_xfem_scene_loads(const Scene& scene, const CutXfemModel& model, const BoundaryFaces& boundary);

} // namespace kerf
