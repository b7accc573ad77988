/// @file branch_null_space.hpp
/// @brief The two identities among the four branch functions, the null vectors they give the stiffness where every corner of every tet with branch functions is enriched (Fries's corrected XFEM on a straight front), and the branch DOFs that remove them.
///
/// With x_a = r cos(theta) and x_b = r sin(theta) the four functions of branch_functions.hpp obey
///
///   x_b F_1 + x_a F_3 - x_b F_4 = 0,     x_b F_2 - x_b F_3 - x_a F_4 = 0
///
/// (derived: r^{3/2} sin(theta) [sin(theta/2) + cos(theta) sin(theta/2) - sin(theta) cos(theta/2)]
/// = 0, since cos(theta) sin(theta/2) - sin(theta) cos(theta/2) = -sin(theta/2); the second the
/// same with cos(theta - theta/2) = cos(theta/2)). On a straight front x_a and x_b are linear in
/// x, so the nodal hats reproduce them: sum_v lambda_v x_b(x_v) = x_b in every tet. Give every
/// branch slot v the coefficients
///
///   N_1:  b_{v,1} = x_b(x_v) e,  b_{v,3} = x_a(x_v) e,  b_{v,4} = -x_b(x_v) e
///   N_2:  b_{v,2} = x_b(x_v) e,  b_{v,3} = -x_b(x_v) e, b_{v,4} = -x_a(x_v) e      (e any vector)
///
/// and the field sum_v lambda_v (R F_l - R(x_v) F_l(x_v)) b_{v,l} is R times the identity minus
/// the interpolant of R times the identity: zero, in every tet whose four corners all have slots.
/// Without Fries's correction the tets at the edge of the enriched zone have some corners without
/// slots, the sum of their hats is not x_b, and the field is not zero there: no null vector (a
/// near one, part of why the conditioning grows with the radius, test_tip_conditioning.cpp).
/// With the correction every corner of every tet with branch functions has a slot, so each
/// connected region of such tets has the six null vectors (two identities, three components),
/// unless Dirichlet conditions hold some of their DOFs. The displacement field does not see them,
/// but a Cholesky factorisation fails.
///
/// The cure keeps the space of fields: hold b_{v0,1} and b_{v0,2} at 0 at the slot v0 of largest
/// |x_b|. N_1 is the only one with b_{v0,1} != 0 and N_2 the only one with b_{v0,2} != 0, so any
/// field of the space is still reached (add the multiple of N_1, N_2 that zeroes them), and the
/// two null directions are gone. On a curved front, or with several fronts, x_a and x_b are not
/// linear: the vectors are then near-null, not null, and are left alone (no DOF is held).
#pragma once

#include "kerf/fem/dof_map.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"

#include <utility>
#include <vector>

namespace kerf {

/// One null vector of the branch block, the same for each of the three components: (DOF node,
/// coefficient) pairs; DOF node = CutXfemModel::branch_dof_node(k) + l for function l of slot k.
struct BranchNullVector {
  std::vector<std::pair<int, double>> coefficients;
};

/// N_1 and N_2 of every connected region of tets with branch functions whose corners all have
/// slots, on a single straight front (the header's comment); empty otherwise.
std::vector<BranchNullVector> branch_null_vectors(const CutXfemModel& model);

/// The branch DOF nodes to hold at 0 so that K_ff has no null vector from the identities: for
/// each vector of branch_null_vectors none of whose DOFs `dofs` prescribes, the DOF node of
/// function 1 (N_1) or 2 (N_2) at the region's slot of largest |x_b|.
std::vector<int> branch_gauge_dof_nodes(const CutXfemModel& model, const DofMap& dofs);

} // namespace kerf
