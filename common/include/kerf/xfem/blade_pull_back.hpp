/// @file blade_pull_back.hpp
/// @brief The blade's edge, which lives in the world, carried into the reference configuration where the cut is stored (Koschier et al. 2017, Fig. 2).
///
/// A blade cuts the deformed body, but chapter 4 clips the reference mesh. So each frame we pull
/// the edge back: points spread along it are pulled back one by one (pull_back.hpp). Most of a
/// scalpel's edge is outside the tissue, where no material point exists to pull back to. There
/// we extend the deformation's local linear map from the nearest sample that is inside:
///
///   X(x) = X_s + F_s^{-1} (x - x_s),   F_s = I + grad u(X_s),
///
/// which continues the cut straight out through the body's surface, exact for a body moving
/// rigidly or linearly (Tet4 pieces are affine, so nearby it is nearly exact). The two ends of the
/// reference edge come from the inside samples nearest to them. A sample's first guess is its
/// reference point a frame ago, else its world point; one whose guess fails is tried again from
/// a neighbour that pulled back (a body moved further than the sample lies from its surface
/// puts the world point outside the reference mesh, where Newton cannot start). A frame with no sample inside
/// (the blade above the organ, or gone through it) has no edge of its own: the caller maps its
/// edge with a neighbouring frame's anchor (ReferenceBlade::anchor), so that the sheet begins and
/// ends just outside the body.
#pragma once

#include "kerf/cut/blade_path.hpp"
#include "kerf/mesh/point_locator.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"

#include <Eigen/Core>
#include <vector>

namespace kerf {

/// A world point x_s inside the body, its reference point X_s and the inverse of the
/// deformation gradient there: the affine map X(x) = X_s + F_s^{-1} (x - x_s).
struct BladeAnchor {
  Eigen::Vector3d world{0, 0, 0}, reference{0, 0, 0};
  Eigen::Matrix3d inverse_gradient = Eigen::Matrix3d::Identity();
  /// X(x) for any world point x (m).
  Eigen::Vector3d map(const Eigen::Vector3d& x) const { return reference + inverse_gradient * (x - world); }
};

/// The blade's edge in the reference configuration, and how much of it is in the tissue.
struct ReferenceBlade {
  BladeEdge edge;                            ///< in the reference configuration (meaningful when in_tissue())
  std::vector<Eigen::Vector3d> samples;      ///< every sample's reference point (the next frame's guesses)
  std::vector<char> inside;                  ///< per sample: pulled back (1) or extrapolated / none (0)
  int samples_inside = 0;                    ///< how many samples pulled back
  BladeAnchor anchor;                        ///< of the middle inside sample (meaningful when in_tissue())
  bool in_tissue() const { return samples_inside > 0; }
};

/// Pulls the world edge `world` back into the reference configuration (the file's comment).
/// @param model, locator, u the body's model, a PointLocator of its mesh, and its DOFs
/// @param world      the edge in the world (m)
/// @param samples    how many points along it, >= 2, ends included
/// @param previous   the last frame's result (its samples are the first guesses), or nullptr
/// @param tolerance  the pull-back's residual bound (m)
ReferenceBlade pull_back_blade_edge(const CutXfemModel& model, const PointLocator& locator, const Eigen::VectorXd& u, const BladeEdge& world,
                                    int samples, const ReferenceBlade* previous, double tolerance);

} // namespace kerf
