/// @file point_locator.hpp
/// @brief Find the tet that contains a point, and the point's reference coordinates in it.
#pragma once

#include "kerf/mesh/tet_mesh.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace kerf {

/// Where a point lies: a tet and reference coordinates xi in it (tet == -1: outside the mesh).
struct PointLocation {
  Eigen::Index tet = -1;
  Eigen::Vector3d xi{0, 0, 0};
};

/// A uniform grid of buckets over the mesh's bounding box, each listing the tets whose
/// bounding boxes overlap it. About one tet per bucket keeps a query to a handful of
/// barycentric tests. Straight-edged tets are assumed (the corners define the geometry), as
/// for every mesh Kerf makes.
class PointLocator {
public:
  explicit PointLocator(const TetMesh& mesh);

  /// The tet containing x, with a relative tolerance of 1e-10 on the barycentric coordinates so
  /// that points on faces, edges and nodes are found; among several candidates the one with the
  /// largest smallest barycentric coordinate wins.
  PointLocation locate(const Eigen::Vector3d& x) const;

private:
  Eigen::Vector3i bucket_of(const Eigen::Vector3d& x) const;

  const TetMesh& mesh_;
  Eigen::Vector3d lower_, bucket_size_;
  Eigen::Vector3i buckets_;
  std::vector<int> bucket_start_; ///< CSR: tets of bucket b are bucket_tets_[bucket_start_[b] .. bucket_start_[b+1])
  std::vector<int> bucket_tets_;
  /// Per tet: its bounding box grown by 1e-9 of its diagonal, which holds every point the
  /// barycentric test with its 1e-10 tolerance could accept. A query solves for the barycentric
  /// coordinates only in the tets of its bucket whose box holds it.
  std::vector<Eigen::AlignedBox3d> boxes_;
};

} // namespace kerf
