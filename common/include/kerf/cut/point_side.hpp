/// @file point_side.hpp
/// @brief Which side of a triangle-mesh cut a point lies on: Paulus's closest-triangle test, and the exact sign from angle-weighted pseudo-normals (Baerentzen and Aanaes 2005).
///
/// Koschier's signed distance (eq. 9) needs a sign s(x) that the paper does not define.
/// Paulus et al. (section 4.1) take the triangle closest to x and the sign of
/// (x - P_0) . n of that triangle. Near a kink this can be wrong: when the closest point is on
/// the kink's edge (or a vertex), two or more triangles are equally close, and the plane of
/// the one picked need not separate x from the surface. It is wrong exactly when the fold is
/// sharper than a right angle (the two normals more than 90 degrees apart): for x in the normal
/// cone of the edge, x - c = alpha n_1 + beta n_2 with alpha, beta >= 0, and
/// (x - c) . n_1 = alpha + beta n_1 . n_2 is negative for beta n_1 . n_2 < -alpha.
///
/// Baerentzen and Aanaes's angle-weighted pseudo-normal fixes this: at the closest point c,
/// take the normal of the feature c lies on, the face's normal inside a face, the sum of the
/// two faces' normals on an edge, and the sum of the incident faces' normals weighted by their
/// angles at a vertex. Then sign((x - c) . n_pseudo) is the side of x for every x off the
/// surface whose closest point is not on the surface's boundary (their theorem is for closed
/// surfaces; on an open one it holds wherever the closest point is an inner point, which is
/// where a cut's sign is needed: inside tets the cut separates).
///
/// Neither is what Kerf's model uses: the pieces of a cut tet (tet_pieces.hpp) say which
/// piece holds a point without any sign. These two are here for the failure study's comparison
/// (results.md, "Where it fails") and for later chapters that need a sign away from the pieces.
#pragma once

#include "kerf/mesh/triangle_surface.hpp"

#include <Eigen/Core>
#include <map>
#include <utility>

namespace kerf {

/// Which feature of a triangle holds a closest point.
enum class TriangleFeature : signed char {
  face,   ///< the triangle's inside
  edge,   ///< one of its edges (vertices a, b)
  vertex, ///< one of its corners (vertex a)
};

/// The point of a surface closest to a query point.
struct ClosestSurfacePoint {
  Eigen::Vector3d point{0, 0, 0};               ///< c (m)
  double distance = 0.0;                        ///< |x - c| (m)
  int triangle = -1;                            ///< the closest triangle (the lowest-numbered on a tie, to 1e-12 relative)
  TriangleFeature feature = TriangleFeature::face;
  int a = -1, b = -1;                           ///< the surface vertices of the edge (a, b) or the vertex a
};

/// The closest point of `surface` to x, by testing every triangle (the region tests of Ericson,
/// Real-Time Collision Detection, section 5.1.5). O(#F): a study's tool, not a mesh's.
ClosestSurfacePoint closest_surface_point(const TriangleSurface& surface, const Eigen::Vector3d& x);

/// Paulus's sign (section 4.1): +1 if (x - P_0) . n > 0 for the closest triangle, with
/// n = (P_1 - P_0) x (P_2 - P_0), -1 if it is negative, 0 if x lies in that triangle's plane.
int closest_triangle_side(const TriangleSurface& surface, const Eigen::Vector3d& x);

/// The angle-weighted pseudo-normals of a surface (Baerentzen and Aanaes 2005, eq. 1):
/// n_v = sum over the triangles at v of alpha_t n_t (alpha_t the triangle's angle at v, n_t its
/// unit normal), n_e = sum of the unit normals of the triangles at edge e, n_f = n_t.
struct PseudoNormals {
  Eigen::MatrixX3d face;                                 ///< #F by 3, unit normals
  Eigen::MatrixX3d vertex;                               ///< #V by 3, angle-weighted sums
  std::map<std::pair<int, int>, Eigen::Vector3d> edge;   ///< key (min, max) vertex pair: the sum of its faces' normals
};

/// Computes the three kinds of pseudo-normal of `surface`.
PseudoNormals angle_weighted_pseudo_normals(const TriangleSurface& surface);

/// The exact sign: +1 if (x - c) . n_pseudo > 0 at the closest point c, -1 if negative, 0 if x
/// is on the surface (or the product vanishes).
/// @param normals angle_weighted_pseudo_normals(surface)
int pseudo_normal_side(const TriangleSurface& surface, const PseudoNormals& normals, const Eigen::Vector3d& x);

} // namespace kerf
