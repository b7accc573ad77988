#include "kerf/cut/cut_sheet.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <stdexcept>

namespace kerf {

CutSheet::CutSheet(double quad_length) : quad_length_(quad_length) {
  if (!(quad_length > 0.0) || !std::isfinite(quad_length)) throw std::invalid_argument("CutSheet: quad_length must be a positive length");
}

std::vector<SweptTriangle> CutSheet::offer(const BladeEdge& edge, bool force) {
  if (edges_.empty()) {
    edges_.push_back(edge);
    return {};
  }
  const BladeEdge& last = edges_.back();
  const double moved = std::max((edge.start - last.start).norm(), (edge.end - last.end).norm());
  if (moved < quad_length_ && !(force && moved > 0.0)) return {};
  // The quad's normal: the edge's direction crossed with its mean motion (swept_quad.hpp's
  // orientation). Against the last quad's, the blade is going back over its own cut.
  const Eigen::Vector3d motion = 0.5 * (edge.start + edge.end - last.start - last.end);
  const Eigen::Vector3d normal = (last.end - last.start).cross(motion);
  if (last_normal_.dot(normal) < 0.0) {
    ++refused_;
    return {};
  }
  const std::vector<SweptTriangle> swept = swept_quad(last, edge);
  if (swept.empty()) return {};
  // swept_quad's corners are copies of a0, b0, a1, b1: number them as the strip's vertices.
  const int k = static_cast<int>(edges_.size()) - 1;
  const std::array<Eigen::Vector3d, 4> corners = {last.start, last.end, edge.start, edge.end};
  for (const SweptTriangle& triangle : swept) {
    Eigen::Vector3i indices;
    for (int c = 0; c < 3; ++c) {
      int found = -1;
      for (int q = 0; q < 4 && found < 0; ++q)
        if (triangle[static_cast<std::size_t>(c)] == corners[static_cast<std::size_t>(q)]) found = q;
      if (found < 0) throw std::logic_error("CutSheet: swept_quad returned a corner that is not an edge end");
      indices[c] = 2 * k + found;
    }
    triangles_.push_back(indices);
  }
  edges_.push_back(edge);
  last_normal_ = normal;
  return swept;
}

TriangleSurface CutSheet::surface() const {
  TriangleSurface s;
  s.vertices.resize(2 * static_cast<Eigen::Index>(edges_.size()), 3);
  for (std::size_t k = 0; k < edges_.size(); ++k) {
    s.vertices.row(2 * static_cast<Eigen::Index>(k)) = edges_[k].start.transpose();
    s.vertices.row(2 * static_cast<Eigen::Index>(k) + 1) = edges_[k].end.transpose();
  }
  s.triangles.resize(static_cast<Eigen::Index>(triangles_.size()), 3);
  for (std::size_t f = 0; f < triangles_.size(); ++f) s.triangles.row(static_cast<Eigen::Index>(f)) = triangles_[f].transpose();
  return s;
}

} // namespace kerf
