// CutXfemModel: the constructors and build(), the slots of each tet, the DOF map and the linear
// solve. The points of the tets are made in cut_xfem_model_rules.cpp, the forces in
// cut_xfem_model_assembly.cpp, the field in cut_xfem_model_field.cpp, and chapter 5's tets in
// branch_tets.cpp (cut_xfem_model.hpp's file comment).
#include "kerf/xfem/cut_xfem_model.hpp"

#include "kerf/fem/rigid_motion_check.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/xfem/branch_null_space.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace kerf {

CutXfemModel::CutXfemModel(const TetMesh& mesh, const LinearMaterial& material, const MeshPieces& pieces,
                           const SurfaceEnrichment& enrichment, const PieceRuleFunction& rule,
                           const CrackTipFunctions* tip)
    : mesh_(mesh), material_(material), pieces_(pieces), enrichment_(enrichment), tip_(tip), rule_(rule),
      whole_(integrate_whole_tets(mesh, material)) {
  build(nullptr);
}

CutXfemModel::CutXfemModel(const CutXfemModel& before, const MeshPieces& pieces, const SurfaceEnrichment& enrichment,
                           const CrackTipFunctions* tip)
    : mesh_(before.mesh_), material_(before.material_), pieces_(pieces), enrichment_(enrichment), tip_(tip),
      rule_(before.rule_), whole_(before.whole_) {
  if (pieces.kept_from_previous.size() != static_cast<std::size_t>(mesh_.num_tets()))
    throw std::invalid_argument(
        "CutXfemModel: the pieces do not say which tets kept their pieces (make them with recut_mesh_into_pieces)");
  build(&before);
}

void CutXfemModel::build(const CutXfemModel* before) {
  if (tip_ && &tip_->enrichment.sign != &enrichment_)
    throw std::invalid_argument("CutXfemModel: with crack-tip functions, the enrichment must be their sign enrichment");
  const std::size_t T = static_cast<std::size_t>(mesh_.num_tets());

  // 1. The slots of every tet: its n nodes, the sign enrichments acting in it, and (chapter 5)
  //    four per branch corner, which BranchTets numbers after the sign ones.
  const std::vector<std::vector<int>> sign_enrichments = sign_enrichments_by_tet();
  std::vector<int> first_branch_slot(T);
  for (std::size_t t = 0; t < T; ++t)
    first_branch_slot[t] = mesh_.nodes_per_tet() + static_cast<int>(sign_enrichments[t].size());
  branch_ = BranchTets(mesh_, pieces_, tip_, std::move(first_branch_slot));
  slots_ = make_slots(sign_enrichments);

  // 2. The points of every tet, each piece with its phantom element's slots (integrate_tet:
  //    whole, kept from `before`, by the piece rule, or by BranchTets).
  piece_data_.assign(T, {});
  position_force_squared_.assign(T, 0.0);
  for (Eigen::Index t = 0; t < mesh_.num_tets(); ++t) integrate_tet(t, before);

  // 3. The position force |K X| of the whole mesh: the floor of f_int's round-off.
  double force_norm_squared = 0.0;
  for (const double f : position_force_squared_) force_norm_squared += f;
  position_force_norm_ = std::sqrt(force_norm_squared);
}

std::vector<std::vector<int>> CutXfemModel::sign_enrichments_by_tet() const {
  std::vector<std::vector<int>> result(static_cast<std::size_t>(mesh_.num_tets()));
  for (std::size_t t = 0; t < result.size(); ++t) {
    std::vector<int>& list = result[t];
    for (const int k : enrichment_.active[t])
      if (k >= 0) list.push_back(k);
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return result;
}

TetMatrix CutXfemModel::make_slots(const std::vector<std::vector<int>>& sign_enrichments) const {
  const int n = mesh_.nodes_per_tet();
  const Eigen::Index T = mesh_.num_tets();
  const auto N = static_cast<int>(mesh_.num_nodes());
  int width = n;
  for (Eigen::Index t = 0; t < T; ++t) {
    const int sign_slots = n + static_cast<int>(sign_enrichments[static_cast<std::size_t>(t)].size());
    width = std::max(width, branch_.contains(t) ? branch_.num_slots(t) : sign_slots);
  }
  TetMatrix slots = TetMatrix::Constant(T, width, -1);
  for (Eigen::Index t = 0; t < T; ++t) {
    const std::vector<int>& list = sign_enrichments[static_cast<std::size_t>(t)];
    for (int a = 0; a < n; ++a) slots(t, a) = mesh_.tets(t, a);
    for (std::size_t k = 0; k < list.size(); ++k) slots(t, n + static_cast<int>(k)) = N + list[k];
    if (!branch_.contains(t)) continue;
    // Function l of the j-th branch corner: DOF node N + M + 4 k + l, k the corner's branch slot.
    const std::vector<int>& branch_nodes = branch_.local_nodes(t);
    for (std::size_t j = 0; j < branch_nodes.size(); ++j) {
      const int k = tip_->enrichment.branch_slot[static_cast<std::size_t>(mesh_.tets(t, branch_nodes[j]))];
      for (int l = 0; l < 4; ++l)
        slots(t, branch_.first_slot(t) + 4 * static_cast<int>(j) + l) = static_cast<int>(branch_dof_node(k)) + l;
    }
  }
  return slots;
}

int CutXfemModel::num_slots(Eigen::Index t) const {
  int slots = mesh_.nodes_per_tet();
  while (slots < slots_.cols() && slots_(t, slots) >= 0) ++slots;
  return slots;
}

int CutXfemModel::num_sign_slots(Eigen::Index t) const {
  const int end = branch_.contains(t) ? branch_.first_slot(t) : num_slots(t);
  return end - mesh_.nodes_per_tet();
}

std::vector<int> CutXfemModel::phantom_slots(Eigen::Index t, int p) const {
  const int n = mesh_.nodes_per_tet();
  std::vector<int> slot(static_cast<std::size_t>(n), -1);
  const std::vector<int>& active = enrichment_.active[static_cast<std::size_t>(t)];
  if (active.empty()) return slot;
  // active holds, per node a and piece p, the enrichment k active there (-1: none); its slot
  // is the one whose DOF node is N + k.
  const int np = pieces_.num_pieces(t);
  const int end = n + num_sign_slots(t);
  for (int a = 0; a < n; ++a) {
    const int k = active[static_cast<std::size_t>(a * np + p)];
    if (k < 0) continue;
    for (int s = n; s < end; ++s)
      if (slots_(t, s) == mesh_.num_nodes() + k) slot[static_cast<std::size_t>(a)] = s;
  }
  return slot;
}

std::vector<UnheldPiece> cut_xfem_unheld_pieces(const CutXfemModel& model, const DofMap& dofs) {
  PhantomMesh phantom = model.phantom_mesh();
  const Eigen::Index N = model.mesh().num_nodes();
  // A prescribed enrichment (a gripped node's, or a sliver's: Koschier et al. 2017, eq. 22)
  // makes the phantom value u_i + a_k move with u_i: the pieces that use it hang on node i, so
  // they take node i itself.
  const auto prescribed = [&](Eigen::Index dof_node) {
    for (int p = 0; p < 3; ++p)
      if (dofs.free_index[static_cast<std::size_t>(3 * dof_node + p)] >= 0) return false;
    return true;
  };
  for (Eigen::Index t = 0; t < phantom.mesh.tets.rows(); ++t)
    for (int a = 0; a < 4; ++a) {
      const int v = phantom.mesh.tets(t, a);
      if (v >= N && prescribed(v))
        phantom.mesh.tets(t, a) = model.enrichment().enrichment_node[static_cast<std::size_t>(v - N)];
    }
  // The value u_i + a_k of a phantom node is held when both are prescribed: it counts as free
  // when u_i is (only "free or not" matters to the check).
  DofMap phantom_dofs = dofs;
  for (Eigen::Index k = 0; k < model.enrichment().num_enrichments(); ++k) {
    const int node = model.enrichment().enrichment_node[static_cast<std::size_t>(k)];
    for (int p = 0; p < 3; ++p)
      if (dofs.free_index[static_cast<std::size_t>(3 * node + p)] >= 0)
        phantom_dofs.free_index[static_cast<std::size_t>(3 * (N + k) + p)] = 0;
  }
  return unheld_pieces(phantom.mesh, phantom_dofs, phantom.piece_volume, phantom.piece_point);
}

DofMap make_cut_xfem_dof_map(const CutXfemModel& model, const std::vector<DirichletNodes>& conditions,
                             double sliver_fraction) {
  const SurfaceEnrichment& enrichment = model.enrichment();
  const auto num_nodes = static_cast<int>(model.mesh().num_nodes());
  DirichletNodes enrichments_of_gripped;
  // Koschier et al. 2017, eq. 22: a sliver's enrichment is held at 0, like a gripped node's.
  for (const int k : sliver_enrichments(model.enrichment_volumes(), sliver_fraction))
    enrichments_of_gripped.nodes.push_back(num_nodes + k);
  for (const DirichletNodes& condition : conditions)
    for (const int v : condition.nodes) {
      if (v >= num_nodes) continue;
      const std::size_t node = static_cast<std::size_t>(v);
      for (int k = enrichment.first_enrichment[node]; k < enrichment.first_enrichment[node + 1]; ++k)
        enrichments_of_gripped.nodes.push_back(num_nodes + k);
      // A gripped branch node's four functions too: with them at 0 the field there is the
      // standard one, held at the node's value (the shifted functions vanish at every node).
      if (const CrackTipFunctions* tip = model.crack_tip(); tip && tip->enrichment.branch_slot[node] >= 0) {
        const auto first = static_cast<int>(model.branch_dof_node(tip->enrichment.branch_slot[node]));
        for (int l = 0; l < 4; ++l) enrichments_of_gripped.nodes.push_back(first + l);
      }
    }
  // First, so that a condition the caller puts on an enrichment itself has the last word.
  std::vector<DirichletNodes> with_enrichments{enrichments_of_gripped};
  with_enrichments.insert(with_enrichments.end(), conditions.begin(), conditions.end());
  DofMap dofs = make_dof_map(model.num_dof_nodes(), with_enrichments);
  // The null vectors of the branch functions' identities that these conditions leave free, each
  // removed by holding one branch DOF at 0 (branch_null_space.hpp: the field space is the same).
  if (const std::vector<int> gauge = branch_gauge_dof_nodes(model, dofs); !gauge.empty()) {
    with_enrichments.push_back({gauge, Eigen::Vector3d::Zero()});
    dofs = make_dof_map(model.num_dof_nodes(), with_enrichments);
  }
  return dofs;
}

Eigen::VectorXd solve_linear_cut_xfem(const CutXfemModel& model, const DofMap& dofs, const Eigen::VectorXd& f_ext,
                                      const SolverSettings& solver_settings) {
  if (const std::vector<UnheldPiece> unheld = cut_xfem_unheld_pieces(model, dofs); !unheld.empty())
    throw std::runtime_error("the XFEM stiffness is singular: " + describe_unheld_pieces(unheld));
  SparseAssembler assembler(model.assembly_slots(), dofs);
  Eigen::VectorXd rhs = dofs.restrict_to_free(f_ext);
  model.assemble_linear_stiffness(assembler, rhs);
  return dofs.expand(solve_once(assembler.matrix(), rhs, solver_settings));
}

} // namespace kerf
