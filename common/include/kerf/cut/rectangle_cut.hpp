/// @file rectangle_cut.hpp
/// @brief A planar rectangular cut surface: the plane it spans, signed distances to that plane, and the rectangle itself.
///
/// The `cut` area is pure geometry: it knows nothing about enrichment. A rectangle is all the
/// papers' experiments need (Schoch et al., section 5.2: "a cut, represented by a simple 2D plane
/// in 3D space"), and a plane needs nothing beyond Eigen. CGAL enters this area later, with
/// cut surfaces given as triangle meshes, where exact predicates and AABB trees pay for their
/// compile time.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace kerf {

/// The rectangle {origin + s edge1 + t edge2 : 0 <= s, t <= 1} of a scene's
/// `cuts[i].rectangle`, and the plane through it.
///
/// Orientation: the unit normal is n = edge1 x edge2 / |edge1 x edge2|, and "above" (the
/// positive side, Omega+ in Paulus et al. section 3.2) is the side n points to.
///
/// Eq. 72 of Schoch et al. define the level set as the signed distance to the cut surface
/// Gamma_cut, i.e. to the rectangle as a bounded set. For deciding on which side of a plane cut
/// a point lies (the classification of a tet, eq. 73, and the sign of the Heaviside
/// enrichment), only the sign matters, and the sign is that of the distance to the PLANE: it is
/// also the only choice whose nodal values interpolate linearly to the exact cut inside a Tet4.
/// So we keep both: signed_distance_to_plane() for the level set, distance_to_rectangle() for
/// the Euclidean distance to the bounded cut, and contains_projection() to tell whether a point
/// of the plane belongs to the cut itself (Paulus et al.'s partially / completely cut elements).
class RectangleCut {
public:
  /// @param origin one corner of the rectangle (m)
  /// @param edge1  the first edge from that corner (m)
  /// @param edge2  the second edge from that corner (m), perpendicular to edge1
  /// @throws std::invalid_argument if an edge has zero length, or the edges are not
  ///         perpendicular to within 1e-9 relative (a parallelogram is not a rectangle, and
  ///         distance_to_rectangle() relies on the right angle)
  RectangleCut(const Eigen::Vector3d& origin, const Eigen::Vector3d& edge1, const Eigen::Vector3d& edge2);

  const Eigen::Vector3d& origin() const { return origin_; }
  const Eigen::Vector3d& edge1() const { return edge1_; }
  const Eigen::Vector3d& edge2() const { return edge2_; }

  /// The unit normal n = edge1 x edge2 / |edge1 x edge2|; it points to the positive side.
  const Eigen::Vector3d& normal() const { return normal_; }

  /// Signed distance n . (x - origin) of x to the plane of the rectangle: positive above, negative
  /// below, zero on the plane. This is the level set Lambda(x) used for a plane cut (eq. 72 with
  /// Gamma_cut extended to the whole plane).
  double signed_distance_to_plane(const Eigen::Vector3d& x) const;

  /// Whether the orthogonal projection of x onto the plane lies in the closed rectangle,
  /// enlarged by `tolerance` on every side.
  /// @param x         the point (m); its distance to the plane does not matter
  /// @param tolerance how far outside the rectangle the projection may lie and still count as
  ///                  inside (m); points on the boundary count as inside, as Paulus et al. use the
  ///                  closure of the cut
  bool contains_projection(const Eigen::Vector3d& x, double tolerance) const;

  /// The (unsigned) Euclidean distance from x to the rectangle as a set, min |x - x*| over x*
  /// in the rectangle (the magnitude in eq. 72). Zero exactly on the rectangle.
  double distance_to_rectangle(const Eigen::Vector3d& x) const;

  /// The area in which a convex polygon of the plane overlaps the rectangle shrunk by `inset`
  /// on every side (enlarged for a negative inset): how much of a tet's section by the plane
  /// the cut covers. The corners may come in any order (a convex polygon's corners, sorted by
  /// angle about their mean, are in order); they are projected onto the plane first.
  /// @param corners the polygon's corners (m), e.g. the cut points of a tet
  /// @param inset   how far inside its edges the rectangle is taken (m)
  /// @return the area (m^2), 0 for fewer than 3 corners or no overlap
  double overlap_area(std::vector<Eigen::Vector3d> corners, double inset) const;

private:
  Eigen::Vector3d origin_, edge1_, edge2_, normal_;
};

} // namespace kerf
