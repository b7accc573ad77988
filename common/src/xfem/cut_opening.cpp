#include "kerf/xfem/cut_opening.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace kerf {

Eigen::Vector3d CutOpeningSampler::value(const Eigen::VectorXd& u, std::size_t begin, std::size_t end) const {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t k = begin; k < end; ++k) sum += terms_[k].second * u.segment<3>(3 * terms_[k].first);
  return sum;
}

CutSamplePoints::CutSamplePoints(const PointLocator& locator, double spacing, double eps) : locator_(locator), spacing_(spacing), eps_(eps) {
  if (!(spacing > 0.0) || !std::isfinite(spacing)) throw std::invalid_argument("CutSamplePoints: spacing must be positive and finite");
  if (!(eps > 0.0) || !std::isfinite(eps)) throw std::invalid_argument("CutSamplePoints: eps must be positive and finite");
}

CutSamplePoints::SampledTriangle CutSamplePoints::sample_triangle(const Eigen::Matrix3d& corners) const {
  SampledTriangle sampled{corners, {}};
  const Eigen::Vector3d a = corners.row(0).transpose(), b = corners.row(1).transpose(), c = corners.row(2).transpose();
  const Eigen::Vector3d area_normal = 0.5 * (b - a).cross(c - a);
  const double area = area_normal.norm();
  if (!(area > 0.0)) return sampled; // a degenerate triangle has no normal and no area to count
  const Eigen::Vector3d n = area_normal / area;
  const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
  const int m = std::max(1, static_cast<int>(std::ceil(longest / spacing_)));
  const Eigen::Vector3d step_ab = (b - a) / m, step_ac = (c - a) / m;
  const auto located = [&](const Eigen::Vector3d& X) { return Located{X, locator_.locate(X).tet}; };
  // The m^2 sub-triangles: in row i, column j, the upright one (centroid at (i + 1/3, j + 1/3)
  // in steps) and, but in the last column, the inverted one at (i + 2/3, j + 2/3).
  for (int i = 0; i < m; ++i) {
    for (int j = 0; i + j < m; ++j) {
      for (const double shift : {1.0 / 3.0, 2.0 / 3.0}) {
        if (shift > 0.5 && i + j == m - 1) continue;
        const Eigen::Vector3d centroid = a + (i + shift) * step_ab + (j + shift) * step_ac;
        sampled.samples.push_back({area / (m * m), n, located(centroid + eps_ * n), located(centroid - eps_ * n)});
      }
    }
  }
  return sampled;
}

void CutSamplePoints::update(const std::vector<TriangleSurface>& cuts) {
  cuts_.resize(cuts.size());
  for (std::size_t k = 0; k < cuts.size(); ++k) {
    const TriangleSurface& cut = cuts[k];
    std::vector<SampledTriangle>& sampled = cuts_[k];
    sampled.resize(static_cast<std::size_t>(cut.num_triangles()));
    for (Eigen::Index f = 0; f < cut.num_triangles(); ++f) {
      Eigen::Matrix3d corners;
      for (int v = 0; v < 3; ++v) corners.row(v) = cut.vertices.row(cut.triangles(f, v));
      SampledTriangle& known = sampled[static_cast<std::size_t>(f)];
      if (known.corners != corners) known = sample_triangle(corners);
    }
  }
}

CutOpeningSampler::CutOpeningSampler(const CutXfemModel& model, const PointLocator& locator, const std::vector<TriangleSurface>& cuts,
                                     double spacing, double eps)
    : CutOpeningSampler(model, [&] {
        CutSamplePoints points(locator, spacing, eps);
        points.update(cuts);
        return points;
      }()) {}

CutOpeningSampler::CutOpeningSampler(const CutXfemModel& model, const CutSamplePoints& points) : model_(model) {
  // Appends the weights of the field at a point, on the piece of its tet that holds it; false
  // (and nothing appended) outside the mesh or outside every piece.
  const auto append_weights = [&](const CutSamplePoints::Located& at) {
    if (at.tet < 0) return false;
    const int p = model.piece_at(at.tet, at.X);
    if (p < 0) return false;
    const Eigen::VectorXd N = model.shape_values(at.tet, at.X);
    // The phantom element's nodal value u_p,a = u_a + a_k (a_k: the enrichment active on p, if any).
    for (int a = 0; a < N.size(); ++a) {
      const int node = model.mesh().tets(at.tet, a), phantom = model.phantom_node(at.tet, p, a);
      terms_.emplace_back(node, N[a]);
      if (phantom != node) terms_.emplace_back(phantom, N[a]);
    }
    for (const auto& term : model.branch_values_at(at.tet, p, at.X)) terms_.push_back(term);
    return true;
  };
  points.for_each_sample([&](const CutSamplePoints::Sample& sample) {
    const std::size_t above = terms_.size();
    if (!append_weights(sample.above)) return;
    const std::size_t below = terms_.size();
    if (!append_weights(sample.below)) {
      terms_.resize(above);
      return;
    }
    samples_.push_back({sample.area, sample.n, above, below, terms_.size()});
  });
}

CutOpening CutOpeningSampler::measure(const Eigen::VectorXd& u) const {
  if (u.size() != 3 * model_.num_dof_nodes()) throw std::invalid_argument("CutOpeningSampler::measure: u has the wrong size");
  CutOpening opening;
  for (const Sample& sample : samples_) {
    const Eigen::Vector3d jump = value(u, sample.above, sample.below) - value(u, sample.below, sample.end); // [[u]](c_s)
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
