#include "kerf/xfem/enrichment.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
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

/// The minimum-fraction rule: moves onto the cut the corners on the small side of every tet
/// whose smaller piece is below the threshold, until no such tet is left. Moving a corner only
/// ever sets a value to 0, so this ends after at most #V rounds (in practice one or two).
void snap_small_pieces(const TetMesh& mesh, const RectangleCut& cut, double minimum_fraction, Enrichment& e) {
  for (bool changed = true; changed;) {
    changed = false;
    const MeshCutClassification classes = classify_mesh_cut(mesh, e.level_set, cut);
    for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
      const auto k = static_cast<std::size_t>(t);
      if (!is_cut(classes.tet_case[k]) || !cut_by_rectangle(classes.state[k])) continue;
      const Eigen::Vector4d lambda = corner_values(mesh, e.level_set, t);
      const ClippedTet clipped = clip_tet(tet_corners(mesh, t), lambda);
      const double fraction_a = clipped.V_a / (clipped.V_a + clipped.V_b);
      if (minimum_volume_fraction_met(fraction_a, 1.0 - fraction_a, minimum_fraction)) continue;
      const int small_side = fraction_a < 0.5 ? 1 : -1;
      for (int a = 0; a < 4; ++a)
        if (level_set_sign(lambda[a]) == small_side) {
          const int v = mesh.tets(t, a);
          e.largest_snap = std::max(e.largest_snap, std::abs(e.level_set.lambda[v]));
          e.level_set.lambda[v] = 0.0;
          e.level_set.sign[v] = 0;
          ++e.snapped_nodes;
          changed = true;
        }
    }
  }
}

} // namespace

Enrichment make_enrichment(const TetMesh& mesh, const RectangleCut& cut, const EnrichmentSettings& settings) {
  if (mesh.order() != 1)
    throw std::invalid_argument("make_enrichment: chapter 3's XFEM is for Tet4 meshes; Tet10 needs chapter 4's sub-element quadrature");
  Enrichment e;
  e.minimum_volume_fraction = settings.minimum_volume_fraction;
  e.level_set = make_level_set(mesh, cut);
  snap_small_pieces(mesh, cut, settings.minimum_volume_fraction, e);
  e.classification = classify_mesh_cut(mesh, e.level_set, cut);

  // The side of every node (eqs. 58-59: a node on the cut counts as above).
  const auto num_nodes = static_cast<std::size_t>(mesh.num_nodes());
  e.node_sign.resize(num_nodes);
  for (std::size_t v = 0; v < num_nodes; ++v) e.node_sign[v] = e.level_set.lambda[static_cast<Eigen::Index>(v)] >= 0.0 ? 1 : -1;

  // The side of every tet, and its pieces and fractions when the cut splits it.
  const auto num_tets = static_cast<std::size_t>(mesh.num_tets());
  e.tet_side.resize(num_tets);
  e.fraction_above.resize(num_tets);
  e.pieces.resize(num_tets);
  std::vector<double> volume(num_tets);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const auto k = static_cast<std::size_t>(t);
    const Eigen::Vector4d lambda = corner_values(mesh, e.level_set, t);
    volume[k] = std::abs(signed_tet_volume(tet_corners(mesh, t)));
    if (is_cut(e.classification.tet_case[k])) {
      if (!cut_by_rectangle(e.classification.state[k])) {
        e.tet_side[k] = TetSide::beyond;
        e.fraction_above[k] = 0.5; // never used: no enriched node touches a tet beyond the front
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

  // Faces lying in the cut plane between a tet above and a tet below: the cut runs along them.
  // Rule 2 needs to know, for every node, whether such a face through it leaves the rectangle.
  std::map<std::array<int, 3>, std::vector<int>> plane_faces;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    for (int opposite = 0; opposite < 4; ++opposite) {
      std::array<int, 3> face{};
      int n = 0;
      for (int a = 0; a < 4; ++a)
        if (a != opposite) face[static_cast<std::size_t>(n++)] = mesh.tets(t, a);
      if (std::all_of(face.begin(), face.end(), [&](int v) { return e.level_set.lambda[v] == 0.0; })) {
        std::sort(face.begin(), face.end());
        plane_faces[face].push_back(static_cast<int>(t));
      }
    }
  std::vector<char> plane_face_leaves_cut(num_nodes, 0);
  const double tolerance = e.level_set.snap_tolerance;
  for (const auto& [face, tets] : plane_faces) {
    if (tets.size() != 2) continue; // a boundary face: no material on the other side, no jump
    if (e.tet_side[static_cast<std::size_t>(tets[0])] == e.tet_side[static_cast<std::size_t>(tets[1])]) continue;
    const bool inside = std::all_of(face.begin(), face.end(), [&](int v) {
      return cut.contains_projection(mesh.nodes.row(v).transpose(), tolerance);
    });
    if (!inside)
      for (int v : face) plane_face_leaves_cut[static_cast<std::size_t>(v)] = 1;
  }

  // Rules 1 and 3 over the tets around each node.
  std::vector<char> touches_beyond(num_nodes, 0);
  std::vector<double> volume_above(num_nodes, 0.0), volume_below(num_nodes, 0.0);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const auto k = static_cast<std::size_t>(t);
    for (int a = 0; a < 4; ++a) {
      const auto v = static_cast<std::size_t>(mesh.tets(t, a));
      if (e.tet_side[k] == TetSide::beyond) {
        touches_beyond[v] = 1;
        continue;
      }
      volume_above[v] += e.fraction_above[k] * volume[k];
      volume_below[v] += (1.0 - e.fraction_above[k]) * volume[k];
    }
  }
  e.enriched_index.assign(num_nodes, -1);
  for (std::size_t v = 0; v < num_nodes; ++v) {
    const bool both_sides = volume_above[v] > 0.0 && volume_below[v] > 0.0;
    if (both_sides && touches_beyond[v]) ++e.front_nodes;
    if (!both_sides || touches_beyond[v] || plane_face_leaves_cut[v]) continue;
    e.enriched_index[v] = static_cast<int>(e.enriched_nodes.size());
    e.enriched_nodes.push_back(static_cast<int>(v));
  }
  return e;
}

} // namespace kerf
