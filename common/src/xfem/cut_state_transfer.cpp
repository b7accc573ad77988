#include "kerf/xfem/cut_state_transfer.hpp"

#include "kerf/cut/clip_tet.hpp"
#include "kerf/cut/convex_cell.hpp"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace kerf {

// The fit near the front (the header's comment). The unknowns c are the new model's DOF nodes
// (standard, sign and branch) that act in a tet with branch functions, before or after, except
// the held ones; every other DOF node keeps the value the rule of phantom values gives it. Over
// the tets R any unknown acts in, at the new model's own quadrature points (for_each_slot_gradient),
// with (g_U, G_U) and (g_F, G_F) the values and gradients of the unknown and the fixed new
// functions and (h, H) those of the old functions (the old model's functions_at), and the
// error e = g_U^T c + g_F^T p - h^T q_old (p the fixed new DOFs):
//
//   min sum_q w_q (|grad e|^2 + |e|^2 / l^2)   =>   M c = B_old q_old - B_fixed p,
//
//   M = sum_q w_q (G_U G_U^T + g_U g_U^T / l^2),  B_old = sum_q w_q (G_U H^T + g_U h^T / l^2),
//   B_fixed = sum_q w_q (G_U G_F^T + g_U g_F^T / l^2).
//
// The three components share these scalar matrices (columns of a n x 3 view of q).
struct CutStateTransfer::Fit {
  std::vector<int> unknown_node;                 // the new DOF node of each unknown
  Eigen::SparseMatrix<double> B_old, B_fixed;    // m x from's DOF nodes, m x to's DOF nodes
  Eigen::VectorXd scale;                         // 1 / sqrt(diag M): the system is solved scaled
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt; // of the scaled, lifted M
  Eigen::Index points = 0;
};

namespace {

using NodeRows = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>;

// The rule of phantom values (the header's comment), as offsets from the old u_i: for each
// enrichment of `to` and for each node's home part in `to`, the DOF node of `from` that holds the
// old phantom value there minus u_i, or -1 where that is u_i itself (the old home part).
struct PhantomSources {
  std::vector<int> enrichment, home;
};

PhantomSources phantom_sources(const CutXfemModel& from, const CutXfemModel& to) {
  const TetMesh& mesh = to.mesh();
  const int n = mesh.nodes_per_tet();
  const SurfaceEnrichment& enrichment = to.enrichment();
  const MeshPieces& pieces = to.pieces();
  PhantomSources source{std::vector<int>(static_cast<std::size_t>(to.num_dof_nodes() - mesh.num_nodes()), -1),
                        std::vector<int>(static_cast<std::size_t>(mesh.num_nodes()), -1)};
  std::vector<char> enrichment_done(static_cast<std::size_t>(enrichment.num_enrichments()), 0);
  std::vector<char> home_done(static_cast<std::size_t>(mesh.num_nodes()), 0);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    if (enrichment.active[static_cast<std::size_t>(t)].empty() || pieces.entry[static_cast<std::size_t>(t)] < 0) continue;
    const TetPieces& tp = pieces.tets[static_cast<std::size_t>(pieces.entry[static_cast<std::size_t>(t)])];
    for (int p = 0; p < pieces.num_pieces(t); ++p) {
      // A point strictly inside the new piece: off the new cut, so off the old one too. Every new
      // part lies inside one old part (the cut only grows), so one piece per part suffices.
      const TetPiece& piece = tp.pieces[static_cast<std::size_t>(p)];
      const Eigen::Vector3d x = convex_cell_inner_point(tp.cells[static_cast<std::size_t>(piece.cells.front())]);
      int p_old = -2;
      for (int a = 0; a < n; ++a) {
        const int i = mesh.tets(t, a);
        const int k = enrichment.active_enrichment(pieces, t, a, p);
        char& done = k >= 0 ? enrichment_done[static_cast<std::size_t>(k)] : home_done[static_cast<std::size_t>(i)];
        if (done) continue;
        done = 1;
        if (p_old == -2) p_old = from.piece_at(t, x);
        if (p_old < 0) throw std::logic_error("CutStateTransfer: a piece's inner point lies outside its tet");
        // The old phantom value at node a is q of from.phantom_node: u_i itself, or u_i + a_old.
        const int old_node = from.phantom_node(t, p_old, a);
        if (old_node == i) continue;
        (k >= 0 ? source.enrichment[static_cast<std::size_t>(k)] : source.home[static_cast<std::size_t>(i)]) = old_node;
      }
    }
  }
  return source;
}

// Whether the DofMap prescribes any component of DOF node d.
bool is_held(const DofMap& dofs, int d) {
  for (int c = 0; c < 3; ++c)
    if (dofs.free_index[static_cast<std::size_t>(3 * d + c)] < 0) return true;
  return false;
}

// The number of slots of row t of a model's assembly slots.
int num_slots(const TetMatrix& slots, Eigen::Index t) {
  int s = 0;
  while (s < slots.cols() && slots(t, s) >= 0) ++s;
  return s;
}

} // namespace

CutStateTransfer::CutStateTransfer(const CutXfemModel& from, const CutXfemModel& to, BranchStateRule rule, const DofMap* held)
    : from_dof_nodes_(from.num_dof_nodes()), to_dof_nodes_(to.num_dof_nodes()), num_nodes_(to.mesh().num_nodes()) {
  if (&from.mesh() != &to.mesh() && from.mesh().num_nodes() != to.mesh().num_nodes())
    throw std::invalid_argument("transfer_cut_state: the two models are on different meshes");
  PhantomSources sources = phantom_sources(from, to);
  enrichment_source_ = std::move(sources.enrichment);
  anchor_source_ = std::move(sources.home);
  to_enrichment_node_.assign(enrichment_source_.size(), -1);
  std::copy(to.enrichment().enrichment_node.begin(), to.enrichment().enrichment_node.end(), to_enrichment_node_.begin());
  if (held) {
    if (held->free_index.size() != static_cast<std::size_t>(3 * to.num_dof_nodes()))
      throw std::invalid_argument("transfer_cut_state: the DofMap is not the new model's");
    // The held enrichments take 0. Where one glues its part to the home part, the larger part
    // keeps its old value: it becomes the anchor of u_i (the header's comment).
    const SurfaceEnrichment& enrichment = to.enrichment();
    const EnrichmentVolumes volumes = to.enrichment_volumes();
    for (Eigen::Index i = 0; i < num_nodes_; ++i) {
      double anchor_volume = -1.0;
      for (int k = enrichment.first_enrichment[static_cast<std::size_t>(i)]; k < enrichment.first_enrichment[static_cast<std::size_t>(i) + 1]; ++k) {
        if (!is_held(*held, static_cast<int>(num_nodes_) + k)) continue;
        held_enrichments_.push_back(static_cast<int>(num_nodes_) + k);
        if (anchor_volume < 0.0) anchor_volume = volumes.home_fraction(k) * volumes.support[static_cast<std::size_t>(k)];
        if (volumes.enriched[static_cast<std::size_t>(k)] > anchor_volume) {
          anchor_volume = volumes.enriched[static_cast<std::size_t>(k)];
          anchor_source_[static_cast<std::size_t>(i)] = enrichment_source_[static_cast<std::size_t>(k)];
        }
      }
    }
  }
  if (rule == BranchStateRule::fit && (to.crack_tip() || from.crack_tip())) fit_ = make_fit(from, to, held);
  if (rule == BranchStateRule::keep_values && to.crack_tip() && from.crack_tip()) {
    const std::vector<int>& slot_to = to.crack_tip()->enrichment.branch_slot;
    const std::vector<int>& slot_from = from.crack_tip()->enrichment.branch_slot;
    for (std::size_t v = 0; v < slot_to.size(); ++v) {
      if (slot_to[v] < 0 || slot_from[v] < 0) continue;
      kept_branch_nodes_.emplace_back(to.branch_dof_node(slot_to[v]), from.branch_dof_node(slot_from[v]));
    }
  }
}

CutStateTransfer::CutStateTransfer(CutStateTransfer&&) noexcept = default;
CutStateTransfer& CutStateTransfer::operator=(CutStateTransfer&&) noexcept = default;
CutStateTransfer::~CutStateTransfer() = default;

Eigen::Index CutStateTransfer::num_fitted() const { return fit_ ? static_cast<Eigen::Index>(fit_->unknown_node.size()) : 0; }
Eigen::Index CutStateTransfer::num_fit_points() const { return fit_ ? fit_->points : 0; }

Eigen::VectorXd CutStateTransfer::operator()(const Eigen::VectorXd& q) const {
  if (q.size() != 3 * from_dof_nodes_) throw std::invalid_argument("transfer_cut_state: q has the wrong size");
  Eigen::VectorXd out = Eigen::VectorXd::Zero(3 * to_dof_nodes_);
  out.head(3 * num_nodes_) = q.head(3 * num_nodes_);
  // The offset of each source from the old u_i (0 for the old home part).
  const auto offset = [&](int source) -> Eigen::Vector3d { return source >= 0 ? Eigen::Vector3d(q.segment<3>(3 * source)) : Eigen::Vector3d::Zero(); };
  for (std::size_t e = 0; e < enrichment_source_.size(); ++e) {
    const int i = to_enrichment_node_[e];
    const Eigen::Vector3d anchor = i >= 0 ? offset(anchor_source_[static_cast<std::size_t>(i)]) : Eigen::Vector3d::Zero();
    out.segment<3>(3 * (num_nodes_ + static_cast<Eigen::Index>(e))) = offset(enrichment_source_[e]) - anchor;
  }
  for (Eigen::Index i = 0; i < num_nodes_; ++i) out.segment<3>(3 * i) += offset(anchor_source_[static_cast<std::size_t>(i)]);
  for (const int e : held_enrichments_) out.segment<3>(3 * e).setZero();
  for (const auto& [target, source] : kept_branch_nodes_) out.segment<12>(3 * target) = q.segment<12>(3 * source);
  if (!fit_) return out;
  // M c = B_old q_old - B_fixed p (the Fit's comment); the unknowns' own entries of `out` are
  // outside B_fixed's columns, so `out` as it stands serves as p.
  const NodeRows q_nodes(q.data(), from_dof_nodes_, 3), p_nodes(out.data(), to_dof_nodes_, 3);
  const Eigen::MatrixX3d rhs = fit_->B_old * q_nodes - fit_->B_fixed * p_nodes;
  const Eigen::MatrixX3d c = fit_->scale.asDiagonal() * fit_->ldlt.solve(fit_->scale.asDiagonal() * rhs);
  for (std::size_t i = 0; i < fit_->unknown_node.size(); ++i) out.segment<3>(3 * fit_->unknown_node[i]) = c.row(static_cast<Eigen::Index>(i)).transpose();
  return out;
}

std::unique_ptr<CutStateTransfer::Fit> CutStateTransfer::make_fit(const CutXfemModel& from, const CutXfemModel& to, const DofMap* held) {
  if (held && held->free_index.size() != static_cast<std::size_t>(3 * to.num_dof_nodes()))
    throw std::invalid_argument("transfer_cut_state: the DofMap is not the new model's");
  const TetMesh& mesh = to.mesh();
  const int n = mesh.nodes_per_tet();
  const TetMatrix& slots = to.assembly_slots();
  // The unknowns: the slots of every tet with branch functions, but the held DOF nodes; and
  // those tets' volume, for l below.
  std::vector<int> unknown(static_cast<std::size_t>(to.num_dof_nodes()), -1);
  auto fit = std::make_unique<CutStateTransfer::Fit>();
  double volume = 0.0;
  int counted = 0;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    if (!to.has_branch_functions(t) && !from.has_branch_functions(t)) continue;
    volume += std::abs(signed_tet_volume(tet_corners(mesh, t)));
    ++counted;
    for (int s = 0; s < num_slots(slots, t); ++s) {
      if (held && is_held(*held, slots(t, s))) continue;
      int& k = unknown[static_cast<std::size_t>(slots(t, s))];
      if (k < 0) {
        k = static_cast<int>(fit->unknown_node.size());
        fit->unknown_node.push_back(slots(t, s));
      }
    }
  }
  const auto m = static_cast<Eigen::Index>(fit->unknown_node.size());
  if (m == 0) return nullptr;

  // l, which weighs the L2 term against the gradients: the size of a tet near the front, the cube
  // root of the mean volume of the tets with branch functions. The L2 term makes M definite (a
  // piece whose DOFs are all unknowns could otherwise translate freely) and keeps the field from
  // drifting where the gradients say little; measured on the box of tests/chapter_07, weights of
  // 0.1 and 1 on it changed the elastic energy at a change of the cut by -1.8 % and +0.2 %.
  const double inverse_length_squared = std::pow(volume / counted, -2.0 / 3.0);

  std::vector<Eigen::Triplet<double>> M_entries, old_entries, fixed_entries;
  std::vector<int> local;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const int width = num_slots(slots, t);
    local.assign(static_cast<std::size_t>(width), -1);
    bool acts = false;
    for (int s = 0; s < width; ++s) {
      local[static_cast<std::size_t>(s)] = unknown[static_cast<std::size_t>(slots(t, s))];
      acts = acts || local[static_cast<std::size_t>(s)] >= 0;
    }
    if (!acts) continue;
    // Per tet, dense: A_t on the new slots, B_t against the old DOF nodes met in this tet, of
    // the inner product (e, f) = int grad e : grad f + e . f / l^2 of the header's fit. The new
    // functions come as the model stored them at its points; the old ones are evaluated there.
    Eigen::MatrixXd A_t = Eigen::MatrixXd::Zero(width, width);
    std::vector<int> old_nodes;
    Eigen::MatrixXd B_t = Eigen::MatrixXd::Zero(width, 0);
    to.for_each_slot_gradient(t, [&](int, double w, const Eigen::VectorXd& v_new, const Eigen::MatrixX3d& G_new) {
      ++fit->points;
      Eigen::Vector3d x = Eigen::Vector3d::Zero(); // sum_a N_a x_a: the point, on straight-edged tets
      for (int a = 0; a < n; ++a) x += v_new[a] * mesh.nodes.row(mesh.tets(t, a)).transpose();
      const CutXfemModel::FunctionsAt before = from.functions_at(t, x);
      if (before.dof_node.empty()) throw std::logic_error("CutStateTransfer: a quadrature point lies outside its tet");
      A_t.noalias() += w * (G_new * G_new.transpose() + inverse_length_squared * v_new * v_new.transpose());
      for (std::size_t j = 0; j < before.dof_node.size(); ++j) {
        const int node = before.dof_node[j];
        auto found = std::find(old_nodes.begin(), old_nodes.end(), node);
        const Eigen::Index column = found - old_nodes.begin();
        if (found == old_nodes.end()) {
          old_nodes.push_back(node);
          B_t.conservativeResize(Eigen::NoChange, B_t.cols() + 1);
          B_t.col(column).setZero();
        }
        const auto J = static_cast<Eigen::Index>(j);
        B_t.col(column).noalias() += w * (G_new * before.gradient.row(J).transpose() + inverse_length_squared * before.value[J] * v_new);
      }
    });
    for (int s = 0; s < width; ++s) {
      const int i = local[static_cast<std::size_t>(s)];
      if (i < 0) continue;
      for (int s2 = 0; s2 < width; ++s2) {
        const int j = local[static_cast<std::size_t>(s2)];
        if (j >= 0) M_entries.emplace_back(i, j, A_t(s, s2));
        else fixed_entries.emplace_back(i, slots(t, s2), A_t(s, s2));
      }
      for (std::size_t c = 0; c < old_nodes.size(); ++c) old_entries.emplace_back(i, old_nodes[c], B_t(s, static_cast<Eigen::Index>(c)));
    }
  }
  Eigen::SparseMatrix<double> M(m, m);
  M.setFromTriplets(M_entries.begin(), M_entries.end());
  fit->B_old.resize(m, from.num_dof_nodes());
  fit->B_old.setFromTriplets(old_entries.begin(), old_entries.end());
  fit->B_fixed.resize(m, to.num_dof_nodes());
  fit->B_fixed.setFromTriplets(fixed_entries.begin(), fixed_entries.end());
  // Scaled to a unit diagonal, and lifted by 1e-10: the shifted branch functions and the sign
  // enrichments of a tet can be nearly dependent (branch_null_space.hpp); the lift sets such
  // directions, which the field does not see, to about zero instead of to round-off noise.
  fit->scale = M.diagonal().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
  Eigen::SparseMatrix<double> I(m, m);
  I.setIdentity();
  const Eigen::SparseMatrix<double> M_scaled = fit->scale.asDiagonal() * M * fit->scale.asDiagonal() + 1e-10 * I;
  fit->ldlt.compute(M_scaled);
  if (fit->ldlt.info() != Eigen::Success) throw std::runtime_error("transfer_cut_state: the fit near the front could not be factorised");
  return fit;
}

Eigen::VectorXd transfer_cut_state(const CutXfemModel& from, const CutXfemModel& to, const Eigen::VectorXd& q) {
  return CutStateTransfer(from, to)(q);
}

} // namespace kerf
