/// @file corotated_piece.hpp
/// @brief A corotated element on general "slots" with one rotation for the whole piece: how
///        chapter 5 turns a tet with crack-tip functions with the tissue.
///
/// corotated_element.hpp rotates one quadrature point of an ordinary element: its shape gradients
/// G are constant there, and F = I + u^T G. A tet with branch functions has, besides its nodes'
/// slots, sign slots and four branch slots per branch corner, and the branch functions'
/// gradients grow like r^(-1/2) towards the front: a rotation per point would turn the points
/// next to the front by their singular strain. Kerf gives such a piece ONE rotation, that of its
/// mean deformation gradient
///
///   F_bar = sum_s x_s g_bar_s^T,   g_bar_s = (1 / V_p) int_p grad(phi_s) dV,
///
/// where phi_s is slot s's function (N_a; N_a on the piece for a sign slot; the shifted branch
/// function) and x_s the slot's "position": X_a + u_a for a node's own slot, the coefficient
/// q_s for an enriched one (enrichments add nothing to the geometry, and sum_a X_a g_bar_a^T = I).
/// The mean exists though the gradient is singular (r^(-1/2) is integrable). With F_bar = R S,
///
///   d_s = R^T (x_s - x_0) - (X_s - X_0)  for node slots,  d_s = R^T q_s  for enriched slots,
///   f  += R K d,          Kt += R K R^T  (+ the terms from dR, consistent tangent),
///
/// K the piece's linear stiffness on its slots (eq. 30 over the piece). This is the warped
/// stiffness of Mueller and Gross applied to the piece: in a rigid rotation Q of the piece and
/// its enrichment coefficients, F_bar turns into Q F_bar, R into Q R, d is unchanged and f turns
/// into Q f: no ghost forces. The consistent tangent differentiates f with R moving, dR = R W,
/// W = [w]_x, (tr(S) I - S) w = g_bar_s x r_c for a move of slot s along e_c (r_c = row c of R),
/// as corotated_element.hpp does for a point:
///
///   d f = R (w x (K d)_t)_t + R K (d_u x w)_u   with  d_u = R^T x_u  (the rotated positions).
///
/// Unlike a point of corotated_element.hpp, f is not exactly the gradient of 1/2 d^T K d when F
/// varies across the piece (R is the mean's, not each point's): the difference is of the order of
/// the strain's variation times the rotation, and CutXfemModel::energy says so.
#pragma once

#include "kerf/corotation/corotated_element.hpp"
#include "kerf/corotation/corotation_statistics.hpp"

#include <Eigen/Core>

namespace kerf {

/// F_bar = sum_s x_s g_bar_s^T with x_s = X_s + q_s on the first num_node_slots slots and q_s on
/// the others (the arguments as for add_corotated_piece).
Eigen::Matrix3d piece_mean_deformation_gradient(const Eigen::MatrixX3d& mean_gradient, int num_node_slots, const Eigen::MatrixX3d& X,
                                                const Eigen::MatrixX3d& q);

/// d (3S): d_s = R^T (x_s - x_0) - (X_s - X_0) on the node slots, measured from node 0 as in
/// corotated_element.hpp (no round-off of absolute coordinates; K annihilates the translation),
/// and d_s = R^T q_s on the enriched ones. With R = I it is q up to that translation.
Eigen::VectorXd corotated_piece_displacement(const Eigen::Matrix3d& R, int num_node_slots, const Eigen::MatrixX3d& X,
                                             const Eigen::MatrixX3d& q);

/// Adds a piece's corotated force and tangent.
/// @param K            the piece's linear stiffness on its S slots (3S x 3S)
/// @param mean_gradient S x 3: row s is g_bar_s, slot s's gradient averaged over the piece
/// @param num_node_slots the first slots that are the element's nodes (their X rows are positions)
/// @param X            S x 3: the nodes' reference positions in the first num_node_slots rows, 0 below
/// @param q            S x 3: each slot's unknowns (u_a for a node, the coefficient for an enrichment)
/// @param volume       the piece's volume (m^3), for `statistics`
/// @param f            3S: the force is added here
/// @param Kt           3S x 3S: the tangent is added here when given
/// @return the piece's rotation
PolarDecomposition add_corotated_piece(const Eigen::MatrixXd& K, const Eigen::MatrixX3d& mean_gradient, int num_node_slots,
                                       const Eigen::MatrixX3d& X, const Eigen::MatrixX3d& q, double volume,
                                       RotationMethod method, CorotationalTangent tangent, Eigen::VectorXd& f,
                                       Eigen::MatrixXd* Kt, CorotationStatistics* statistics = nullptr);

} // namespace kerf
