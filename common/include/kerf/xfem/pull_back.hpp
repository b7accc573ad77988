/// @file pull_back.hpp
/// @brief The reference position of the material point that the deformation has carried to a given world position: how chapter 7 stores a blade's cut in the reference configuration (Koschier et al. 2017, Fig. 2).
///
/// The blade lives in the world; the cut must live in the reference configuration, where the
/// model's pieces, quadrature and enrichment are defined. A world point x is the image
/// X + u(X) of the reference point X we want, so X solves
///
///   g(X) = X + u(X) - x = 0,
///
/// and Newton's method on g takes X <- X - (I + grad u(X))^{-1} g(X), with grad u the XFEM
/// field's gradient on the piece that holds X (CutXfemModel::displacement_gradient_at). Newton
/// rather than the fixed point X <- x - u(X): that one converges only while |grad u| < 1, which a
/// rotation beyond 60 degrees breaks (|R - I| = 2 sin(angle / 2)). On a Tet4 piece u is affine,
/// so Newton is exact in one step once X stays in one piece; a few steps cross pieces.
///
/// Where there is no such X the iteration says so rather than invent one: x in the gap of an
/// opened cut (no material is there), or outside the deformed body. Then the last iterate leaves
/// the mesh or the residual stops falling, and `converged` is false.
#pragma once

#include "kerf/mesh/point_locator.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"

#include <Eigen/Core>

namespace kerf {

/// The result of pull_back_to_reference.
struct PullBack {
  Eigen::Vector3d reference{0, 0, 0}; ///< X (m): the last iterate
  Eigen::Index tet = -1;              ///< the tet that holds X, -1 if X left the mesh
  int iterations = 0;                 ///< Newton steps taken
  double residual = 0.0;              ///< |X + u(X) - x| (m) at the last iterate (infinity if it left the mesh)
  bool converged = false;             ///< residual <= tolerance
};

/// Solves X + u(X) = x by Newton's method (the file's comment).
/// @param model     the XFEM model whose field u is
/// @param locator   a PointLocator of model.mesh()
/// @param u         all DOFs of the model (3 num_dof_nodes())
/// @param x         the world point (m)
/// @param guess     the first iterate (m): x itself, or the reference point of a neighbouring blade point
/// @param tolerance on the residual (m)
/// @param max_iterations Newton steps at most
PullBack pull_back_to_reference(const CutXfemModel& model, const PointLocator& locator, const Eigen::VectorXd& u,
                                const Eigen::Vector3d& x, const Eigen::Vector3d& guess, double tolerance, int max_iterations = 20);

} // namespace kerf
