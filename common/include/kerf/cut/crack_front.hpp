/// @file crack_front.hpp
/// @brief The fronts of the cut surfaces inside a mesh, as oriented polylines with a frame, and the polar coordinates (r, theta) of a point about them (Paulus et al., section 3.4).
///
/// A cut surface that ends inside the tissue ends along its front: the part of the surface's
/// boundary (its edges that belong to one triangle only) that lies inside the mesh. Boundary
/// edges outside the mesh, or lying in the mesh's surface (a cut that ends exactly at the
/// body's skin), are not front: the cut is open there, not stopped.
///
/// The frame (Paulus et al., section 3.4, whose printed formulas are garbled; theta by atan2, the
/// usual reading, as in Moes et al. 1999 and Sukumar et al. 2000): on each front segment
///   b = the unit normal of the cut triangle the segment bounds (the side Kerf calls above),
///   a = b x c, pointing AHEAD of the front into uncut material,
///   c = along the front,
/// where c is the edge's direction, and a and c are flipped together when a would point back
/// into the triangle (the paper does not orient a; this is the usual choice), so (a, b, c) stays
/// right-handed. Then the cut lies at theta = +-pi, theta > 0 is the side above the cut (H = +1), theta < 0 below.
///
/// Polar coordinates, and why they are continuous along a curved front. Paulus takes the
/// closest point of the front and the frame of its segment. On a polyline that frame jumps at
/// every vertex, so theta jumps on the planes where the closest segment changes (the paper
/// does not treat curved or kinked fronts). Kerf makes the frame continuous instead:
/// - each vertex gets a frame of its own, c_v the normalised sum of its two segments' c, b_v the
///   normalised sum of their b (a polyline's end keeps its segment's frame);
/// - along segment k, c(t) and b(t) are interpolated linearly between the vertex frames and
///   re-orthonormalised (b made perpendicular to c), a(t) = b(t) x c(t);
/// - the foot of x is the point gamma(t) of the polyline at which x - gamma(t) is perpendicular
///   to c(t) (a quadratic in t on each segment; on a straight front it is the closest point);
///   among several feet the nearest wins;
/// - x_a = (x - gamma) . a(t), x_b = (x - gamma) . b(t), r = sqrt(x_a^2 + x_b^2),
///   theta = atan2(x_b, x_a) in (-pi, pi].
/// At a vertex both segments give the same foot and the same frame, so r and theta are
/// continuous in x everywhere the nearest foot is unique: everywhere closer to the front than its
/// radius of curvature (the level-set polar coordinates of Stolarska et al. 2001 are continuous
/// in the same region; they need a signed distance to an open surface, which is itself
/// discontinuous beyond the front). At an open end of a polyline (where the front leaves the
/// mesh) the first and last segments are extended straight, so a point just beyond the end still
/// has a foot. For a straight front all this is exactly Paulus's closest-point frame. The
/// gradients of x_a and x_b (FrontPolar::grad_x_a, grad_x_b) follow the foot and the frame as
/// they move with x, so that the branch functions' gradients are those of the functions used.
#pragma once

#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/mesh/tet_mesh.hpp"

#include <Eigen/Core>
#include <vector>

namespace kerf {

/// One straight piece of a front: part of a boundary edge of a cut triangle, inside the mesh.
struct FrontSegment {
  Eigen::Vector3d start{0, 0, 0}, end{0, 0, 0}; ///< its ends (m), in the direction of c
  Eigen::Vector3d a{1, 0, 0};                   ///< unit, in the triangle's plane, pointing ahead of the front
  Eigen::Vector3d b{0, 1, 0};                   ///< unit normal of the cut triangle (towards H = +1)
  Eigen::Vector3d c{0, 0, 1};                   ///< unit, along the front: (end - start) / |end - start|, c = a x b
  int surface = 0;                              ///< which cut surface (0-based)
  int triangle = 0;                             ///< which triangle of it the edge bounds
};

/// A front as a chain of segments, segment k from points[k] to points[k + 1].
struct FrontPolyline {
  std::vector<Eigen::Vector3d> points;   ///< #segments + 1 points (m); for a closed front the last equals the first
  std::vector<FrontSegment> segments;    ///< in order, each one's c along the chain
  std::vector<Eigen::Vector3d> tangents; ///< per point: the vertex frame's c (unit)
  std::vector<Eigen::Vector3d> normals;  ///< per point: the vertex frame's b (unit, perpendicular to the tangent)
  bool closed = false;                   ///< a loop (a cut whose whole boundary lies inside the mesh)
};

/// Where a point lies with respect to the fronts: its polar coordinates and the frame there.
struct FrontPolar {
  double r = 0.0;                 ///< sqrt(x_a^2 + x_b^2) (m)
  double theta = 0.0;             ///< atan2(x_b, x_a) in (-pi, pi]; +-pi on the cut
  double x_a = 0.0, x_b = 0.0;    ///< the coordinates of x - foot along a and b (m)
  Eigen::Vector3d foot{0, 0, 0};  ///< the point of the front the coordinates are taken from (m)
  Eigen::Vector3d a{1, 0, 0}, b{0, 1, 0}, c{0, 0, 1}; ///< the frame at the foot, right-handed
  /// grad x_a and grad x_b in x, the foot's and the frame's motion included: a and b on a
  /// straight front; on a polyline they differ by the frame's turning (up to half the angle
  /// between neighbouring segments, plus O(r / R) for the curvature). Where no foot is found
  /// (the closest-point fallback far from a closed front), a and b.
  Eigen::Vector3d grad_x_a{1, 0, 0}, grad_x_b{0, 1, 0};
  int polyline = -1;              ///< which front (-1: there is no front)
  int segment = -1;               ///< which segment of it
};

/// The fronts of all cut surfaces inside one mesh.
struct CrackFronts {
  std::vector<FrontPolyline> polylines;

  bool empty() const { return polylines.empty(); }
  /// The number of segments of all fronts.
  int num_segments() const;
  /// The total length of the fronts (m).
  double length() const;

  /// The polar coordinates of x about the nearest front (see the file comment).
  /// @param x        the point (m)
  /// @param cut_side 0 for a point anywhere; +1 or -1 for a point known to lie ON the cut, on the
  ///                 face above (+1) or below (-1): theta is then set to cut_side * pi whatever
  ///                 the round-off in x_b, so that F_1 = sqrt(r) sin(theta / 2) takes the value
  ///                 of that side (F_1 is two-valued at a node on the cut, and the
  ///                 node's value must be that of its Heaviside side)
  /// @throws std::logic_error if there is no front
  FrontPolar polar(const Eigen::Vector3d& x, int cut_side = 0) const;

  /// The Euclidean distance from x to the nearest front segment (m), +infinity without fronts.
  double distance(const Eigen::Vector3d& x) const;
};

/// The part of a front segment inside one tet.
struct FrontPiece {
  Eigen::Vector3d start{0, 0, 0}, end{0, 0, 0}; ///< in the direction of the segment's c (m)
  int polyline = 0, segment = 0;                ///< which segment of which front
};

/// The pieces of the fronts inside the closed tet X (rows: corners) that have a length above
/// 1e-10 of the tet's size: a front through a face or along an edge meets the tets on both
/// sides, one that only touches a corner meets none.
std::vector<FrontPiece> front_in_tet(const CrackFronts& fronts, const Eigen::Matrix<double, 4, 3>& X);

/// The fronts of `cuts` inside `mesh`: every boundary edge of every cut surface clipped to the
/// closed tets (barycentric tolerance 1e-10), the parts lying in the mesh's boundary faces
/// removed (a point within 1e-10 of the tet's size of a boundary face counts as on it), the rest
/// merged per edge and chained into polylines through shared surface vertices (a vertex where
/// more than two front edges meet ends the chains there).
/// @param mesh Tet4 or Tet10 mesh (its corners define the geometry)
/// @param cuts the cut surfaces, each consistently oriented (check_triangle_surface)
CrackFronts find_crack_fronts(const TetMesh& mesh, const CutSurfaces& cuts);

} // namespace kerf
