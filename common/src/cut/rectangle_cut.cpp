#include "kerf/cut/rectangle_cut.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
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

double RectangleCut::overlap_area(std::vector<Eigen::Vector3d> corners, double inset) const {
  // In-plane coordinates (m) along the two edges, the polygon in order by angle about its mean.
  const Eigen::Vector3d e1 = edge1_.normalized(), e2 = edge2_.normalized();
  std::vector<Eigen::Vector2d> polygon;
  for (const Eigen::Vector3d& x : corners) polygon.emplace_back((x - origin_).dot(e1), (x - origin_).dot(e2));
  if (polygon.size() < 3) return 0.0;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& q : polygon) mean += q / static_cast<double>(polygon.size());
  std::sort(polygon.begin(), polygon.end(), [&](const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
    return std::atan2(p.y() - mean.y(), p.x() - mean.x()) < std::atan2(q.y() - mean.y(), q.x() - mean.x());
  });
  // Sutherland-Hodgman against the half-planes s >= inset, s <= |edge1| - inset, t >= inset,
  // t <= |edge2| - inset: keep the side where sign * (coordinate - bound) >= 0.
  const double length1 = edge1_.norm(), length2 = edge2_.norm();
  const std::array<std::array<double, 3>, 4> sides{{{0, inset, 1.0}, {0, length1 - inset, -1.0}, {1, inset, 1.0}, {1, length2 - inset, -1.0}}};
  for (const auto& [axis_value, bound, sign] : sides) {
    const auto axis = static_cast<Eigen::Index>(axis_value);
    std::vector<Eigen::Vector2d> clipped;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
      const Eigen::Vector2d& p = polygon[i];
      const Eigen::Vector2d& q = polygon[(i + 1) % polygon.size()];
      const double dp = sign * (p[axis] - bound), dq = sign * (q[axis] - bound);
      if (dp >= 0.0) clipped.push_back(p);
      if (dp * dq < 0.0) clipped.push_back(p + dp / (dp - dq) * (q - p));
    }
    polygon = std::move(clipped);
  }
  double twice_area = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d& p = polygon[i];
    const Eigen::Vector2d& q = polygon[(i + 1) % polygon.size()];
    twice_area += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * std::abs(twice_area);
}

} // namespace kerf
