// The random cut of one tet that the pieces' property tests share: tet corners and the fan's
// centre on multiples of 1/8, its rim offset by multiples of 1/16, so that cuts through
// corners, along edges and in faces happen all the time. The surface is a fan of 2-5 triangles round a centre, its rim about 3
// away (a wavy disc with a slit where the fan does not close: a manifold, consistently
// oriented, that cuts some tets completely and some partially).
#pragma once

#include "kerf/cut/tet_pieces.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <optional>
#include <random>
#include <vector>

namespace random_fan {

struct Case {
  Eigen::Matrix<double, 4, 3> X;         // the tet's corners
  Eigen::Vector3d centre;                // the fan's centre
  std::vector<Eigen::Vector3d> rim;      // its rim, in order; no triangle joins the last to the first
  std::vector<kerf::CutTriangle> surface; // the fan's triangles (centre, rim k, rim k + 1)
};

// The next case drawn from `random`, or nothing for a tet of volume below 1e-3 (its draws are
// used all the same, so that a sequence of calls is reproducible).
inline std::optional<Case> next(std::mt19937& random) {
  std::uniform_int_distribution<int> grid(-4, 8);
  const auto on_grid = [&]() {
    Eigen::Vector3d x;
    for (int c = 0; c < 3; ++c) x[c] = 0.25 * grid(random);
    return x;
  };
  Case c;
  for (int i = 0; i < 4; ++i) c.X.row(i) = (on_grid() * 0.5).transpose();
  const double volume = (c.X.row(1) - c.X.row(0)).cross(c.X.row(2) - c.X.row(0)).dot(c.X.row(3) - c.X.row(0)) / 6.0;
  if (std::abs(volume) < 1e-3) return std::nullopt;
  c.centre = on_grid() * 0.5;
  std::uniform_int_distribution<int> spokes(3, 6);
  const int n = spokes(random);
  for (int k = 0; k < n; ++k) {
    const double angle = 2.0 * M_PI * k / n;
    c.rim.emplace_back(c.centre + 3.0 * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0.0) + on_grid() * 0.25);
  }
  for (int k = 0; k + 1 < n; ++k) {
    const Eigen::Vector3d& a = c.rim[static_cast<std::size_t>(k)];
    const Eigen::Vector3d& b = c.rim[static_cast<std::size_t>(k + 1)];
    if ((a - c.centre).cross(b - c.centre).norm() < 1e-9) continue;
    c.surface.push_back({{c.centre, a, b}, 0, k});
  }
  return c;
}

} // namespace random_fan
