/// @file cut_sheet.hpp
/// @brief The cut a moving blade leaves, in the reference configuration: a strip of quads between the blade edges it recorded.
///
/// Every frame the blade's edge, pulled back into the reference configuration
/// (xfem/blade_pull_back.hpp), is offered to the sheet. The sheet keeps an edge only when the
/// blade has moved far enough since the last kept one: Gutierrez and Ramos (section 3.3) grow
/// their "collision quad" only when it exceeds "a value specified by a constant", and find
/// "better responses if the size of this quad is approximated to the average sizes of the
/// elements". Fewer, larger quads give the clipping of chapter 4 fewer triangles per tet; the
/// price is a delay of at most one quad before the cut reaches a tet.
///
/// Between two kept edges (a0, b0) and (a1, b1) the sheet gains swept_quad's two triangles, so the
/// sheet is a strip of consistently oriented triangles sharing their vertices: one cut surface for
/// chapter 4, whose front (chapter 5) is its boundary inside the body, the path of the blade's
/// inner end and its last edge.
///
/// A blade that turns back would fold the strip onto itself (two triangles over each other with
/// opposite normals, which no cut surface may have). So a quad whose normal points against the
/// last kept quad's is refused: a blade that trembles back over its own cut adds nothing, and the
/// sheet grows again once the blade moves forward past its last edge. The cost of the rule: a path
/// that reverses to cut a second way through the same plane cuts nothing new on the way back.
#pragma once

#include "kerf/cut/blade_path.hpp"
#include "kerf/cut/swept_quad.hpp"
#include "kerf/mesh/triangle_surface.hpp"

#include <Eigen/Core>
#include <vector>

namespace kerf {

/// One strip of cut, grown edge by edge.
class CutSheet {
public:
  /// @param quad_length how far (m) an end of the edge must move from the last kept edge before
  ///        the next one is kept; > 0
  /// @throws std::invalid_argument for quad_length <= 0 or not finite
  explicit CutSheet(double quad_length);

  /// Offers the blade's edge (reference configuration, m). The first edge starts the sheet; a
  /// later one is kept when an end has moved at least quad_length from the last kept edge (or
  /// `force`: the blade leaves the body, or the path ends) and the quad does not fold back.
  /// @return the triangles the sheet gained (0, 1 or 2), as swept_quad gives them
  std::vector<SweptTriangle> offer(const BladeEdge& edge, bool force = false);

  /// Whether no edge has been kept.
  bool empty() const { return edges_.empty(); }
  /// The number of edges kept.
  int num_edges() const { return static_cast<int>(edges_.size()); }
  /// The last edge kept (only for a non-empty sheet).
  const BladeEdge& last_edge() const { return edges_.back(); }
  /// The number of triangles so far.
  int num_triangles() const { return static_cast<int>(triangles_.size()); }
  /// How many offered quads were refused because they fold back.
  int num_refused() const { return refused_; }
  /// The sheet as a triangle surface: vertex 2 k is edge k's start, 2 k + 1 its end.
  TriangleSurface surface() const;

private:
  double quad_length_;
  std::vector<BladeEdge> edges_;
  std::vector<Eigen::Vector3i> triangles_;
  Eigen::Vector3d last_normal_ = Eigen::Vector3d::Zero(); // of the last quad kept (0: none yet)
  int refused_ = 0;
};

} // namespace kerf
