#include "kerf/cut/semi_progressive_cut.hpp"

#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <iterator>
#include <numeric>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

namespace kerf {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Segment = Kernel::Segment_3;
using Triangle = Kernel::Triangle_3;
using Primitive = CGAL::AABB_segment_primitive<Kernel, std::vector<Segment>::const_iterator>;
using AabbTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

Kernel::Point_3 to_cgal(const Eigen::Vector3d& x) { return {x[0], x[1], x[2]}; }

/// Compressed rows: the items of row r are items[start[r] .. start[r+1]).
struct Rows {
  std::vector<int> start, items;
  template <class Visit>
  void for_each(int r, Visit&& visit) const {
    for (int k = start[static_cast<std::size_t>(r)]; k < start[static_cast<std::size_t>(r) + 1]; ++k) visit(items[static_cast<std::size_t>(k)]);
  }
};

/// Rows from (row, item) pairs.
Rows make_rows(int num_rows, std::vector<std::pair<int, int>> pairs) {
  std::sort(pairs.begin(), pairs.end());
  Rows rows;
  rows.start.assign(static_cast<std::size_t>(num_rows) + 1, 0);
  for (const auto& [r, item] : pairs) ++rows.start[static_cast<std::size_t>(r) + 1];
  std::partial_sum(rows.start.begin(), rows.start.end(), rows.start.begin());
  rows.items.reserve(pairs.size());
  for (const auto& pair : pairs) rows.items.push_back(pair.second);
  return rows;
}

} // namespace

struct SemiProgressiveCut::Data {
  NodeMatrix nodes;
  std::vector<std::array<int, 4>> corners;      // #T: the corner nodes
  std::vector<std::array<int, 2>> edges;        // #E: the two nodes, smaller first
  std::vector<std::array<int, 6>> tet_edges;    // #T: the edge ids, in the order of tet_edge_corners
  Rows edge_tets, node_tets;                    // the tets around each edge, around each node
  std::vector<Segment> segments;                // #E, the tree's primitives
  AabbTree tree;

  std::vector<char> edge_crossed;               // #E
  std::vector<EdgeCrossing> crossing;           // #E, meaningful where edge_crossed
  std::vector<char> on_sheet;                   // #V
  std::vector<signed char> crossed_edge_count;  // #T
  std::vector<char> tet_crossed;                // #T
  std::vector<int> crossed_tets;
  int num_crossed_edges = 0, num_on_sheet = 0;

  /// The separation test of tet t (tet_corners_separated) on its edges' and corners' state.
  bool corners_separated(int t) const {
    const auto tt = static_cast<std::size_t>(t);
    std::array<bool, 6> crossed{};
    std::array<bool, 4> on{};
    for (std::size_t j = 0; j < 6; ++j) crossed[j] = edge_crossed[static_cast<std::size_t>(tet_edges[tt][j])] != 0;
    for (std::size_t a = 0; a < 4; ++a) on[a] = on_sheet[static_cast<std::size_t>(corners[tt][a])] != 0;
    return tet_corners_separated(crossed, on);
  }
};

SemiProgressiveCut::SemiProgressiveCut(const TetMesh& mesh) : data_(std::make_unique<Data>()) {
  if (mesh.nodes_per_tet() != 4 && mesh.nodes_per_tet() != 10)
    throw std::invalid_argument("SemiProgressiveCut: a Tet4 or Tet10 mesh is needed, not " + std::to_string(mesh.nodes_per_tet()) + " nodes per tet");
  Data& d = *data_;
  d.nodes = mesh.nodes;
  const int num_tets = static_cast<int>(mesh.num_tets());
  const int num_nodes = static_cast<int>(mesh.num_nodes());
  d.corners.resize(static_cast<std::size_t>(num_tets));
  for (int t = 0; t < num_tets; ++t)
    for (int a = 0; a < 4; ++a) d.corners[static_cast<std::size_t>(t)][static_cast<std::size_t>(a)] = mesh.tets(t, a);

  // The unique edges: sort the 6 #T (smaller node, larger node, tet, local edge) and number the runs.
  std::vector<std::tuple<int, int, int, int>> tet_edge_list;
  tet_edge_list.reserve(6 * static_cast<std::size_t>(num_tets));
  for (int t = 0; t < num_tets; ++t)
    for (int j = 0; j < 6; ++j) {
      const int a = mesh.tets(t, tet_edge_corners[j][0]), b = mesh.tets(t, tet_edge_corners[j][1]);
      tet_edge_list.emplace_back(std::min(a, b), std::max(a, b), t, j);
    }
  std::sort(tet_edge_list.begin(), tet_edge_list.end());
  d.tet_edges.resize(static_cast<std::size_t>(num_tets));
  std::vector<std::pair<int, int>> edge_tet_pairs, node_tet_pairs;
  for (const auto& [a, b, t, j] : tet_edge_list) {
    if (d.edges.empty() || d.edges.back() != std::array<int, 2>{a, b}) d.edges.push_back({a, b});
    const int e = static_cast<int>(d.edges.size()) - 1;
    d.tet_edges[static_cast<std::size_t>(t)][static_cast<std::size_t>(j)] = e;
    edge_tet_pairs.emplace_back(e, t);
  }
  for (int t = 0; t < num_tets; ++t)
    for (const int v : d.corners[static_cast<std::size_t>(t)]) node_tet_pairs.emplace_back(v, t);
  const int num_edges = static_cast<int>(d.edges.size());
  d.edge_tets = make_rows(num_edges, std::move(edge_tet_pairs));
  d.node_tets = make_rows(num_nodes, std::move(node_tet_pairs));

  d.segments.reserve(d.edges.size());
  for (const auto& [a, b] : d.edges) d.segments.emplace_back(to_cgal(mesh.nodes.row(a).transpose()), to_cgal(mesh.nodes.row(b).transpose()));
  // The tree refers to the segments through iterators: build it once they no longer move.
  d.tree.insert(d.segments.cbegin(), d.segments.cend());
  d.tree.build();

  d.edge_crossed.assign(d.edges.size(), 0);
  d.crossing.resize(d.edges.size());
  d.on_sheet.assign(static_cast<std::size_t>(num_nodes), 0);
  d.crossed_edge_count.assign(static_cast<std::size_t>(num_tets), 0);
  d.tet_crossed.assign(static_cast<std::size_t>(num_tets), 0);
}

SemiProgressiveCut::~SemiProgressiveCut() = default;
SemiProgressiveCut::SemiProgressiveCut(SemiProgressiveCut&&) noexcept = default;
SemiProgressiveCut& SemiProgressiveCut::operator=(SemiProgressiveCut&&) noexcept = default;

std::vector<int> SemiProgressiveCut::add_swept_triangles(const std::vector<SweptTriangle>& triangles) {
  Data& d = *data_;
  std::vector<int> new_edges, new_nodes;
  std::vector<Primitive::Id> candidates;
  for (const SweptTriangle& corners : triangles) {
    const Triangle triangle(to_cgal(corners[0]), to_cgal(corners[1]), to_cgal(corners[2]));
    if (triangle.is_degenerate()) continue; // swept_quad drops these; a collinear triangle has no side to cross to
    // The tree gives the edges whose boxes meet the triangle's box; the exact tests follow. (Asking
    // the tree with the triangle itself is exact too, but CGAL's triangle-box test falls back to
    // multiprecision so often on these long thin triangles that a call took 20 times longer.)
    candidates.clear();
    d.tree.all_intersected_primitives(triangle.bbox(), std::back_inserter(candidates));
    for (const Primitive::Id& id : candidates) {
      const int e = static_cast<int>(id - d.segments.cbegin());
      const std::array<int, 2> ends = d.edges[static_cast<std::size_t>(e)];
      const Eigen::Vector3d xa = d.nodes.row(ends[0]).transpose(), xb = d.nodes.row(ends[1]).transpose();
      const EdgeTriangleContact contact = edge_triangle_contact(corners, xa, xb);
      for (std::size_t k = 0; k < 2; ++k) {
        const auto v = static_cast<std::size_t>(ends[k]);
        if (!contact.end_on_sheet[k] || d.on_sheet[v]) continue;
        d.on_sheet[v] = 1;
        ++d.num_on_sheet;
        new_nodes.push_back(ends[k]);
      }
      // An edge is crossed once, where the sheet first met it (a trembling blade cannot move it).
      if (!contact.crossed || d.edge_crossed[static_cast<std::size_t>(e)]) continue;
      const double s = contact.parameter;
      d.edge_crossed[static_cast<std::size_t>(e)] = 1;
      d.crossing[static_cast<std::size_t>(e)] = {s, (1.0 - s) * xa + s * xb};
      ++d.num_crossed_edges;
      new_edges.push_back(e);
    }
  }

  // Only the tets around what changed can have become crossed.
  std::vector<int> affected;
  for (const int e : new_edges)
    d.edge_tets.for_each(e, [&](int t) {
      ++d.crossed_edge_count[static_cast<std::size_t>(t)];
      affected.push_back(t);
    });
  for (const int v : new_nodes) d.node_tets.for_each(v, [&](int t) { affected.push_back(t); });
  std::sort(affected.begin(), affected.end());
  affected.erase(std::unique(affected.begin(), affected.end()), affected.end());
  std::vector<int> newly_crossed;
  for (const int t : affected) {
    if (d.tet_crossed[static_cast<std::size_t>(t)] || !d.corners_separated(t)) continue;
    d.tet_crossed[static_cast<std::size_t>(t)] = 1;
    d.crossed_tets.push_back(t);
    newly_crossed.push_back(t);
  }
  return newly_crossed;
}

int SemiProgressiveCut::num_edges() const { return static_cast<int>(data_->edges.size()); }
std::array<int, 2> SemiProgressiveCut::edge_nodes(int e) const { return data_->edges.at(static_cast<std::size_t>(e)); }
std::array<int, 6> SemiProgressiveCut::tet_edges(int t) const { return data_->tet_edges.at(static_cast<std::size_t>(t)); }
bool SemiProgressiveCut::edge_crossed(int e) const { return data_->edge_crossed.at(static_cast<std::size_t>(e)) != 0; }

const EdgeCrossing& SemiProgressiveCut::edge_crossing(int e) const {
  if (!edge_crossed(e)) throw std::invalid_argument("SemiProgressiveCut::edge_crossing: edge " + std::to_string(e) + " is not crossed");
  return data_->crossing[static_cast<std::size_t>(e)];
}

int SemiProgressiveCut::num_crossed_edges(int t) const { return data_->crossed_edge_count.at(static_cast<std::size_t>(t)); }
bool SemiProgressiveCut::node_on_sheet(int v) const { return data_->on_sheet.at(static_cast<std::size_t>(v)) != 0; }
int SemiProgressiveCut::num_crossed_edges_total() const { return data_->num_crossed_edges; }
int SemiProgressiveCut::num_nodes_on_sheet() const { return data_->num_on_sheet; }
bool SemiProgressiveCut::tet_crossed(int t) const { return data_->tet_crossed.at(static_cast<std::size_t>(t)) != 0; }
const std::vector<int>& SemiProgressiveCut::crossed_tets() const { return data_->crossed_tets; }

std::vector<Eigen::Vector3d> SemiProgressiveCut::cut_points(int t) const {
  const Data& d = *data_;
  std::vector<Eigen::Vector3d> points;
  for (const int e : d.tet_edges.at(static_cast<std::size_t>(t)))
    if (d.edge_crossed[static_cast<std::size_t>(e)]) points.push_back(d.crossing[static_cast<std::size_t>(e)].point);
  for (const int v : d.corners[static_cast<std::size_t>(t)])
    if (d.on_sheet[static_cast<std::size_t>(v)]) points.push_back(d.nodes.row(v).transpose());
  return points;
}

} // namespace kerf
