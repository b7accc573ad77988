#include "kerf/mesh/liver_wedge.hpp"

#include <cmath>

namespace kerf {

namespace {

// The smooth maximum -smin(-a, -b, k): above max(a, b) by at most k ln 2.
double smooth_maximum(double a, double b, double k) { return -smooth_minimum(-a, -b, k); }

// The signed distance to the visceral plane, positive below it (outside).
double visceral_phi(const LiverVisceralPlane& plane, const Eigen::Vector3d& x) {
  const double height = plane.z0 + plane.rise_front * (plane.y0 - x.y()) + plane.rise_left * (x.x() - plane.x0);
  const double norm = std::sqrt(1.0 + plane.rise_front * plane.rise_front + plane.rise_left * plane.rise_left);
  return (height - x.z()) / norm;
}

} // namespace

double liver_wedge_phi(const Eigen::Vector3d& x) {
  const double dome = smooth_minimum(liver_lobe_phi(liver_wedge_right_lobe, x), liver_lobe_phi(liver_wedge_left_lobe, x),
                                     liver_wedge_lobe_blend);
  const double wedge = smooth_maximum(dome, visceral_phi(liver_visceral_plane, x), liver_wedge_border_blend);
  const double floored = smooth_maximum(wedge, liver_wedge_floor_height - x.z(), liver_wedge_floor_blend);
  return smooth_maximum(floored, -liver_lobe_phi(liver_wedge_notch, x), liver_wedge_notch_blend);
}

Eigen::AlignedBox3d liver_wedge_bounding_box() {
  return blended_lobes_box(liver_wedge_right_lobe, liver_wedge_left_lobe, liver_wedge_lobe_blend, liver_wedge_floor_height);
}

} // namespace kerf
