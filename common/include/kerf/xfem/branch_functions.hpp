/// @file branch_functions.hpp
/// @brief The four asymptotic crack-tip (branch) functions, their closed-form gradients, and their shifted form N_i (F_l - F_l(x_i)) (Paulus section 3.4).
///
/// Near the front of a crack the displacement of linear elasticity behaves like sqrt(r) times
/// functions of theta (Williams 1957). The four functions
///
///   F(r, theta) = sqrt(r) ( sin(theta/2), cos(theta/2), sin(theta/2) sin(theta), cos(theta/2) sin(theta) )
///
/// (Fleming et al. 1997, Belytschko and Black 1999; Paulus section 3.4) span the first term of
/// that expansion for every mode: mode I is u_a = K_I / (2 mu sqrt(2 pi))
/// ((kappa - 1) F_2 + F_3) and u_b = K_I / (2 mu sqrt(2 pi)) ((kappa + 1) F_1 - F_4). Only F_1 is
/// discontinuous across the cut (theta = +-pi), with the jump 2 sqrt(r); the others are continuous.
///
/// Kerf uses them shifted (Paulus does not; Belytschko et al. 2001, Ventura et al. 2009): node i's four enrichment
/// functions are N_i(x) (F_l(x) - F_l(x_i)), which vanish at every node, so the nodal unknown u_i
/// is the displacement there (chapter 3's Kronecker property) and Dirichlet values are imposed by
/// fixing u_i alone. F_l(x_i) is taken with the node's side when the node lies on the cut
/// (CrackFronts::polar's cut_side).
#pragma once

#include "kerf/cut/crack_front.hpp"

#include <Eigen/Core>

namespace kerf {

/// F_l and grad F_l at one point (l = 0..3 for the paper's F_1..F_4).
struct BranchValues {
  Eigen::Vector4d F = Eigen::Vector4d::Zero();                    ///< F_l (m^1/2)
  Eigen::Matrix<double, 4, 3> dF_dx = Eigen::Matrix<double, 4, 3>::Zero(); ///< row l: grad F_l in x (m^-1/2)
};

/// The four functions of r and theta.
Eigen::Vector4d branch_function_values(double r, double theta);

/// The derivatives of the four functions along the frame's a and b (derived in closed form,
/// not in the paper; d/dx_c = 0), column 0 d/dx_a, column 1 d/dx_b. They grow like 1 / sqrt(r).
/// @param r > 0 (at r = 0 they are unbounded; the caller guards)
Eigen::Matrix<double, 4, 2> branch_function_frame_derivatives(double r, double theta);

/// F and grad F at a point given its polar coordinates: grad F_l = dF_l/dx_a grad x_a +
/// dF_l/dx_b grad x_b (with a and b for grad x_a and grad x_b, the frame treated as
/// constant, as Paulus does: exact for a straight front). On a polyline front the frame turns
/// along it, and CrackFronts::polar gives grad x_a and grad x_b with that turning: treating the
/// frame as constant there was 2.4 % off on a 64-chord arc (test_branch_functions.cpp), the
/// derivative of the function actually used agrees with finite differences.
/// Exactly on the front (r = 0) F = 0 and the gradient, unbounded there, is returned as 0: no
/// quadrature rule of this chapter puts a point on the front, and a NaN would be worse.
BranchValues branch_functions(const FrontPolar& polar);

/// Node i's four shifted enrichment functions N_i (F_l - F_l(x_i)) and their gradients
/// grad N_i (F_l - F_l(x_i)) + N_i grad F_l.
/// @param N_i      the node's shape function at x
/// @param grad_N_i its gradient at x (1/m)
/// @param at_x     branch_functions at x
/// @param at_node  F at the node, branch_function_values there (with its cut side)
BranchValues shifted_branch_functions(double N_i, const Eigen::Vector3d& grad_N_i, const BranchValues& at_x,
                                      const Eigen::Vector4d& at_node);

} // namespace kerf
