#include "kerf/xfem/cut_state_transfer.hpp"

#include "kerf/cut/convex_cell.hpp"

#include <stdexcept>
#include <vector>

namespace kerf {

Eigen::VectorXd transfer_cut_state(const CutXfemModel& from, const CutXfemModel& to, const Eigen::VectorXd& q) {
  const TetMesh& mesh = to.mesh();
  if (&from.mesh() != &mesh && from.mesh().num_nodes() != mesh.num_nodes())
    throw std::invalid_argument("transfer_cut_state: the two models are on different meshes");
  if (q.size() != 3 * from.num_dof_nodes()) throw std::invalid_argument("transfer_cut_state: q has the wrong size");
  const Eigen::Index N = mesh.num_nodes();
  const int n = mesh.nodes_per_tet();
  Eigen::VectorXd out = Eigen::VectorXd::Zero(3 * to.num_dof_nodes());
  out.head(3 * N) = q.head(3 * N);

  // Sign enrichments: each from one piece of its part (the file's comment).
  const SurfaceEnrichment& enrichment = to.enrichment();
  const MeshPieces& pieces = to.pieces();
  std::vector<char> done(static_cast<std::size_t>(enrichment.num_enrichments()), 0);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    if (enrichment.active[static_cast<std::size_t>(t)].empty()) continue;
    const int num_pieces = pieces.num_pieces(t);
    for (int p = 0; p < num_pieces; ++p)
      for (int a = 0; a < n; ++a) {
        const int k = enrichment.active_enrichment(pieces, t, a, p);
        if (k < 0 || done[static_cast<std::size_t>(k)]) continue;
        done[static_cast<std::size_t>(k)] = 1;
        // A point strictly inside the new piece: off the new cut, so off the old one too.
        const TetPieces& tp = pieces.tets[static_cast<std::size_t>(pieces.entry[static_cast<std::size_t>(t)])];
        const TetPiece& piece = tp.pieces[static_cast<std::size_t>(p)];
        const Eigen::Vector3d x = convex_cell_inner_point(tp.cells[static_cast<std::size_t>(piece.cells.front())]);
        const int p_old = from.piece_at(t, x);
        if (p_old < 0) throw std::logic_error("transfer_cut_state: a piece's inner point lies outside its tet");
        const int i = mesh.tets(t, a);
        const Eigen::Vector3d w = from.phantom_displacements(q, t, p_old).row(a).transpose();
        out.segment<3>(3 * (N + k)) = w - q.segment<3>(3 * i);
      }
  }

  // Branch functions: kept per node where the node carries them in both models.
  const CrackTipFunctions* tip_to = to.crack_tip();
  const CrackTipFunctions* tip_from = from.crack_tip();
  if (tip_to && tip_from) {
    const std::vector<int>& slot_to = tip_to->enrichment.branch_slot;
    const std::vector<int>& slot_from = tip_from->enrichment.branch_slot;
    for (Eigen::Index v = 0; v < N; ++v) {
      const int k_to = slot_to[static_cast<std::size_t>(v)], k_from = slot_from[static_cast<std::size_t>(v)];
      if (k_to < 0 || k_from < 0) continue;
      out.segment<12>(3 * to.branch_dof_node(k_to)) = q.segment<12>(3 * from.branch_dof_node(k_from));
    }
  }
  return out;
}

} // namespace kerf
