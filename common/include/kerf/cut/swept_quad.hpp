/// @file swept_quad.hpp
/// @brief The sheet a blade's edge sweeps between two instants: the quad (a0, b0, b1, a1) as two triangles.
#pragma once

#include "kerf/cut/blade_path.hpp"

#include <Eigen/Core>
#include <array>
#include <vector>

namespace kerf {

/// One flat triangle of a swept sheet, corners in order (m).
using SweptTriangle = std::array<Eigen::Vector3d, 3>;

/// The surface the edge sweeps from `from` = (a0, b0) to `to` = (a1, b1): Gutierrez and Ramos's
/// "collision quad" (section 3.3), with each end of the edge moving on a straight line.
///
/// The quad (a0, b0, b1, a1) is in general not planar (a blade that turns while it moves), so we
/// split it along the diagonal a0-b1 into the triangles (a0, b0, b1) and (a0, b1, a1). Both are
/// oriented alike: for a blade that translates by d, each normal (x1 - x0) x (x2 - x0) is
/// (b0 - a0) x d, the edge's direction crossed with the motion. A triangle of zero area (its
/// corners collinear, decided exactly by CGAL's predicate) is dropped: a blade that does not move,
/// or slides along its own line, sweeps nothing; one that pivots about an end sweeps one triangle.
/// @return 0, 1 or 2 triangles
std::vector<SweptTriangle> swept_quad(const BladeEdge& from, const BladeEdge& to);

} // namespace kerf
