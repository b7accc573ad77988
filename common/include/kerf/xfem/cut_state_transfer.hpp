/// @file cut_state_transfer.hpp
/// @brief When a cut grows during a run, the state of the old model in the DOFs of the new one, with the field unchanged (notes 7.2, "DOF state at the moment of cutting").
///
/// Chapter 7's blade cuts while the body moves: each time a tet becomes crossed the model is
/// rebuilt on the longer cut, with more enrichments. Its displacement, velocity and acceleration
/// vectors must be carried over. No paper says how (notes 7.6, question 6); the standard answer
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
/// enrichment starts at zero, as the notes say) and the old a for a part that already was a far
/// part. One piece per enrichment suffices: the old field takes the same phantom value on all of
/// C, because C lay inside one old part. The map is linear, so displacement, velocity and
/// acceleration go through it alike, and the kinetic and elastic energies are unchanged: the same
/// field, integrated by rules exact for it (asserted in tests/chapter_07).
///
/// Branch functions (chapter 5) do not obey the rule: they depend on where the front is, and the
/// front moves when the cut grows. A node branch-enriched in both models keeps its four values
/// (their functions are now about the new front), a new one starts at 0. The field then changes in
/// the branch tets by the change of the functions times the old values; chapter 7's results
/// measure it.
#pragma once

#include "kerf/xfem/cut_xfem_model.hpp"

#include <Eigen/Core>

namespace kerf {

/// The DOF vector of `to` that gives the field of `q` on `from` (the file's comment).
/// @param from the model before the cut grew (its mesh is `to`'s)
/// @param to   the model of the grown cut
/// @param q    3 from.num_dof_nodes() values: a displacement, velocity or acceleration
/// @return     3 to.num_dof_nodes() values
Eigen::VectorXd transfer_cut_state(const CutXfemModel& from, const CutXfemModel& to, const Eigen::VectorXd& q);

} // namespace kerf
