#include "kerf/xfem/blade_pull_back.hpp"

#include "kerf/xfem/pull_back.hpp"

#include <Eigen/LU>
#include <array>
#include <stdexcept>

namespace kerf {

ReferenceBlade pull_back_blade_edge(const CutXfemModel& model, const PointLocator& locator, const Eigen::VectorXd& u, const BladeEdge& world,
                                    int samples, const ReferenceBlade* previous, double tolerance) {
  if (samples < 2) throw std::invalid_argument("pull_back_blade_edge: at least 2 samples");
  ReferenceBlade result;
  result.samples.resize(static_cast<std::size_t>(samples));
  result.inside.assign(static_cast<std::size_t>(samples), 0);
  std::vector<Eigen::Vector3d> x(static_cast<std::size_t>(samples));
  std::vector<Eigen::Index> tet(static_cast<std::size_t>(samples), -1);
  const bool warm = previous && static_cast<int>(previous->samples.size()) == samples;
  for (int s = 0; s < samples; ++s) {
    const double lambda = static_cast<double>(s) / (samples - 1);
    x[static_cast<std::size_t>(s)] = (1.0 - lambda) * world.start + lambda * world.end;
    // Guesses: the sample's reference point a frame ago (the blade moves little per frame),
    // else the world point itself (right for small displacements).
    const Eigen::Vector3d guess = warm && previous->inside[static_cast<std::size_t>(s)] ? previous->samples[static_cast<std::size_t>(s)]
                                                                                        : x[static_cast<std::size_t>(s)];
    PullBack back = pull_back_to_reference(model, locator, u, x[static_cast<std::size_t>(s)], guess, tolerance);
    if (!back.converged && guess != x[static_cast<std::size_t>(s)])
      back = pull_back_to_reference(model, locator, u, x[static_cast<std::size_t>(s)], x[static_cast<std::size_t>(s)], tolerance);
    if (back.converged) {
      result.samples[static_cast<std::size_t>(s)] = back.reference;
      result.inside[static_cast<std::size_t>(s)] = 1;
      tet[static_cast<std::size_t>(s)] = back.tet;
      ++result.samples_inside;
    }
  }
  // A sample whose guess failed may still be in the tissue: where the body has moved further
  // than the sample lies from its surface, the world point is outside the reference mesh (no
  // tet to start Newton in), or Newton leaves the mesh from it. A neighbour along the edge that
  // did pull back is a guess as close as the last frame's, so retry from it, until no sample is
  // added (each sample tries each neighbour once).
  std::vector<std::array<char, 2>> tried(static_cast<std::size_t>(samples), {0, 0});
  for (bool added = result.in_tissue(); added;) {
    added = false;
    for (int s = 0; s < samples; ++s) {
      const auto i = static_cast<std::size_t>(s);
      for (int side = 0; side < 2 && !result.inside[i]; ++side) {
        const int n = side == 0 ? s - 1 : s + 1;
        if (n < 0 || n >= samples || !result.inside[static_cast<std::size_t>(n)] || tried[i][static_cast<std::size_t>(side)]) continue;
        tried[i][static_cast<std::size_t>(side)] = 1;
        const PullBack back = pull_back_to_reference(model, locator, u, x[i], result.samples[static_cast<std::size_t>(n)], tolerance);
        if (!back.converged) continue;
        result.samples[i] = back.reference;
        result.inside[i] = 1;
        tet[i] = back.tet;
        ++result.samples_inside;
        added = true;
      }
    }
  }
  if (!result.in_tissue()) {
    for (int s = 0; s < samples; ++s) result.samples[static_cast<std::size_t>(s)] = x[static_cast<std::size_t>(s)];
    return result;
  }
  const auto anchor_at = [&](int s) {
    BladeAnchor anchor;
    anchor.world = x[static_cast<std::size_t>(s)];
    anchor.reference = result.samples[static_cast<std::size_t>(s)];
    const Eigen::Matrix3d F = Eigen::Matrix3d::Identity() + model.displacement_gradient_at(u, tet[static_cast<std::size_t>(s)], anchor.reference);
    anchor.inverse_gradient = F.inverse();
    return anchor;
  };
  std::vector<int> in;
  for (int s = 0; s < samples; ++s)
    if (result.inside[static_cast<std::size_t>(s)]) in.push_back(s);
  const BladeAnchor first = anchor_at(in.front()), last = anchor_at(in.back());
  result.anchor = anchor_at(in[in.size() / 2]);
  // Outside samples: extended from the nearest inside one along the edge.
  for (int s = 0; s < samples; ++s)
    if (!result.inside[static_cast<std::size_t>(s)])
      result.samples[static_cast<std::size_t>(s)] = (s < in.front() ? first : last).map(x[static_cast<std::size_t>(s)]);
  result.edge.start = result.samples.front();
  result.edge.end = result.samples.back();
  return result;
}

} // namespace kerf
