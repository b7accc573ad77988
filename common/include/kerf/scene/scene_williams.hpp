/// @file scene_williams.hpp
/// @brief Williams's near-front field as a scene's Dirichlet condition on a cut body: the front it is measured from, and its value on every part of each node's support.
///
/// Chapter 5 validates the crack-tip model against a field known in closed form: Williams's
/// field (williams_field.hpp) prescribed on the whole boundary of a cracked slab is the exact
/// solution inside. A `"displacement_file"` cannot prescribe it where the crack reaches the
/// boundary: it gives one value per node, and a node whose support the cut splits needs one per
/// part of that support. A gripped node's enrichments are held at 0 (make_cut_xfem_dof_map), so
/// the crack's mouth stays shut where the exact field opens it by 2 A_I (kappa + 1) sqrt(r).
/// A `"williams"` entry prescribes every DOF of every node of its region instead, the XFEM
/// interpolant of the field:
///
///   u_v     = u_home(x_v)               the field on the node's home part (surface_enrichment.hpp),
///   a_v^k   = u_k(x_v) - u_home(x_v)    the field on part k minus the home part's: a_v^k is
///                                       always "far side minus home side",
///   b_{v,l} = c_l                       a branch node's four functions (williams_branch_coefficients.hpp),
///
/// where u_k(x_v) is the field at x_v as part k sees it. Behind the front the field has two
/// values, one on each face of the crack: a part on the side above the cut (the side its
/// triangles' normals point to, theta > 0) sees theta in (0, pi], one below sees (-pi, 0), and at
/// a node on the crack itself theta = pi on the part above and -pi on the part below. Taking a
/// value across a face is continuing theta by -+ 2 pi, which changes the sign of sin(theta/2)
/// and cos(theta/2) and keeps sin(theta): every mode's displacement changes sign, so a far part
/// across the crack gets a_v^k = -2 u_home(x_v). Ahead of the front the field is single valued.
/// Which side a part lies on is read off its pieces' faces on the cut (PieceBoundaryPolygon's
/// cut_side), so that a node within round-off of the crack's plane takes the side the exact
/// predicates of the cut gave its parts, not the side atan2 gives the round-off in x_b.
///
/// The front: the scene's cuts must have exactly one front inside the mesh (find_crack_fronts),
/// straight and with one normal; its first point, its a (ahead) and its b (the cut's normal) are
/// Williams's frame. A front given in the scene instead could disagree with the cut the model
/// actually has; taken from the cut it cannot. The material: mu and kappa = 3 - 4 nu of the
/// scene's material, plane strain, which is the exact three-dimensional solution when the field is
/// prescribed on the faces the front ends on too (it does not depend on the coordinate along the
/// front, and its u_c of mode III is antiplane).
#pragma once

#include "kerf/cut/crack_front.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/linear_material.hpp"
#include "kerf/fracture/williams_field.hpp"
#include "kerf/scene/scene.hpp"
#include "kerf/xfem/cut_xfem_field_error.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace kerf {

/// The frame of the one straight front of `fronts`: origin its first point, a ahead, b the cut's
/// normal. No front, several, a closed one, or one that bends or twists (a point off the line
/// through its ends, or a normal that turns, by more than 1e-9 of its length) is an InputError
/// naming the scene file and `field` (e.g. "dirichlet[2].williams").
StraightFrontFrame williams_front(const Scene& scene, const CrackFronts& fronts, const std::string& field);

/// Williams's field at x (m) as a part on side `side` of the crack sees it: +1 above the cut, -1
/// below, 0 unknown (the value atan2 gives). Behind the front a part on the other side than
/// atan2's theta gets the value continued across the crack's face, -u(x) (the file comment).
Eigen::Vector3d williams_on_side(const StraightFrontFrame& front, const StressIntensityFactors& K,
                                 const LinearMaterial& material, const Eigen::Vector3d& x, int side);

/// The XFEM interpolant of Williams's field, scaled by `lambda`, on every DOF of `nodes` (mesh
/// nodes of `model`): u_v, each sign enrichment a_v^k and, for a node with a branch slot (a
/// branch node or Fries's ramp node), its four b_{v,l} (the file comment), one DirichletNodes
/// per DOF node. Given to make_cut_xfem_dof_map after the gripped nodes, they replace the zeros
/// it would hold the enrichments at.
std::vector<DirichletNodes> williams_dirichlet_nodes(const CutXfemModel& model, const StraightFrontFrame& front,
                                                     const StressIntensityFactors& K, const LinearMaterial& material,
                                                     const std::vector<int>& nodes, double lambda = 1.0);

/// The error of a solution of the scene against the field of its first "williams" entry, over
/// the whole body (cut_xfem_field_error), and which entry that is.
struct SceneWilliamsError {
  std::size_t entry = 0; ///< the index of the entry in "dirichlet"
  FieldError error;
};

/// What chapter 5's program reports when the scene prescribes Williams's field: how near the
/// solution u (all DOFs of `model`) comes to it. The comparison is the convergence study's when
/// the field is the problem's exact solution: prescribed on the whole boundary, with no gravity
/// and no traction. std::nullopt when the scene has no "williams" entry.
std::optional<SceneWilliamsError> scene_williams_error(const Scene& scene, const CutXfemModel& model,
                                                       const CrackFronts& fronts, const Eigen::VectorXd& u);

} // namespace kerf
