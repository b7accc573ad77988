#include "kerf/mesh/liver_shape.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace kerf {

double liver_lobe_phi(const LiverLobe& lobe, const Eigen::Vector3d& x) {
  const Eigen::Vector3d q = (x - lobe.centre).cwiseQuotient(lobe.semi_axes);
  return lobe.semi_axes.minCoeff() * (q.norm() - 1.0);
}

double smooth_minimum(double a, double b, double k) {
  // min(a, b) - k log(1 + exp(-|a - b| / k)) is the same function written so that no exponential
  // can overflow, however large |a - b| / k.
  return std::min(a, b) - k * std::log1p(std::exp(-std::abs(a - b) / k));
}

double liver_phi(const Eigen::Vector3d& x) {
  const double lobes = smooth_minimum(liver_lobe_phi(liver_right_lobe, x), liver_lobe_phi(liver_left_lobe, x), liver_lobe_blend);
  const double below_floor = liver_floor_height - x.z();
  return -smooth_minimum(-lobes, -below_floor, liver_floor_blend);
}

namespace {

/// The box of the points where the lobe's phi is below `grow` (m): its semi-axes scaled by
/// 1 + grow / (smallest semi-axis), from the lobe's definition.
Eigen::AlignedBox3d grown_lobe_box(const LiverLobe& lobe, double grow) {
  const Eigen::Vector3d half = lobe.semi_axes * (1.0 + grow / lobe.semi_axes.minCoeff());
  return {lobe.centre - half, lobe.centre + half};
}

} // namespace

Eigen::AlignedBox3d blended_lobes_box(const LiverLobe& a, const LiverLobe& b, double blend, double floor) {
  // phi < 0 needs smooth_minimum(lobes) < 0, so min(phi_a, phi_b) < k ln 2, and needs z > floor,
  // because the smooth maximum is never below either argument.
  const double grow = blend * std::log(2.0);
  Eigen::AlignedBox3d box = grown_lobe_box(a, grow);
  box.extend(grown_lobe_box(b, grow));
  box.min().z() = std::max(box.min().z(), floor);
  return box;
}

Eigen::AlignedBox3d liver_bounding_box() {
  return blended_lobes_box(liver_right_lobe, liver_left_lobe, liver_lobe_blend, liver_floor_height);
}

Eigen::Vector3d liver_centre() { return liver_bounding_box().center(); }

double liver_bounding_radius() { return 1.1 * 0.5 * liver_bounding_box().diagonal().norm(); }

double liver_volume(double cell) { return implicit_volume(liver_phi, liver_bounding_box(), cell); }

double implicit_volume(const std::function<double(const Eigen::Vector3d&)>& phi, const Eigen::AlignedBox3d& box, double cell) {
  if (!(cell > 0.0)) throw std::invalid_argument("implicit_volume: the grid cell must be positive");
  const Eigen::Vector3i cells = (box.sizes() / cell).array().ceil().cast<int>();
  const Eigen::Vector3d h = box.sizes().cwiseQuotient(cells.cast<double>());
  long inside = 0;
  for (int k = 0; k < cells.z(); ++k)
    for (int j = 0; j < cells.y(); ++j)
      for (int i = 0; i < cells.x(); ++i) {
        const Eigen::Vector3d midpoint = box.min() + h.cwiseProduct(Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5));
        if (phi(midpoint) < 0.0) ++inside;
      }
  return static_cast<double>(inside) * h.prod();
}

} // namespace kerf
