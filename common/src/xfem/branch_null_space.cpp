#include "kerf/xfem/branch_null_space.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <numeric>

namespace kerf {

namespace {

// Whether the fronts are one straight line: one polyline whose segments share one frame and lie
// on one line (the frame the model's polar coordinates use is then the same everywhere).
bool one_straight_front(const CrackFronts& fronts) {
  if (fronts.polylines.size() != 1) return false;
  const FrontPolyline& line = fronts.polylines[0];
  const FrontSegment& first = line.segments.front();
  const double length = (line.points.back() - line.points.front()).norm();
  for (const FrontSegment& s : line.segments)
    if ((s.a - first.a).norm() > 1e-12 || (s.b - first.b).norm() > 1e-12) return false;
  for (const Eigen::Vector3d& p : line.points)
    if ((p - line.points.front()).cross(first.c).norm() > 1e-12 * length) return false;
  return true;
}

int find_root(std::vector<int>& parent, int i) {
  while (parent[static_cast<std::size_t>(i)] != i) i = parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
  return i;
}

} // namespace

std::vector<BranchNullVector> branch_null_vectors(const CutXfemModel& model) {
  const CrackTipFunctions* tip = model.crack_tip();
  if (!tip || model.num_branch_nodes() == 0 || !one_straight_front(tip->fronts)) return {};
  const BranchEnrichment& branch = tip->enrichment;
  const TetMesh& mesh = model.mesh();
  // Regions: slots joined by the tets with branch functions they share; a region is closed when
  // every such tet has all four corners slotted.
  const int S = branch.num_branch_nodes();
  std::vector<int> parent(static_cast<std::size_t>(S));
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<int> open_tet_slots;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    if (!model.has_branch_functions(t)) continue;
    int first = -1;
    bool closed = true;
    for (int a = 0; a < 4; ++a) {
      const int k = branch.branch_slot[static_cast<std::size_t>(mesh.tets(t, a))];
      if (k < 0) {
        closed = false;
        continue;
      }
      if (first < 0) first = k;
      parent[static_cast<std::size_t>(find_root(parent, k))] = find_root(parent, first);
    }
    if (!closed && first >= 0) open_tet_slots.push_back(first);
  }
  std::vector<char> open(static_cast<std::size_t>(S), 0);
  for (const int k : open_tet_slots) open[static_cast<std::size_t>(find_root(parent, k))] = 1;

  const FrontSegment& frame = tip->fronts.polylines[0].segments.front();
  const Eigen::Vector3d origin = tip->fronts.polylines[0].points.front();
  std::vector<std::vector<int>> regions(static_cast<std::size_t>(S));
  for (int k = 0; k < S; ++k) regions[static_cast<std::size_t>(find_root(parent, k))].push_back(k);
  std::vector<BranchNullVector> result;
  for (int root = 0; root < S; ++root) {
    const std::vector<int>& slots = regions[static_cast<std::size_t>(root)];
    if (slots.empty() || open[static_cast<std::size_t>(root)]) continue;
    BranchNullVector n1, n2;
    for (const int k : slots) {
      const Eigen::Vector3d d = mesh.nodes.row(branch.branch_node[static_cast<std::size_t>(k)]).transpose() - origin;
      const double x_a = d.dot(frame.a), x_b = d.dot(frame.b);
      const int first = static_cast<int>(model.branch_dof_node(k));
      n1.coefficients.insert(n1.coefficients.end(), {{first, x_b}, {first + 2, x_a}, {first + 3, -x_b}});
      n2.coefficients.insert(n2.coefficients.end(), {{first + 1, x_b}, {first + 2, -x_b}, {first + 3, -x_a}});
    }
    result.push_back(std::move(n1));
    result.push_back(std::move(n2));
  }
  return result;
}

std::vector<int> branch_gauge_dof_nodes(const CutXfemModel& model, const DofMap& dofs) {
  std::vector<int> held;
  for (const BranchNullVector& n : branch_null_vectors(model)) {
    // Free: no DOF it moves is prescribed (a DOF node is free or prescribed as a whole).
    bool free = true;
    double largest = 0.0;
    int pivot = -1;
    for (const auto& [dof_node, c] : n.coefficients) {
      if (c == 0.0) continue;
      if (dofs.free_index[3 * static_cast<std::size_t>(dof_node)] < 0) free = false;
      // The pivot: function 1 or 2 (the vector's own, N_1 or N_2: offset 0 or 1 in its slot's four)
      // at the slot of largest |x_b|, which is that DOF's coefficient.
      const int offset = (dof_node - static_cast<int>(model.branch_dof_node(0))) % 4;
      if (offset <= 1 && std::abs(c) > largest) largest = std::abs(c), pivot = dof_node;
    }
    if (free && pivot >= 0) held.push_back(pivot);
  }
  return held;
}

} // namespace kerf
