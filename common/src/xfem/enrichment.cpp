#include "kerf/xfem/enrichment.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

namespace kerf {

namespace {

Eigen::Vector4d corner_values(const TetMesh& mesh, const LevelSet& level_set, Eigen::Index t) {
  Eigen::Vector4d lambda;
  for (int a = 0; a < 4; ++a) lambda[a] = level_set.lambda[mesh.tets(t, a)];
  return lambda;
}

/// Whether the rectangle (not only its plane) reaches into tet t: partially or completely cut.
bool cut_by_rectangle(ElementCutState state) {
  return state == ElementCutState::partially_cut || state == ElementCutState::completely_cut;
}

/// The length of the shortest mesh edge at every node.
std::vector<double> shortest_edge_at_nodes(const TetMesh& mesh) {
  std::vector<double> shortest(static_cast<std::size_t>(mesh.num_nodes()), std::numeric_limits<double>::infinity());
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    for (const auto& edge : tet_edge_corners) {
      const int p = mesh.tets(t, edge[0]), q = mesh.tets(t, edge[1]);
      const double length = (mesh.nodes.row(p) - mesh.nodes.row(q)).norm();
      for (const int v : {p, q}) shortest[static_cast<std::size_t>(v)] = std::min(shortest[static_cast<std::size_t>(v)], length);
    }
  return shortest;
}

/// Step 1, the minimum-fraction rule: moves onto the cut the corners on the small side of every
/// tet whose smaller piece is below the threshold, until no such tet is left, unless a corner
/// would move further than the settings allow: then that tet keeps its sliver. Moving a corner
/// only ever sets a value to 0, so this ends after at most #V rounds (in practice one or two).
void snap_small_pieces(const TetMesh& mesh, const RectangleCut& cut, const EnrichmentSettings& settings, Enrichment& e) {
  const std::vector<double> shortest_edge = shortest_edge_at_nodes(mesh);
  std::vector<char> kept(static_cast<std::size_t>(mesh.num_tets()), 0);
  for (bool changed = true; changed;) {
    changed = false;
    const MeshCutClassification classes = classify_mesh_cut(mesh, e.level_set, cut);
    for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
      const auto k = static_cast<std::size_t>(t);
      if (!is_cut(classes.tet_case[k]) || !cut_by_rectangle(classes.state[k])) continue;
      const Eigen::Vector4d lambda = corner_values(mesh, e.level_set, t);
      const ClippedTet clipped = clip_tet(tet_corners(mesh, t), lambda);
      const double fraction_a = clipped.V_a / (clipped.V_a + clipped.V_b);
      if (minimum_volume_fraction_met(fraction_a, 1.0 - fraction_a, settings.minimum_volume_fraction)) continue;
      const int small_side = fraction_a < 0.5 ? 1 : -1;
      bool within_limit = true;
      for (int a = 0; a < 4; ++a)
        if (level_set_sign(lambda[a]) == small_side)
          within_limit = within_limit && std::abs(lambda[a]) <= settings.maximum_snap_fraction *
                                                                   shortest_edge[static_cast<std::size_t>(mesh.tets(t, a))];
      if (!within_limit) {
        kept[k] = 1;
        continue;
      }
      for (int a = 0; a < 4; ++a)
        if (level_set_sign(lambda[a]) == small_side) {
          const int v = mesh.tets(t, a);
          e.largest_snap = std::max(e.largest_snap, std::abs(e.level_set.lambda[v]));
          e.level_set.lambda[v] = 0.0;
          e.level_set.sign[v] = 0;
          e.snapped.push_back(v);
          changed = true;
        }
    }
  }
  std::sort(e.snapped.begin(), e.snapped.end());
  e.snapped_nodes = static_cast<int>(e.snapped.size());
  e.kept_slivers = static_cast<int>(std::count(kept.begin(), kept.end(), 1));
}

/// Step 2: the side of every node, H_i (eqs. 58-59: a node on the cut counts as above, but a
/// snapped node keeps the side it came from).
void assign_node_signs(const TetMesh& mesh, const LevelSet& original, Enrichment& e) {
  e.node_sign.resize(static_cast<std::size_t>(mesh.num_nodes()));
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) e.node_sign[static_cast<std::size_t>(v)] = e.level_set.lambda[v] >= 0.0 ? 1 : -1;
  for (const int v : e.snapped) e.node_sign[static_cast<std::size_t>(v)] = original.lambda[v] >= 0.0 ? 1 : -1;
}

/// Step 3: the side of every tet, and its pieces and fractions when the cut splits it.
void split_tets(const TetMesh& mesh, Enrichment& e) {
  const auto num_tets = static_cast<std::size_t>(mesh.num_tets());
  e.tet_side.resize(num_tets);
  e.fraction_above.resize(num_tets);
  e.pieces.resize(num_tets);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const auto k = static_cast<std::size_t>(t);
    const Eigen::Vector4d lambda = corner_values(mesh, e.level_set, t);
    if (is_cut(e.classification.tet_case[k])) {
      if (!cut_by_rectangle(e.classification.state[k])) {
        e.tet_side[k] = TetSide::beyond;
        e.fraction_above[k] = std::numeric_limits<double>::quiet_NaN(); // no sides: see TetSide::beyond
        continue;
      }
      e.pieces[k] = clip_tet(tet_corners(mesh, t), lambda);
      e.tet_side[k] = TetSide::cut;
      e.fraction_above[k] = e.pieces[k].V_a / (e.pieces[k].V_a + e.pieces[k].V_b);
      ++e.cut_tets;
    } else {
      // One side only; a tet with all corners on the plane counts as above, as in clip_tet().
      const bool below = lambda.minCoeff() < 0.0;
      e.tet_side[k] = below ? TetSide::below : TetSide::above;
      e.fraction_above[k] = below ? 0.0 : 1.0;
    }
  }
}

/// Rule 1: the nodes of tets beyond the front.
std::vector<char> nodes_touching_beyond(const TetMesh& mesh, const Enrichment& e) {
  std::vector<char> touches(static_cast<std::size_t>(mesh.num_nodes()), 0);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    if (e.tet_side[static_cast<std::size_t>(t)] == TetSide::beyond)
      for (int a = 0; a < 4; ++a) touches[static_cast<std::size_t>(mesh.tets(t, a))] = 1;
  return touches;
}

/// Rule 2: the nodes of faces that lie in the cut plane between a tet above and a tet below (the
/// cut runs along them) but not inside the rectangle.
std::vector<char> nodes_on_plane_faces_outside_rectangle(const TetMesh& mesh, const RectangleCut& cut, const Enrichment& e) {
  std::map<std::array<int, 3>, std::vector<int>> plane_faces;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    for (const auto& corners : tet_outward_face_corners) {
      std::array<int, 3> face{mesh.tets(t, corners[0]), mesh.tets(t, corners[1]), mesh.tets(t, corners[2])};
      if (std::all_of(face.begin(), face.end(), [&](int v) { return e.level_set.lambda[v] == 0.0; })) {
        std::sort(face.begin(), face.end());
        plane_faces[face].push_back(static_cast<int>(t));
      }
    }
  std::vector<char> outside(static_cast<std::size_t>(mesh.num_nodes()), 0);
  const double tolerance = e.level_set.snap_tolerance;
  for (const auto& [face, tets] : plane_faces) {
    if (tets.size() != 2) continue; // a boundary face: no material on the other side, no jump
    if (e.tet_side[static_cast<std::size_t>(tets[0])] == e.tet_side[static_cast<std::size_t>(tets[1])]) continue;
    const bool inside = std::all_of(face.begin(), face.end(), [&](int v) {
      return cut.contains_projection(mesh.nodes.row(v).transpose(), tolerance);
    });
    if (!inside)
      for (int v : face) outside[static_cast<std::size_t>(v)] = 1;
  }
  return outside;
}

/// Rule 3: whether the tets around each node hold volume on both sides (beyond tets have no
/// sides and are left out; rule 1 excludes their nodes anyway).
std::vector<char> nodes_with_volume_on_both_sides(const TetMesh& mesh, const Enrichment& e) {
  std::vector<double> above(static_cast<std::size_t>(mesh.num_nodes()), 0.0), below(above);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    if (e.tet_side[static_cast<std::size_t>(t)] == TetSide::beyond) continue;
    const double volume = std::abs(signed_tet_volume(tet_corners(mesh, t)));
    for (int a = 0; a < 4; ++a) {
      const auto v = static_cast<std::size_t>(mesh.tets(t, a));
      above[v] += e.piece_fraction(t, +1) * volume;
      below[v] += e.piece_fraction(t, -1) * volume;
    }
  }
  std::vector<char> both(above.size(), 0);
  for (std::size_t v = 0; v < both.size(); ++v) both[v] = above[v] > 0.0 && below[v] > 0.0;
  return both;
}

} // namespace

double Enrichment::piece_fraction(Eigen::Index t, int side) const {
  const auto k = static_cast<std::size_t>(t);
  if (tet_side[k] == TetSide::beyond)
    throw std::logic_error("Enrichment::piece_fraction: tet " + std::to_string(t) + " lies beyond the cut's front and has no sides");
  return side > 0 ? fraction_above[k] : 1.0 - fraction_above[k];
}

Enrichment make_enrichment(const TetMesh& mesh, const RectangleCut& cut, const EnrichmentSettings& settings) {
  if (mesh.order() != 1)
    throw std::invalid_argument("make_enrichment: chapter 3's XFEM is for Tet4 meshes; Tet10 needs chapter 4's sub-element quadrature");
  Enrichment e;
  e.minimum_volume_fraction = settings.minimum_volume_fraction;
  const LevelSet original = make_level_set(mesh, cut);
  e.level_set = original;
  snap_small_pieces(mesh, cut, settings, e);
  e.classification = classify_mesh_cut(mesh, e.level_set, cut);
  assign_node_signs(mesh, original, e);
  split_tets(mesh, e);

  const std::vector<char> touches_beyond = nodes_touching_beyond(mesh, e);                            // rule 1
  const std::vector<char> plane_face_outside = nodes_on_plane_faces_outside_rectangle(mesh, cut, e); // rule 2
  const std::vector<char> both_sides = nodes_with_volume_on_both_sides(mesh, e);                     // rule 3
  e.enriched_index.assign(static_cast<std::size_t>(mesh.num_nodes()), -1);
  for (std::size_t v = 0; v < e.enriched_index.size(); ++v) {
    if (both_sides[v] && touches_beyond[v]) ++e.front_nodes;
    if (touches_beyond[v] || plane_face_outside[v] || !both_sides[v]) continue;
    e.enriched_index[v] = static_cast<int>(e.enriched_nodes.size());
    e.enriched_nodes.push_back(static_cast<int>(v));
  }
  return e;
}

} // namespace kerf
