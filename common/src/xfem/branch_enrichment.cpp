#include "kerf/xfem/branch_enrichment.hpp"

#include "kerf/xfem/branch_functions.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace kerf {

namespace {

// Chapter 4's enrichment without the enrichments of the nodes `drop` marks.
SurfaceEnrichment without_nodes(const SurfaceEnrichment& all, const std::vector<char>& drop) {
  SurfaceEnrichment kept;
  const std::size_t V = all.first_enrichment.size() - 1;
  kept.first_enrichment.assign(V + 1, 0);
  std::vector<int> renumber(all.enrichment_node.size(), -1);
  for (std::size_t i = 0; i < V; ++i) {
    kept.first_enrichment[i + 1] = kept.first_enrichment[i];
    if (drop[i]) continue;
    const int n = all.enrichments_of(static_cast<Eigen::Index>(i));
    for (int k = all.first_enrichment[i]; k < all.first_enrichment[i + 1]; ++k) {
      renumber[static_cast<std::size_t>(k)] = static_cast<int>(kept.enrichment_node.size());
      kept.enrichment_node.push_back(static_cast<int>(i));
    }
    kept.first_enrichment[i + 1] += n;
    if (n > 0) ++kept.enriched_nodes;
    kept.most_enrichments = std::max(kept.most_enrichments, n);
  }
  kept.active.resize(all.active.size());
  for (std::size_t t = 0; t < all.active.size(); ++t) {
    std::vector<int> list = all.active[t];
    bool any = false;
    for (int& k : list) {
      k = k < 0 ? -1 : renumber[static_cast<std::size_t>(k)];
      any = any || k >= 0;
    }
    if (any) kept.active[t] = std::move(list);
  }
  return kept;
}

// Whether node i lies on a cut: a corner of a polygon on the cut of a piece of one of its tets.
// Exact: tet_pieces.hpp decides a tet corner's side of a cut triangle's plane by an exact
// predicate and keeps a corner on the plane as it is, so a cut through the node has it as a
// corner of its polygon, bitwise.
bool node_on_a_cut(const TetMesh& mesh, const MeshPieces& pieces, Eigen::Index i) {
  const Eigen::Vector3d x = mesh.nodes.row(i).transpose();
  for (const int t : pieces.neighbours->node_tets[static_cast<std::size_t>(i)]) {
    const int e = pieces.entry[static_cast<std::size_t>(t)];
    if (e < 0) continue;
    for (const TetPiece& piece : pieces.tets[static_cast<std::size_t>(e)].pieces)
      for (const PieceBoundaryPolygon& b : piece.boundary)
        if (b.on_cut && std::find(b.polygon.begin(), b.polygon.end(), x) != b.polygon.end()) return true;
  }
  return false;
}

} // namespace

int BranchEnrichment::count(NodeEnrichmentKind k) const { return static_cast<int>(std::count(kind.begin(), kind.end(), k)); }

BranchEnrichment make_branch_enrichment(const TetMesh& mesh, const MeshPieces& pieces, const CrackFronts& fronts,
                                        TipEnrichmentRule rule, double radius, BlendingCorrection blending) {
  if (!(radius >= 0.0) || !std::isfinite(radius))
    throw std::invalid_argument("make_branch_enrichment: the enrichment radius must be finite and >= 0");
  const Eigen::Index V = mesh.num_nodes(), T = mesh.num_tets();
  BranchEnrichment result;
  result.front_tet.assign(static_cast<std::size_t>(T), 0);
  std::vector<char> branch(static_cast<std::size_t>(V), 0);
  // Only corners carry branch functions, on a Tet10 too, where their partition of unity is the
  // corners' linear hats lambda_v (the Tet4 shape functions), not the Tet10's: the functions obey
  // x_b F_1 + x_a F_3 - x_b F_4 = 0 and x_b F_2 - x_b F_3 - x_a F_4 = 0 (from r F_3 = x_b F_1,
  // r F_4 = x_b F_2), so with quadratic shape functions, which hold lambda_v x_a and lambda_v x_b,
  // the products N_i F_l of a fully enriched one-ring are linearly dependent (two null vectors
  // per component and inner vertex: the stiffness is singular). With linear hats they are not.
  std::vector<char> corner(static_cast<std::size_t>(V), 0);
  for (Eigen::Index t = 0; t < T; ++t)
    for (int a = 0; a < 4; ++a) corner[static_cast<std::size_t>(mesh.tets(t, a))] = 1;
  // The tets the front passes through. Every tet is asked, not only those a cut triangle meets
  // (pieces.entry_tet): a cut lying in a plane of mesh faces meets the tets on one side of it
  // only (chapter 4 gives the face to one side), while a front lying in such a face belongs to
  // the tets on both sides (the header's rule; the tets below were missed before,
  // tests/chapter_05/test_front_degenerate.cpp).
  // A box around the fronts rejects the far tets before the exact clipping.
  Eigen::Vector3d front_low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), front_high = -front_low;
  for (const FrontPolyline& line : fronts.polylines)
    for (const Eigen::Vector3d& x : line.points) front_low = front_low.cwiseMin(x), front_high = front_high.cwiseMax(x);
  if (!fronts.empty())
    for (Eigen::Index t = 0; t < T; ++t) {
      const Eigen::Matrix<double, 4, 3> X = tet_corners(mesh, t);
      const double slack = 1e-9 * (X.colwise().maxCoeff() - X.colwise().minCoeff()).norm();
      if ((X.colwise().minCoeff().transpose().array() > front_high.array() + slack).any() ||
          (X.colwise().maxCoeff().transpose().array() < front_low.array() - slack).any())
        continue;
      if (!front_in_tet(fronts, X).empty()) {
        result.front_tet[static_cast<std::size_t>(t)] = 1;
        for (int a = 0; a < 4; ++a) branch[static_cast<std::size_t>(mesh.tets(t, a))] = 1;
      }
    }
  if (rule == TipEnrichmentRule::geometric && !fronts.empty())
    for (Eigen::Index i = 0; i < V; ++i)
      if (corner[static_cast<std::size_t>(i)] && fronts.distance(mesh.nodes.row(i).transpose()) <= radius)
        branch[static_cast<std::size_t>(i)] = 1;

  // Fries's ramp nodes: the corners of the blending tets that are not in I*.
  std::vector<char> ramp(static_cast<std::size_t>(V), 0);
  if (blending == BlendingCorrection::corrected)
    for (Eigen::Index t = 0; t < T; ++t) {
      bool any = false;
      for (int a = 0; a < 4; ++a) any = any || branch[static_cast<std::size_t>(mesh.tets(t, a))];
      if (any)
        for (int a = 0; a < 4; ++a)
          if (!branch[static_cast<std::size_t>(mesh.tets(t, a))]) ramp[static_cast<std::size_t>(mesh.tets(t, a))] = 1;
    }

  result.blending_correction = blending;
  result.sign = without_nodes(make_surface_enrichment(mesh, pieces), branch);
  result.kind.assign(static_cast<std::size_t>(V), NodeEnrichmentKind::none);
  result.branch_slot.assign(static_cast<std::size_t>(V), -1);
  result.cut_side.assign(static_cast<std::size_t>(V), 0);
  for (Eigen::Index i = 0; i < V; ++i) {
    if (result.sign.enrichments_of(i) > 0) result.kind[static_cast<std::size_t>(i)] = NodeEnrichmentKind::sign;
    if (ramp[static_cast<std::size_t>(i)]) {
      // R(x_i) = 0: the shift R(x_i) F(x_i) vanishes whatever side of the cut the node is on.
      result.branch_slot[static_cast<std::size_t>(i)] = static_cast<int>(result.branch_node.size());
      result.branch_node.push_back(static_cast<int>(i));
      result.node_values.push_back(Eigen::Vector4d::Zero());
    } else if (branch[static_cast<std::size_t>(i)]) {
      result.kind[static_cast<std::size_t>(i)] = NodeEnrichmentKind::branch;
      result.branch_slot[static_cast<std::size_t>(i)] = static_cast<int>(result.branch_node.size());
      result.branch_node.push_back(static_cast<int>(i));
      // A node on the cut is above it, as chapter 4 counts it (surface_enrichment.hpp).
      const int side = node_on_a_cut(mesh, pieces, i) ? 1 : 0;
      result.cut_side[static_cast<std::size_t>(i)] = side;
      const FrontPolar p = fronts.polar(mesh.nodes.row(i).transpose(), side);
      result.node_values.push_back(branch_function_values(p.r, p.theta));
    }
  }
  result.has_branch_nodes.assign(static_cast<std::size_t>(T), 0);
  result.blending.assign(static_cast<std::size_t>(T), 0);
  for (Eigen::Index t = 0; t < T; ++t) {
    int count = 0;
    for (int a = 0; a < 4; ++a) count += branch[static_cast<std::size_t>(mesh.tets(t, a))];
    result.has_branch_nodes[static_cast<std::size_t>(t)] = count > 0;
    result.blending[static_cast<std::size_t>(t)] = count > 0 && count < 4;
  }
  return result;
}

} // namespace kerf
