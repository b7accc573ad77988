#include "kerf/cut/blade_path.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace kerf {

namespace {

[[noreturn]] void refuse(const std::string& what) { throw std::invalid_argument("BladePath: " + what); }

} // namespace

BladePath::BladePath(std::vector<BladeKeyframe> keyframes) : keyframes_(std::move(keyframes)) {
  if (keyframes_.size() < 2) {
    std::ostringstream message;
    message << keyframes_.size() << (keyframes_.size() == 1 ? " keyframe" : " keyframes") << " given, at least 2 are needed";
    refuse(message.str());
  }
  for (std::size_t k = 0; k < keyframes_.size(); ++k) {
    const BladeKeyframe& key = keyframes_[k];
    const auto at = [&](const std::string& what) { refuse("keyframe " + std::to_string(k) + what); };
    if (!std::isfinite(key.time) || !key.edge.start.allFinite() || !key.edge.end.allFinite()) at(" has a non-finite time or position");
    // Exact comparison on purpose: a repeated time would make the interpolation divide by zero,
    // and any positive step, however small, is a valid (if fast) motion.
    if (k > 0 && !(key.time > keyframes_[k - 1].time)) {
      std::ostringstream message;
      message << "'s time " << key.time << " s is not after keyframe " << k - 1 << "'s (" << keyframes_[k - 1].time << " s)";
      at(message.str());
    }
    if (key.edge.start == key.edge.end) at("'s edge has zero length");
  }
}

BladeEdge BladePath::edge_at(double time) const {
  if (time <= start_time()) return keyframes_.front().edge;
  if (time >= end_time()) return keyframes_.back().edge;
  // The first keyframe later than `time`; the one before it is at or before `time`.
  const auto after = std::upper_bound(keyframes_.begin(), keyframes_.end(), time,
                                      [](double t, const BladeKeyframe& key) { return t < key.time; });
  const BladeKeyframe& k1 = *after;
  const BladeKeyframe& k0 = *std::prev(after);
  const double s = (time - k0.time) / (k1.time - k0.time);
  return {(1.0 - s) * k0.edge.start + s * k1.edge.start, (1.0 - s) * k0.edge.end + s * k1.edge.end};
}

} // namespace kerf
