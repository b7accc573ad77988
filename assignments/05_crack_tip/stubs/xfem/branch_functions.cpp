// Assignment 05 (assignments/05_crack_tip/README.md): the four crack-tip (branch) functions and
// their gradients. This file replaces common/src/xfem/branch_functions.cpp in the graded build;
// the declarations, with their full comments, are in kerf/xfem/branch_functions.hpp.
#include "kerf/xfem/branch_functions.hpp"

#include <cmath>
#include <stdexcept>

namespace kerf {

/// The four functions of r and theta (Paulus section 3.4; Fleming et al. 1997):
///   F(r, theta) = sqrt(r) ( sin(theta/2), cos(theta/2), sin(theta/2) sin(theta), cos(theta/2) sin(theta) ),
/// entry l = 0..3 for the paper's F_1..F_4 (m^1/2). Only F_1 jumps across the cut theta = +-pi.
Eigen::Vector4d branch_function_values([[maybe_unused]] double r, [[maybe_unused]] double theta) {
  throw std::logic_error("assignment 05: implement branch_function_values (assignments/05_crack_tip/README.md)");
}

/// The derivatives of the four functions along the front's frame (in closed form;
/// d/dx_c = 0): row l is F_{l+1}, column 0 is dF/dx_a, column 1 is dF/dx_b, with
///   d/dx_a = cos(theta) d/dr - sin(theta) / r d/dtheta,   d/dx_b = sin(theta) d/dr + cos(theta) / r d/dtheta.
/// They grow like 1 / sqrt(r). @param r > 0 (at r = 0 they are unbounded; the caller guards)
Eigen::Matrix<double, 4, 2> branch_function_frame_derivatives([[maybe_unused]] double r, [[maybe_unused]] double theta) {
  throw std::logic_error("assignment 05: implement branch_function_frame_derivatives (assignments/05_crack_tip/README.md)");
}

/// F and grad F at a point given its polar coordinates about the front (FrontPolar: r, theta and
/// the gradients grad x_a, grad x_b of its frame coordinates):
///   grad F_l = dF_l/dx_a grad x_a + dF_l/dx_b grad x_b   (row l of BranchValues::dF_dx, 1 by 3).
/// Exactly on the front (r = 0, or any r that is not > 0) F = 0 and the gradient, unbounded there,
/// is returned as 0: never a NaN.
BranchValues branch_functions([[maybe_unused]] const FrontPolar& polar) {
  throw std::logic_error("assignment 05: implement branch_functions (assignments/05_crack_tip/README.md)");
}

/// Node i's four shifted enrichment functions (Paulus eq. 3 in the shifted form)
///   N_i(x) (F_l(x) - F_l(x_i)),   gradient  grad N_i (F_l(x) - F_l(x_i)) + N_i grad F_l(x),
/// which vanish at every node. at_x is branch_functions at x, at_node is F at the node x_i.
BranchValues shifted_branch_functions([[maybe_unused]] double N_i, [[maybe_unused]] const Eigen::Vector3d& grad_N_i,
                                      [[maybe_unused]] const BranchValues& at_x, [[maybe_unused]] const Eigen::Vector4d& at_node) {
  throw std::logic_error("assignment 05: implement shifted_branch_functions (assignments/05_crack_tip/README.md)");
}

} // namespace kerf
