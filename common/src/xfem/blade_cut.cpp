#include "kerf/xfem/blade_cut.hpp"

#include "kerf/app/input_error.hpp"

#include <cmath>
#include <stdexcept>

namespace kerf {

namespace {

double mean_edge_length(const TetMesh& mesh, const SemiProgressiveCut& crossing) {
  double length = 0.0;
  for (int e = 0; e < crossing.num_edges(); ++e) {
    const std::array<int, 2> ends = crossing.edge_nodes(e);
    length += (mesh.nodes.row(ends[0]) - mesh.nodes.row(ends[1])).norm();
  }
  return length / crossing.num_edges();
}

} // namespace

BladeCut::BladeCut(const TetMesh& mesh, double quad_length, int samples) : samples_(samples), crossing_(mesh) {
  if (samples < 2) throw std::invalid_argument("BladeCut: expected at least 2 samples along the edge");
  if (!(quad_length >= 0.0) || !std::isfinite(quad_length)) throw std::invalid_argument("BladeCut: expected a quad length >= 0");
  quad_length_ = quad_length > 0.0 ? quad_length : 0.25 * mean_edge_length(mesh, crossing_);
  grown_.setEmpty();
}

bool BladeCut::advance(const CutXfemModel& model, const PointLocator& locator, const Eigen::VectorXd& u, const BladeEdge* world, bool last) {
  if (!world) {
    sheet_open_ = false;
    outside_edge_.reset();
    return false;
  }
  const ReferenceBlade blade = pull_back_blade_edge(model, locator, u, *world, samples_, sheet_open_ ? &last_blade_ : nullptr, 1e-9);
  std::vector<SweptTriangle> added;
  if (!blade.in_tissue()) {
    if (sheet_open_) {
      const BladeEdge closing{last_blade_.anchor.map(world->start), last_blade_.anchor.map(world->end)};
      added = sheets_.back().offer(closing, true);
      sheet_open_ = false;
    }
    outside_edge_ = *world;
  } else {
    if (!sheet_open_) {
      sheets_.emplace_back(quad_length_);
      // Entering from outside: the sheet starts at the edge outside the skin. Put down in the
      // tissue (the window's press), it starts where the blade is: the anchor's map of this
      // frame's world edge is not its pull-back (they differ by the body's deformation, centimetres
      // in a sagging liver), and a first quad between them would point the cut a way the hand
      // never moved, and the sheet refuses quads that fold back against its first.
      if (outside_edge_) sheets_.back().offer({blade.anchor.map(outside_edge_->start), blade.anchor.map(outside_edge_->end)});
      else sheets_.back().offer(blade.edge);
      sheet_open_ = true;
    }
    added = sheets_.back().offer(blade.edge, last);
    last_blade_ = blade;
  }
  if (added.empty()) return false;
  for (const SweptTriangle& triangle : added)
    for (const Eigen::Vector3d& corner : triangle) grown_.extend(corner);
  return !crossing_.add_swept_triangles(added).empty();
}

std::vector<TriangleSurface> BladeCut::surfaces() const {
  std::vector<TriangleSurface> surfaces;
  for (const CutSheet& sheet : sheets_)
    if (sheet.num_triangles() > 0) surfaces.push_back(sheet.surface());
  return surfaces;
}

Eigen::AlignedBox3d BladeCut::take_grown_box() {
  const Eigen::AlignedBox3d box = grown_;
  grown_.setEmpty();
  return box;
}

void require_blade_starts_outside(const CutXfemModel& model, const PointLocator& locator, const BladePath& path, int samples,
                                  const std::string& file) {
  const Eigen::VectorXd at_rest = Eigen::VectorXd::Zero(3 * model.num_dof_nodes());
  const ReferenceBlade first = pull_back_blade_edge(model, locator, at_rest, path.edge_at(path.start_time()), samples, nullptr, 1e-9);
  if (first.in_tissue())
    throw InputError(file, "blade.path",
                     "the blade's edge starts inside the body (" + std::to_string(first.samples_inside) + " of " + std::to_string(samples) +
                         " samples): start it outside, so that the cut opens through the skin");
}

} // namespace kerf
