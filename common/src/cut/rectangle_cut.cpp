#include "kerf/cut/rectangle_cut.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace kerf {

RectangleCut::RectangleCut(const Eigen::Vector3d& origin, const Eigen::Vector3d& edge1, const Eigen::Vector3d& edge2)
    : origin_(origin), edge1_(edge1), edge2_(edge2) {
  const double length1 = edge1.norm(), length2 = edge2.norm();
  if (!(length1 > 0.0) || !(length2 > 0.0)) throw std::invalid_argument("RectangleCut: edge1 and edge2 must be nonzero");
  if (std::abs(edge1.dot(edge2)) > 1e-9 * length1 * length2)
    throw std::invalid_argument("RectangleCut: edge1 and edge2 must be perpendicular");
  normal_ = edge1.cross(edge2).normalized();
}

double RectangleCut::signed_distance_to_plane(const Eigen::Vector3d& x) const { return normal_.dot(x - origin_); }

bool RectangleCut::contains_projection(const Eigen::Vector3d& x, double tolerance) const {
  // Because the edges are perpendicular, the in-plane coordinates of the projection are the
  // plain projections onto each edge; we measure them in metres so that the tolerance is a length.
  const Eigen::Vector3d d = x - origin_;
  const double length1 = edge1_.norm(), length2 = edge2_.norm();
  const double s = d.dot(edge1_) / length1, t = d.dot(edge2_) / length2;
  return s >= -tolerance && s <= length1 + tolerance && t >= -tolerance && t <= length2 + tolerance;
}

double RectangleCut::distance_to_rectangle(const Eigen::Vector3d& x) const {
  // The closest point of a rectangle clamps each in-plane coordinate to its edge's range
  // (this is where the right angle matters: for a parallelogram clamping is not enough).
  const Eigen::Vector3d d = x - origin_;
  const double s = std::clamp(d.dot(edge1_) / edge1_.squaredNorm(), 0.0, 1.0);
  const double t = std::clamp(d.dot(edge2_) / edge2_.squaredNorm(), 0.0, 1.0);
  const Eigen::Vector3d closest = origin_ + s * edge1_ + t * edge2_;
  return (x - closest).norm();
}

} // namespace kerf
