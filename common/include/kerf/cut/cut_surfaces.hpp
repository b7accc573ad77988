/// @file cut_surfaces.hpp
/// @brief All the cut surfaces of a scene, with one AABB tree over their triangles: which triangles meet a tet.
#pragma once

#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/cut/tet_pieces.hpp"
#include "kerf/mesh/triangle_surface.hpp"

#include <Eigen/Core>
#include <memory>
#include <vector>

namespace kerf {

/// The rectangle of a chapter 3 cut as a surface of two triangles, oriented so that their
/// normals are the rectangle's (edge1 x edge2): from chapter 4 on, a rectangle is just the
/// simplest triangle mesh, and every cut goes through the same geometry.
TriangleSurface rectangle_surface(const RectangleCut& rectangle);

/// The cut surfaces of a scene and a search structure over all their triangles.
///
/// Why an AABB tree (CGAL's AABB_tree over the triangles): a mesh has #T tets and the cuts #F
/// triangles, and testing every pair costs #T #F exact intersection tests. The tree answers
/// "which triangles' boxes overlap this tet's box" in O(log #F + k); only those k candidates
/// get the exact test (CGAL's do_intersect of a tetrahedron and a triangle, with exact
/// predicates, so that a triangle touching a tet in a single point is found, not missed by
/// round-off).
class CutSurfaces {
public:
  /// @param surfaces the cuts, each checked by check_triangle_surface (the readers do it)
  explicit CutSurfaces(std::vector<TriangleSurface> surfaces);
  ~CutSurfaces();
  CutSurfaces(CutSurfaces&&) noexcept;
  CutSurfaces& operator=(CutSurfaces&&) noexcept;

  int num_surfaces() const { return static_cast<int>(surfaces_.size()); }
  const TriangleSurface& surface(int s) const { return surfaces_[static_cast<std::size_t>(s)]; }
  /// All of them, in order.
  const std::vector<TriangleSurface>& surfaces() const { return surfaces_; }
  /// The total number of triangles of all surfaces.
  Eigen::Index num_triangles() const;

  /// The triangles that meet the closed tet with corners X (rows): inside it, crossing it, or
  /// touching its boundary, in the order of (surface, triangle).
  std::vector<CutTriangle> triangles_meeting_tet(const Eigen::Matrix<double, 4, 3>& X) const;
  /// The triangles whose bounding boxes meet the segment p-q's bounding box, in the order of
  /// (surface, triangle): the candidates of a segment's crossing, found through the tree in
  /// O(log n + found) instead of a test of every triangle; the caller decides which it crosses.
  std::vector<CutTriangle> triangles_near_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& q) const;

private:
  struct Tree;
  // Triangle k of the tree (all surfaces' triangles in order), as a CutTriangle.
  CutTriangle cut_triangle(std::size_t k) const;
  std::vector<TriangleSurface> surfaces_;
  std::unique_ptr<Tree> tree_;
};

} // namespace kerf
