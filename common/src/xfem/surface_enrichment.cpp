#include "kerf/xfem/surface_enrichment.hpp"

#include <algorithm>
#include <numeric>

namespace kerf {

namespace {

int find_root(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// The pieces of tet t that hold its local node a: for a corner, the pieces whose closure holds
// it (exact: corners are never moved); for a Tet10 mid-edge node, the pieces holding the edge's
// midpoint (a point of the tet, located with a tolerance of 1e-12 of the edge).
std::vector<int> pieces_at_node(const TetMesh& mesh, const MeshPieces& pieces, Eigen::Index t, int a) {
  const int e = pieces.entry[static_cast<std::size_t>(t)];
  if (e < 0) return {0};
  const TetPieces& tet = pieces.tets[static_cast<std::size_t>(e)];
  if (a < 4) return tet.corner_pieces[static_cast<std::size_t>(a)];
  const int i = tet_edge_corners[a - 4][0], j = tet_edge_corners[a - 4][1];
  const Eigen::Vector3d xi = mesh.nodes.row(mesh.tets(t, i)).transpose();
  const Eigen::Vector3d xj = mesh.nodes.row(mesh.tets(t, j)).transpose();
  return pieces_containing(tet, mesh.nodes.row(mesh.tets(t, a)).transpose(), 1e-12 * (xi - xj).norm());
}

// Whether piece p of tet t lies above a cut somewhere on its boundary.
bool piece_above_a_cut(const MeshPieces& pieces, Eigen::Index t, int p) {
  const int e = pieces.entry[static_cast<std::size_t>(t)];
  if (e < 0) return false;
  for (const PieceBoundaryPolygon& b : pieces.tets[static_cast<std::size_t>(e)].pieces[static_cast<std::size_t>(p)].boundary)
    if (b.on_cut && b.cut_side > 0) return true;
  return false;
}

} // namespace

SurfaceEnrichment make_surface_enrichment(const TetMesh& mesh, const MeshPieces& pieces) {
  SurfaceEnrichment result;
  const Eigen::Index V = mesh.num_nodes();
  const int n = mesh.nodes_per_tet();
  result.first_enrichment.assign(static_cast<std::size_t>(V) + 1, 0);
  result.active.assign(static_cast<std::size_t>(mesh.num_tets()), {});

  // Only a node of a tet that a cut meets can have a support in several parts.
  std::vector<char> candidate(static_cast<std::size_t>(V), 0);
  for (const int t : pieces.entry_tet)
    for (int a = 0; a < n; ++a) candidate[static_cast<std::size_t>(mesh.tets(t, a))] = 1;

  for (Eigen::Index i = 0; i < V; ++i) {
    result.first_enrichment[static_cast<std::size_t>(i) + 1] = result.first_enrichment[static_cast<std::size_t>(i)];
    if (!candidate[static_cast<std::size_t>(i)]) continue;
    const std::vector<int>& support = pieces.neighbours->node_tets[static_cast<std::size_t>(i)];
    // Local numbering of the support's pieces: tet support[s] has pieces offset[s] ...
    std::vector<int> offset(support.size() + 1, 0);
    for (std::size_t s = 0; s < support.size(); ++s) offset[s + 1] = offset[s] + pieces.num_pieces(support[s]);
    std::vector<int> parent(static_cast<std::size_t>(offset.back()));
    std::iota(parent.begin(), parent.end(), 0);
    for (std::size_t s = 0; s < support.size(); ++s)
      for (int a = 0; a < 4; ++a) {
        const int other = pieces.neighbours->across(support[s], a);
        // Glue within the support only: a path round through tets outside it does not count.
        const auto where = std::lower_bound(support.begin(), support.end(), other);
        if (other < support[s] || where == support.end() || *where != other) continue;
        const std::size_t o = static_cast<std::size_t>(where - support.begin());
        for (const PieceGlue& g : pieces.glued_across(support[s], a))
          parent[find_root(parent, offset[s] + g.piece_a)] = find_root(parent, offset[o] + g.piece_b);
      }
    // The parts, numbered by their lowest piece.
    std::vector<int> part(parent.size(), -1), root_part(parent.size(), -1);
    int parts = 0;
    for (std::size_t q = 0; q < parent.size(); ++q) {
      const int r = find_root(parent, static_cast<int>(q));
      if (root_part[r] < 0) root_part[r] = parts++;
      part[q] = root_part[r];
    }
    if (parts < 2) continue;

    // The home part: where the node is; above the cut when the node lies on one.
    int home = -1, home_above = -1;
    for (std::size_t s = 0; s < support.size(); ++s) {
      const int t = support[s];
      int a = 0;
      while (mesh.tets(t, a) != i) ++a;
      for (const int p : pieces_at_node(mesh, pieces, t, a)) {
        const int c = part[static_cast<std::size_t>(offset[s] + p)];
        if (home < 0 || c < home) home = c;
        if (piece_above_a_cut(pieces, t, p) && (home_above < 0 || c < home_above)) home_above = c;
      }
    }
    bool on_cut = false;
    for (std::size_t s = 0; s < support.size() && !on_cut; ++s) {
      const int t = support[s];
      int a = 0;
      while (mesh.tets(t, a) != i) ++a;
      for (const int p : pieces_at_node(mesh, pieces, t, a)) on_cut = on_cut || part[static_cast<std::size_t>(offset[s] + p)] != home;
    }
    if (on_cut && home_above >= 0) home = home_above;
    if (home < 0) home = 0; // a mid-edge node the point location missed: any part serves

    // One enrichment per part other than home, in the order of the parts.
    const int first = result.first_enrichment[static_cast<std::size_t>(i)];
    std::vector<int> enrichment_of_part(static_cast<std::size_t>(parts), -1);
    for (int c = 0, k = first; c < parts; ++c)
      if (c != home) {
        enrichment_of_part[static_cast<std::size_t>(c)] = k++;
        result.enrichment_node.push_back(static_cast<int>(i));
      }
    result.first_enrichment[static_cast<std::size_t>(i) + 1] = first + parts - 1;
    ++result.enriched_nodes;
    result.most_enrichments = std::max(result.most_enrichments, parts - 1);
    for (std::size_t s = 0; s < support.size(); ++s) {
      const int t = support[s];
      const int np = pieces.num_pieces(t);
      std::vector<int>& list = result.active[static_cast<std::size_t>(t)];
      if (list.empty()) list.assign(static_cast<std::size_t>(n * np), -1);
      int a = 0;
      while (mesh.tets(t, a) != i) ++a;
      for (int p = 0; p < np; ++p)
        list[static_cast<std::size_t>(a * np + p)] = enrichment_of_part[static_cast<std::size_t>(part[static_cast<std::size_t>(offset[s] + p)])];
    }
  }
  return result;
}

} // namespace kerf
