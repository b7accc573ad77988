#include "kerf/xfem/hinged_fragments.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cstddef>
#include <numeric>
#include <stdexcept>

namespace kerf {

namespace {

// Whether every component of DOF node d is prescribed.
bool is_held(const DofMap& dofs, int d) {
  for (int c = 0; c < 3; ++c)
    if (dofs.free_index[static_cast<std::size_t>(3 * d + c)] >= 0) return false;
  return true;
}

// Union-find over the DOF nodes, with path halving.
class Fragments {
public:
  explicit Fragments(int n) : parent_(static_cast<std::size_t>(n)) { std::iota(parent_.begin(), parent_.end(), 0); }
  int root(int x) {
    while (parent_[static_cast<std::size_t>(x)] != x) {
      parent_[static_cast<std::size_t>(x)] = parent_[static_cast<std::size_t>(parent_[static_cast<std::size_t>(x)])];
      x = parent_[static_cast<std::size_t>(x)];
    }
    return x;
  }
  void join(int a, int b) { parent_[static_cast<std::size_t>(root(a))] = root(b); }

private:
  std::vector<int> parent_;
};

// How many directions the points span about their mean: 0 (one point), 1 (a line), 2 or 3. A
// direction counts where the points spread along it by more than 1e-6 of their largest spread:
// three nodes of a mesh on one line span 1.
int affine_rank(const std::vector<Eigen::Vector3d>& points) {
  if (points.size() < 2) return 0;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& x : points) mean += x;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& x : points) scatter.noalias() += (x - mean) * (x - mean).transpose();
  // The spreads along the principal directions: the square roots of the scatter's eigenvalues,
  // in increasing order (two points span one direction: two of them are zero).
  const Eigen::Vector3d spread =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(scatter).eigenvalues().cwiseMax(0.0).cwiseSqrt();
  if (spread[2] == 0.0) return 0;
  return static_cast<int>((spread.array() > 1e-6 * spread[2]).count());
}

} // namespace

std::vector<HingedFragment> hinged_fragments(const CutXfemModel& model, const DofMap& dofs) {
  if (dofs.free_index.size() != static_cast<std::size_t>(3 * model.num_dof_nodes()))
    throw std::invalid_argument("hinged_fragments: the DofMap is not the model's");
  const TetMesh& mesh = model.mesh();
  const auto N = static_cast<int>(mesh.num_nodes());
  const int n = mesh.nodes_per_tet();
  std::vector<HingedFragment> hinged;
  // Only a held enrichment can pin a fragment at a node it does not contain, and only a gripped
  // node can hold a fragment that contains it: without either nothing is hinged.
  bool any_held = false;
  for (int d = 0; d < model.num_dof_nodes() && !any_held; ++d) any_held = is_held(dofs, d);
  if (!any_held) return hinged;

  // Fragments: the pieces joined where they share a phantom node, the same part of a node's
  // support (that part is connected, so its pieces in neighbouring tets share a face). A held
  // enrichment joins its part's pieces too; it does not join them to node i's home part, which it
  // only pins them to. A piece its rule gives no volume has no stiffness to join by.
  Fragments fragments(model.num_dof_nodes());
  std::vector<double> volumes; // of every integrated piece, tet by tet
  std::vector<int> corners;    // their phantom nodes, n a piece
  // A tet with no slot but its nodes' (most of them) is one piece whose phantom nodes are its
  // nodes: read from the mesh, without asking the model piece by piece.
  const TetMatrix& slots = model.assembly_slots();
  const auto plain = [&](Eigen::Index t) { return slots.cols() == n || slots(t, n) < 0; };
  volumes.reserve(static_cast<std::size_t>(mesh.num_tets()));
  corners.reserve(static_cast<std::size_t>(n * mesh.num_tets()));
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    for (int p = 0; p < model.num_integrated_pieces(t); ++p) {
      volumes.push_back(model.integrated_volume(t, p));
      for (int a = 0; a < n; ++a) corners.push_back(plain(t) ? mesh.tets(t, a) : model.phantom_node(t, p, a));
      if (!(volumes.back() > 0.0)) continue;
      const int* c = &corners[corners.size() - static_cast<std::size_t>(n)];
      for (int a = 1; a < n; ++a) fragments.join(c[a], c[0]);
    }

  // Each fragment's attachments: a held standard DOF node (a gripped node it contains: the
  // Dirichlet condition's own hold), or a held enrichment's node i, where the enrichment pins it
  // to u_i: to the world if u_i is held, to node i's home part if that lies in another fragment.
  struct Gathered {
    std::vector<int> attachments, held_enrichments;
    double volume = 0.0, largest = -1.0;
    Eigen::Index largest_tet = 0;
    bool seen = false, own = false;
  };
  std::vector<Gathered> gathered(static_cast<std::size_t>(model.num_dof_nodes()));
  std::vector<int> order; // fragments by their first piece
  const std::vector<int>& enrichment_node = model.enrichment().enrichment_node;
  std::size_t piece = 0;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    for (int p = 0; p < model.num_integrated_pieces(t); ++p) {
      const int* c = &corners[piece * static_cast<std::size_t>(n)];
      const double volume = volumes[piece++];
      if (!(volume > 0.0)) continue;
      const int f = fragments.root(c[0]);
      Gathered& g = gathered[static_cast<std::size_t>(f)];
      if (!g.seen) order.push_back(f);
      g.seen = true;
      g.volume += volume;
      if (volume > g.largest) {
        g.largest = volume;
        g.largest_tet = t;
      }
      for (int a = 0; a < n; ++a) {
        const int d = c[a];
        if (!is_held(dofs, d)) continue;
        if (d < N) {
          g.attachments.push_back(d);
          g.own = true;
          continue;
        }
        const int i = enrichment_node[static_cast<std::size_t>(d - N)];
        g.held_enrichments.push_back(d);
        if (is_held(dofs, i) || fragments.root(i) != f) g.attachments.push_back(i);
      }
    }

  for (const int f : order) {
    Gathered& g = gathered[static_cast<std::size_t>(f)];
    for (std::vector<int>* list : {&g.attachments, &g.held_enrichments}) {
      std::sort(list->begin(), list->end());
      list->erase(std::unique(list->begin(), list->end()), list->end());
    }
    if (g.attachments.empty()) continue; // free already: it falls
    std::vector<Eigen::Vector3d> points;
    for (const int v : g.attachments) points.emplace_back(mesh.nodes.row(v).transpose());
    if (affine_rank(points) >= 2) continue; // held across a plane: it cannot turn
    const Eigen::Vector3d point = tet_corners(mesh, g.largest_tet).colwise().mean().transpose();
    hinged.push_back({g.volume, point, g.attachments, g.held_enrichments, g.own});
  }
  return hinged;
}

DofMap release_hinged_fragments(const CutXfemModel& model, const DofMap& dofs,
                                std::vector<HingedFragment>* released) {
  DofMap out = dofs;
  if (released) released->clear();
  // Only a held enrichment pins a fragment that can be let go: without one there is nothing to
  // do, and nothing to look for (chapter 7's demo holds none but at its last few changes).
  bool pinned = false;
  for (int d = static_cast<int>(model.mesh().num_nodes()); d < model.num_dof_nodes() && !pinned; ++d)
    pinned = is_held(dofs, d);
  if (!pinned) return out;
  // Each round lets go of what pins the hinged fragments; a fragment pinned to one of them can
  // be left hinged by it, and each round frees at least one enrichment, so this ends.
  for (;;) {
    std::vector<int> free_now;
    for (HingedFragment& fragment : hinged_fragments(model, out)) {
      // Pinned by held enrichments only: let go. Held at a gripped node of its own: a hinge the
      // Dirichlet condition makes, which letting its pins go would not undo: kept whole.
      if (fragment.held_at_own_node) continue;
      free_now.insert(free_now.end(), fragment.held_enrichments.begin(), fragment.held_enrichments.end());
      if (released) released->push_back(std::move(fragment));
    }
    if (free_now.empty()) return out;
    for (const int d : free_now)
      for (int c = 0; c < 3; ++c) {
        out.free_index[static_cast<std::size_t>(3 * d + c)] = 0; // any index >= 0: renumbered below
        out.prescribed[3 * d + c] = 0.0;
      }
    out.num_free = 0;
    for (int& index : out.free_index)
      if (index >= 0) index = out.num_free++;
  }
}

} // namespace kerf
