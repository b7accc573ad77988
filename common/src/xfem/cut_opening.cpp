#include "kerf/xfem/cut_opening.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

namespace kerf {

Eigen::Vector3d CutOpeningSampler::PointWeights::value(const Eigen::VectorXd& u) const {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto& [node, weight] : terms) sum += weight * u.segment<3>(3 * node);
  return sum;
}

CutOpeningSampler::CutOpeningSampler(const CutXfemModel& model, const PointLocator& locator, const std::vector<TriangleSurface>& cuts,
                                     double spacing, double eps)
    : model_(model) {
  if (!(spacing > 0.0) || !std::isfinite(spacing)) throw std::invalid_argument("CutOpeningSampler: spacing must be positive and finite");
  if (!(eps > 0.0) || !std::isfinite(eps)) throw std::invalid_argument("CutOpeningSampler: eps must be positive and finite");
  // The weights of the field at X, on the piece of its tet that holds it; none outside the mesh.
  const auto weights_at = [&](const Eigen::Vector3d& X) -> std::optional<PointWeights> {
    const PointLocation where = locator.locate(X);
    if (where.tet < 0) return std::nullopt;
    const int p = model.piece_at(where.tet, X);
    if (p < 0) return std::nullopt;
    PointWeights weights;
    const Eigen::VectorXd N = model.shape_values(where.tet, X);
    // The phantom element's nodal value u_p,a = u_a + a_k (a_k: the enrichment active on p, if any).
    for (int a = 0; a < N.size(); ++a) {
      const int node = model.mesh().tets(where.tet, a), phantom = model.phantom_node(where.tet, p, a);
      weights.terms.emplace_back(node, N[a]);
      if (phantom != node) weights.terms.emplace_back(phantom, N[a]);
    }
    for (const auto& term : model.branch_values_at(where.tet, p, X)) weights.terms.push_back(term);
    return weights;
  };
  for (const TriangleSurface& cut : cuts) {
    for (Eigen::Index f = 0; f < cut.num_triangles(); ++f) {
      const Eigen::Vector3d a = cut.vertices.row(cut.triangles(f, 0)).transpose();
      const Eigen::Vector3d b = cut.vertices.row(cut.triangles(f, 1)).transpose();
      const Eigen::Vector3d c = cut.vertices.row(cut.triangles(f, 2)).transpose();
      const Eigen::Vector3d area_normal = 0.5 * (b - a).cross(c - a);
      const double area = area_normal.norm();
      if (!(area > 0.0)) continue; // a degenerate triangle has no normal and no area to count
      const Eigen::Vector3d n = area_normal / area;
      const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
      const int m = std::max(1, static_cast<int>(std::ceil(longest / spacing)));
      const Eigen::Vector3d step_ab = (b - a) / m, step_ac = (c - a) / m;
      // The m^2 sub-triangles: in row i, column j, the upright one (centroid at (i + 1/3, j + 1/3)
      // in steps) and, but in the last column, the inverted one at (i + 2/3, j + 2/3).
      for (int i = 0; i < m; ++i) {
        for (int j = 0; i + j < m; ++j) {
          for (const double shift : {1.0 / 3.0, 2.0 / 3.0}) {
            if (shift > 0.5 && i + j == m - 1) continue;
            const Eigen::Vector3d centroid = a + (i + shift) * step_ab + (j + shift) * step_ac;
            std::optional<PointWeights> above = weights_at(centroid + eps * n), below = weights_at(centroid - eps * n);
            if (above && below) samples_.push_back({area / (m * m), n, std::move(*above), std::move(*below)});
          }
        }
      }
    }
  }
}

CutOpening CutOpeningSampler::measure(const Eigen::VectorXd& u) const {
  if (u.size() != 3 * model_.num_dof_nodes()) throw std::invalid_argument("CutOpeningSampler::measure: u has the wrong size");
  CutOpening opening;
  for (const Sample& sample : samples_) {
    const Eigen::Vector3d jump = sample.above.value(u) - sample.below.value(u); // [[u]](c_s)
    const double normal_opening = jump.dot(sample.n);
    opening.area += sample.area;
    opening.gap_volume += sample.area * normal_opening; // the midpoint rule of V_gap
    opening.max_normal_opening = opening.samples == 0 ? normal_opening : std::max(opening.max_normal_opening, normal_opening);
    opening.max_jump = std::max(opening.max_jump, jump.norm());
    ++opening.samples;
  }
  return opening;
}

CutOpening measure_cut_opening(const CutXfemModel& model, const PointLocator& locator, const Eigen::VectorXd& u,
                               const std::vector<TriangleSurface>& cuts, double spacing, double eps) {
  return CutOpeningSampler(model, locator, cuts, spacing, eps).measure(u);
}

} // namespace kerf
