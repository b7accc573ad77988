/// @file hinged_fragments.hpp
/// @brief The fragments of a cut body that its holds pin at one point or along one line, and the DofMap that
///        lets them go.
///
/// Why they matter. The frozen corotated step (Mueller and Gross; nonlinear_newmark.hpp) takes each
/// element's rotation at the start of the step, so a body that turns by theta in a step moves
/// along the tangent of its turn instead: every point at distance r from the axis ends the step
/// r (sqrt(1 + theta^2) - 1) too far out. For tissue that its neighbours hold, theta is a
/// fraction of a degree and the stretch is the small lag the step is known for. A fragment that
/// nothing holds against turning, hung from a point beside it, is a pendulum: gravity swings a
/// centimetre-sized one at up to sqrt(2 g / L) ~ 40 rad/s, tens of degrees per 10 ms step. Then
/// each step's stretch is stored as strain, whose force the next step again applies along a
/// tangent: the energy grows by about 1 + theta^2 per step. Chapter 7 measured a chip of 0.37 mm^3
/// turning 55 degrees a step, stretched by 1.45 a step, its energy growing by 2.2 a step, until the
/// run stopped as diverged; a single tet held at one corner under gravity does the same
/// (tests/chapter_07/test_hinged_fragments.cpp). Newton's step follows the turn and does not.
///
/// Where the point comes from. A held enrichment, a_k = 0, gives the part it acts on node i's
/// value u_i there: make_cut_xfem_dof_map holds every enrichment of a gripped node (the clamp
/// holds the tissue on every side of a cut through it) and every sliver's (Koschier et al.
/// 2017, eq. 22). Where the cuts have carved a fragment out of the body, and those holds pin it
/// at one node or at nodes on one line, the fragment turns freely about them: a ball joint or a
/// hinge through nodes it does not contain, which no tissue makes. Several parallel passes of
/// chapter 7's blade beside the held back of the liver leave such fragments between the sheets.
///
/// What we do. Let them go: a hinged fragment's held enrichments become free, and it is a free
/// piece like any the cut frees (chapter 6), which falls. The field does not change when they go
/// (those enrichments were 0 and start free at 0), so no energy is put in. A fragment that holds
/// a gripped node of its own is hinged by the Dirichlet condition itself: it is reported, and
/// kept. The frozen step's limit stays: a piece that turns faster than about 0.13 rad a step for
/// another reason (a sliver left free, pieces pinned across a cut in a region the body holds by
/// slivers only) still makes it diverge (chapter 7's results, "Known defects").
///
/// How. The fragments are the integrated pieces (with volume) joined where they share a phantom
/// node, a DOF node: the same part of a node's support, whose pieces in neighbouring tets share
/// the face between them. A fragment is attached at a gripped node it contains, and at node i
/// where a held enrichment of i pins it, if u_i is held or node i's home part lies in another
/// fragment. It is hinged when it has attachments and they span no plane (fewer than three not on
/// one line). An unattached fragment is free already. Two passes over the pieces, and none where
/// no enrichment is held: at 10k tets 1.7 ms a change of seven passes beside the held back, 6
/// microseconds in chapter 7's demo, which holds none.
#pragma once

#include "kerf/fem/dof_map.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"

#include <Eigen/Core>
#include <vector>

namespace kerf {

/// A fragment of the cut body that its holds pin at one point or along one line (the file's comment).
struct HingedFragment {
  double volume = 0.0;                             ///< the sum of its pieces' volumes, as their rules see them (m^3)
  Eigen::Vector3d point = Eigen::Vector3d::Zero(); ///< the centroid of the tet of its largest piece (m)
  std::vector<int> hinge_nodes;                    ///< the mesh nodes it is attached at, in increasing order
  /// The held enrichment DOF nodes N + k its pieces use, in increasing order: the pins.
  std::vector<int> held_enrichments;
  /// Whether it holds a gripped node of its own (its home part there): a hinge the Dirichlet
  /// condition makes, which release_hinged_fragments keeps.
  bool held_at_own_node = false;
};

/// The hinged fragments of `model` under `dofs`, in the order of their first piece.
/// @param model the cut body
/// @param dofs  its DofMap (make_cut_xfem_dof_map's): 3 num_dof_nodes() entries
/// @throws std::invalid_argument if `dofs` is not the model's
std::vector<HingedFragment> hinged_fragments(const CutXfemModel& model, const DofMap& dofs);

/// `dofs` with the held enrichments of every hinged fragment free (the file's comment), the
/// free DOFs renumbered in increasing order as make_dof_map numbers them. Letting a fragment go
/// can leave another hinged on it; the test is repeated until none is left that an enrichment pins.
/// @param model    the cut body
/// @param dofs     its DofMap (make_cut_xfem_dof_map's): 3 num_dof_nodes() entries
/// @param released if given, receives the fragments let go
/// @throws std::invalid_argument if `dofs` is not the model's
DofMap release_hinged_fragments(const CutXfemModel& model, const DofMap& dofs,
                                std::vector<HingedFragment>* released = nullptr);

} // namespace kerf
