/// @file cut_state_transfer.hpp
/// @brief When a cut grows during a run, the state of the old model in the DOFs of the new one, with the field unchanged (no paper says how).
///
/// Chapter 7's blade cuts while the body moves: each time a tet becomes crossed the model is
/// rebuilt on the longer cut, with more enrichments. Its displacement, velocity and acceleration
/// vectors must be carried over. No paper says how; the standard answer
/// is that new enrichments start at rest and at zero, so that the field does not jump and no
/// energy is injected. With enrichments counted per part of a support (Koschier section 4.3,
/// surface_enrichment.hpp) that answer is exact, and it generalises into one rule:
///
///   the new field equals the old one on every piece of the new model.
///
/// The standard DOFs u_i are the same DOFs in both models (the Kronecker property: u(x_i) = u_i
/// on the home part). An enrichment k of node i in the new model is active on a part C of i's
/// support; on a piece p of C in tet t, the new field's phantom value at i is u_i + a_k. The old
/// field on the old piece that holds p (the cut only grows, so every new piece lies inside one old
/// piece) is a phantom element too, with value w_i at i. Equal fields need u_i + a_k = w_i:
///
///   a_k = w_i - u_i   (old phantom value minus the standard value),
///
/// which is 0 for a part that was the home part before (a tet the blade has just split: the new
/// enrichment starts at zero, the standard answer) and the old a for a part that already was a far
/// part. The standard DOF u_i is itself a phantom value, the one on the node's home part; the
/// home part of a node that lies on a cut can switch when a second cut passes through the node
/// (the parts are numbered anew), so u_i takes the old field's value on the new home part too:
/// u_i = w_i(home), a_k = w_i(C_k) - w_i(home).
///
/// Held enrichments (the new DofMap's: a gripped node's, or eq. 22's slivers) are 0 in the step,
/// so their part moves with u_i: a jump on that part, which the rule cannot avoid and books (the
/// energies before and after differ by it). Which of the two glued parts keeps its value: the
/// larger. A far sliver keeps the home part's value and jumps itself; a home sliver (eq. 22 holds
/// the node's largest part then) jumps to that part's value, instead of dragging it along. One piece per enrichment suffices: the old field takes the same phantom value on all of
/// C, because C lay inside one old part. The map is linear, so displacement, velocity and
/// acceleration go through it alike, and the kinetic and elastic energies are unchanged: the same
/// field, integrated by rules exact for it (asserted in tests/chapter_07).
///
/// Branch functions (chapter 5) do not obey the rule: they depend on where the front is, and the
/// front moves when the cut grows, so no choice of the new DOFs reproduces the old field in the
/// tets they act in. Keeping each node's four values (their functions now about the new front)
/// changes the field there by the change of the functions times those values: chapter 7
/// measured +19 % and +20 % of the elastic energy at two rebuilds, and a run that then diverged.
/// Instead the field near the front is fitted: every DOF node of the new model (standard, sign
/// or branch) that acts in a tet with branch functions, in the old model or the new, is chosen so
/// that the new field is the closest one to the old field in an H1 norm over the tets those DOFs
/// act in,
///
///   min int_R |grad (u_new - u_old)|^2 + |u_new - u_old|^2 / l^2 dV,   l = the size of a tet near the front,
///
/// with every other DOF fixed by the rule above (and the held ones, a DofMap's prescribed DOFs,
/// kept). Where the old field lies in the new space (away from the front) the fit reproduces it;
/// near the front it is the best the new functions can do. The gradient term is what matters:
/// a fit in L2 alone (tried first) matched the displacements closely and still raised the elastic
/// energy by 180 %, since nothing held the gradients of the new functions, and keeping each node's
/// branch values raised it by 132 % (the old front's opening, carried by branch functions,
/// collapses into the linear pieces of the now split tets). tests/chapter_07 asserts the fit's
/// change. The fit is linear in q too: CutStateTransfer builds it once per change of the cut (the
/// geometry, the normal equations and their factorisation) and applies it to u, v and a.
#pragma once

#include "kerf/fem/dof_map.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"

#include <Eigen/Core>
#include <memory>
#include <utility>
#include <vector>

namespace kerf {

/// What the branch DOFs of the new model take at a change of the cut (the file's comment).
enum class BranchStateRule : signed char {
  fit,        ///< the enrichment DOFs near the front fitted to the old field in L2 (the default)
  keep_values ///< each node branch enriched in both models keeps its four values; kept as the baseline the fit is measured against
};

/// The linear map from the DOFs of `from` to those of `to` that carries the field over (the
/// file's comment), built once for a pair of models and applied to each state vector. Keeps
/// nothing of the models: they may go once it is built.
class CutStateTransfer {
public:
  /// @param from the model before the cut grew (its mesh is `to`'s)
  /// @param to   the model of the grown cut
  /// @throws std::invalid_argument if the models are on meshes with different node counts
  /// @param rule what the branch DOFs take
  /// @param held the new model's DofMap, or nullptr. With it, the enrichments it holds (a gripped
  ///             node's, a sliver's: eq. 22) take 0, the value they will have in the step, and
  ///             where that glues a part to the home part the lighter of the two moves (the
  ///             file's comment); the fit leaves them as they are. Without it every enrichment
  ///             takes the rule's value.
  CutStateTransfer(const CutXfemModel& from, const CutXfemModel& to, BranchStateRule rule = BranchStateRule::fit,
                   const DofMap* held = nullptr);
  CutStateTransfer(CutStateTransfer&&) noexcept;
  CutStateTransfer& operator=(CutStateTransfer&&) noexcept;
  ~CutStateTransfer();

  /// @param q 3 from.num_dof_nodes() values: a displacement, velocity or acceleration
  /// @return  3 to.num_dof_nodes() values
  /// @throws std::invalid_argument if q has the wrong size
  Eigen::VectorXd operator()(const Eigen::VectorXd& q) const;
  /// The number of enrichment DOF nodes the fit near the front chooses (0 without branch functions).
  Eigen::Index num_fitted() const;
  /// The number of quadrature points the fit integrates over.
  Eigen::Index num_fit_points() const;

private:
  struct Fit;
  // The fit near the front, assembled and factorised; null if no DOF acts near a front.
  static std::unique_ptr<Fit> make_fit(const CutXfemModel& from, const CutXfemModel& to, const DofMap* held);
  Eigen::Index from_dof_nodes_ = 0, to_dof_nodes_ = 0, num_nodes_ = 0;
  // The rule of phantom values, in offsets from the old u_i: per enrichment DOF node e of `to`
  // (index e - N), the DOF node of `from` holding the old phantom value on its part minus the
  // old u_i (an old enrichment), or -1 for 0 (the old home part); per node i of `to`, the same
  // for the part the new u_i stands for, its anchor (its home part, or the held part that
  // outweighs it: the file's comment).
  std::vector<int> enrichment_source_, anchor_source_;
  // Per enrichment DOF node of `to` (index e - N): its node, or -1 for a branch DOF node.
  std::vector<int> to_enrichment_node_;
  // The enrichment DOF nodes the new DofMap holds, which take 0 (their part moves with u_i).
  std::vector<int> held_enrichments_;
  // keep_values: for each node branch enriched in both models, the first DOF node of its four
  // functions in `to` and in `from` (branch_dof_node).
  std::vector<std::pair<Eigen::Index, Eigen::Index>> kept_branch_nodes_;
  std::unique_ptr<Fit> fit_; // null without branch functions in either model, or with keep_values
};

/// The DOF vector of `to` that gives the field of `q` on `from`: CutStateTransfer(from, to)(q).
/// @param from the model before the cut grew (its mesh is `to`'s)
/// @param to   the model of the grown cut
/// @param q    3 from.num_dof_nodes() values: a displacement, velocity or acceleration
/// @return     3 to.num_dof_nodes() values
Eigen::VectorXd transfer_cut_state(const CutXfemModel& from, const CutXfemModel& to, const Eigen::VectorXd& q);

} // namespace kerf
