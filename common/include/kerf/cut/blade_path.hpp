/// @file blade_path.hpp
/// @brief A scalpel's cutting edge moving in time: keyframes of a segment, and the edge at any time between them.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace kerf {

/// The blade as chapter 7 sees it: its cutting edge, a straight segment from `start` to `end` (m).
/// A real scalpel is a curved plate, but only the edge cuts: the sheet the edge sweeps is the cut
/// (Gutierrez and Ramos section 3.3 sweep a "collision quad" between two frames).
struct BladeEdge {
  Eigen::Vector3d start = Eigen::Vector3d::Zero(); ///< one end of the edge (m)
  Eigen::Vector3d end = Eigen::Vector3d::Zero();   ///< the other end (m)
};

/// Where the edge is at one instant of the path.
struct BladeKeyframe {
  double time = 0.0; ///< s
  BladeEdge edge;    ///< m
};

/// A blade path: keyframes in strictly increasing time, the edge interpolated linearly between
/// them (each end moves on a straight line from keyframe to keyframe, at constant speed).
class BladePath {
public:
  /// @param keyframes at least 2, in strictly increasing time, finite, each edge of non-zero length
  /// @throws std::invalid_argument with a one-line message naming what is wrong:
  ///   `BladePath: 1 keyframe given, at least 2 are needed`,
  ///   `BladePath: keyframe K has a non-finite time or position`,
  ///   `BladePath: keyframe K's time T s is not after keyframe K-1's (T' s)` (a repeated or backward time),
  ///   `BladePath: keyframe K's edge has zero length` (its two ends coincide).
  explicit BladePath(std::vector<BladeKeyframe> keyframes);

  /// The edge at `time` (s): linear between the two keyframes around it, the first keyframe's
  /// edge before the path starts and the last one's after it ends (the blade waits there).
  /// The interpolated edge may be shorter than either keyframe's (a blade that turns), never
  /// checked: the sweep of a short edge is just a narrow quad.
  BladeEdge edge_at(double time) const;

  double start_time() const { return keyframes_.front().time; }
  double end_time() const { return keyframes_.back().time; }
  /// end_time() - start_time() (s), positive.
  double duration() const { return end_time() - start_time(); }
  const std::vector<BladeKeyframe>& keyframes() const { return keyframes_; }

private:
  std::vector<BladeKeyframe> keyframes_;
};

} // namespace kerf
