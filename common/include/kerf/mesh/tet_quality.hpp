/// @file tet_quality.hpp
/// @brief How well shaped a tet is: its smallest dihedral angle and its radius ratio, and a mesh's summary of both.
///
/// A tet's shape decides how well its stiffness is conditioned and how large the interpolation
/// error of its gradient can grow: a sliver (four nearly coplanar corners, dihedral angles near
/// 0 and 180 degrees) has a huge gradient error even when its edges are all of one length. We
/// measure two numbers, both scale-free:
/// - the smallest of the six dihedral angles, 70.53 degrees (arccos 1/3) for the regular tet;
/// - the radius ratio 3 r / R, r the radius of the inscribed sphere, R of the circumscribed one:
///   1 for the regular tet, 0 for a flat one (it catches slivers, needles, caps and wedges).
#pragma once

#include "kerf/mesh/tet_mesh.hpp"

#include <Eigen/Core>

namespace kerf {

/// The smallest dihedral angle (degrees) of the tet with corners X (4 by 3, one corner a row).
/// The dihedral angle at the edge shared by the faces opposite corners a and b is pi minus the
/// angle between their outward normals. 0 for a flat tet.
double tet_min_dihedral_angle(const Eigen::Matrix<double, 4, 3>& X);

/// The radius ratio 3 r / R of the tet with corners X: r = 3 V / (sum of the face areas),
/// R = |circumcentre - x0| with circumcentre - x0 = (|a|^2 b x c + |b|^2 c x a + |c|^2 a x b) / (12 V),
/// a, b, c the edges from x0 and 6 V = a . (b x c). 1 for the regular tet, 0 for a flat one
/// (and 0 for a tet whose volume is not positive, so an inverted tet never looks good).
double tet_radius_ratio(const Eigen::Matrix<double, 4, 3>& X);

/// What a mesh's tets look like, from their corners (Tet10 mid-edge nodes are ignored).
struct TetQualitySummary {
  double min_dihedral_angle = 0.0;      ///< the smallest dihedral angle of any tet (degrees)
  double mean_min_dihedral_angle = 0.0; ///< the mean over the tets of each tet's smallest one (degrees)
  double min_radius_ratio = 0.0;        ///< the smallest radius ratio of any tet
  double mean_radius_ratio = 0.0;       ///< the mean radius ratio over the tets
  Eigen::Index below_dihedral_threshold = 0;     ///< tets whose smallest dihedral angle is below the threshold
  Eigen::Index below_radius_ratio_threshold = 0; ///< tets whose radius ratio is below the threshold
};

/// Summarises the quality of every tet of `mesh`.
/// @param dihedral_threshold     the smallest dihedral angle (degrees) below which a tet is counted
/// @param radius_ratio_threshold the radius ratio below which a tet is counted
/// @throws std::invalid_argument for a mesh without tets
TetQualitySummary tet_quality_summary(const TetMesh& mesh, double dihedral_threshold = 10.0,
                                      double radius_ratio_threshold = 0.1);

} // namespace kerf
