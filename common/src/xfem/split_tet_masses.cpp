#include "kerf/xfem/split_tet_masses.hpp"

#include "kerf/xfem/cut_xfem_mass.hpp"

#include <stdexcept>

namespace kerf {

SplitTetMasses::SplitTetMasses(const CutXfemModel& model, const PieceRuleFunction& rule, const SplitTetMasses* before) : rule_(rule) {
  const Eigen::Index T = model.mesh().num_tets();
  const MeshPieces& pieces = model.pieces();
  if (before && before->split_.size() != static_cast<std::size_t>(T))
    throw std::invalid_argument("SplitTetMasses: the masses before are of another mesh");
  if (before && pieces.kept_from_previous.size() != static_cast<std::size_t>(T))
    throw std::invalid_argument("SplitTetMasses: the pieces do not say which tets kept their pieces (make them with recut_mesh_into_pieces)");
  split_.assign(static_cast<std::size_t>(T), {});
  for (Eigen::Index t = 0; t < T; ++t) {
    // cut_xfem_piece_masses integrates the pieces by `rule` only here: integrated by pieces, several,
    // no branch functions. Elsewhere its masses are the element's or the model's points'.
    const int np = pieces.num_pieces(t);
    if (model.has_branch_functions(t) || !model.integrated_by_pieces(t) || np == 1) continue;
    const std::size_t k = static_cast<std::size_t>(t);
    if (before && pieces.kept_from_previous[k] && before->split_[k].size() == static_cast<std::size_t>(np)) {
      split_[k] = before->split_[k];
    } else {
      split_[k] = cut_xfem_piece_masses(model, t, 1.0, rule);
      ++integrated_;
    }
  }
}

std::vector<Eigen::MatrixXd> SplitTetMasses::operator()(const CutXfemModel& model, Eigen::Index t) const {
  if (model.mesh().num_tets() != static_cast<Eigen::Index>(split_.size()))
    throw std::invalid_argument("SplitTetMasses: asked about a model of another mesh");
  const std::vector<Eigen::MatrixXd>& stored = split_[static_cast<std::size_t>(t)];
  return stored.empty() ? cut_xfem_piece_masses(model, t, 1.0, rule_) : stored;
}

} // namespace kerf
