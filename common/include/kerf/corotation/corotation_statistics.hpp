/// @file corotation_statistics.hpp
/// @brief What one assembly of a corotated body saw: inverted points, Higham failures, singular rotation derivatives.
#pragma once

#include "kerf/corotation/polar_decomposition.hpp"

#include <Eigen/Core>
#include <Eigen/LU>
#include <algorithm>

namespace kerf {

/// Counts over the rotation points of one assembly (a Tet4 or a piece of a cut Tet4 is one
/// point, a Tet10 has four).
struct CorotationStatistics {
  int inverted_points = 0;        ///< rotation points with det F <= 0
  double inverted_volume = 0.0;   ///< the volume (m^3) those points stand for: a tiny piece counts little
  int higham_failures = 0;        ///< points where Higham's iteration gave no rotation (also when the SVD then stood in)
  int max_higham_iterations = 0;  ///< the most Newton steps Higham's iteration took
  int dropped_rotation_terms = 0; ///< consistent-tangent points where tr(S) I - S was singular, so dR/dx was left out

  /// Counts one rotation point: its deformation gradient F, the rotation found for it, and the
  /// volume it stands for.
  void record(const PolarDecomposition& polar, const Eigen::Matrix3d& F, double volume) {
    if (F.determinant() <= 0.0) {
      ++inverted_points;
      inverted_volume += volume;
    }
    if (polar.higham_failed) ++higham_failures;
    max_higham_iterations = std::max(max_higham_iterations, polar.iterations);
  }
};

} // namespace kerf
