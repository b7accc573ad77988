/// @file phantom_piece.hpp
/// @brief One piece of a tet as the cut XFEM model integrates it: the phantom element's slots and the rule's points.
///
/// On piece p of a cut tet every sign enrichment is constant, so the field there is an ordinary
/// Tet4 or Tet10 field with nodal values u_p,a = u_a + a_k, k the enrichment of node a active on
/// p: the piece's "phantom" element (cut_xfem_model.hpp). A PhantomPiece says which of the tet's
/// slots holds each a_k, and keeps the points of the piece's quadrature rule with the shape
/// functions' values and gradients there, computed once: Newton and the time steps assemble the
/// same points again and again. A tet integrated whole is one PhantomPiece on its own rule.
#pragma once

#include "kerf/fem/linear_material.hpp"
#include "kerf/quadrature/piece_quadrature_rule.hpp"

#include <Eigen/Core>
#include <cstddef>
#include <memory>
#include <vector>

namespace kerf {

/// One quadrature point of a piece: its weight and the n shape functions' values and physical
/// gradients there. Fixed at the Tet10's size, a Tet4 uses the first 4 rows: no allocation per point.
struct PiecePoint {
  Eigen::Matrix<double, 10, 3> G = Eigen::Matrix<double, 10, 3>::Zero(); ///< dN_a/dx (m^-1), n rows used
  Eigen::Matrix<double, 10, 1> N = Eigen::Matrix<double, 10, 1>::Zero(); ///< N_a at the point, n entries used
  double weight = 0.0;                                                    ///< m^3; moment fitting may make it negative
};

/// One piece of a tet: its phantom element's slots and its points.
struct PhantomPiece {
  /// n entries: the slot (a column of the tet's row of assembly_slots(), >= n) of the enrichment
  /// that node a's phantom value takes on this piece, u_p,a = u_a + a_k; -1: none, u_p,a = u_a.
  std::vector<int> enrichment_slot;
  std::vector<PiecePoint> points;
  /// A Tet4 piece outside the tets with branch functions: the phantom element's stiffness over
  /// the piece (eq. 30), computed once (tet4_piece_stiffness). A Tet4's gradients are constant,
  /// so a step only turns it (R K_p R^T) and never rebuilds it. Shared by the copies of the piece
  /// (a model rebuilt after the cut grew keeps it); null on a Tet10 and in tets with branch functions.
  std::shared_ptr<const Eigen::Matrix<double, 12, 12>> tet4_stiffness = nullptr;
};

/// J = [x1 - x0, x2 - x0, x3 - x0] (3x3): the straight-edged tet with corners X maps reference
/// coordinates xi to x = x0 + J xi.
Eigen::Matrix3d tet_corner_jacobian(const Eigen::Matrix<double, 4, 3>& X);

/// The point at reference coordinates xi of a straight-edged tet whose J has the inverse
/// J_inverse: `weight` (m^3), and the n (4 or 10) shape functions' values and gradients there.
PiecePoint piece_point_at_reference(const Eigen::Vector3d& xi, const Eigen::Matrix3d& J_inverse, double weight, int n);

/// The points of a rule given in physical coordinates (piece_quadrature_rule.hpp), in the tet
/// with corners X and n nodes, with the shape functions there.
std::vector<PiecePoint> piece_points(const PieceQuadratureRule& rule, const Eigen::Matrix<double, 4, 3>& X, int n);

/// The stiffness of one phantom element over the points, sum_q w_q B_q^T C B_q (eq. 30), 3n x 3n.
Eigen::MatrixXd phantom_piece_stiffness(const std::vector<PiecePoint>& points, int n, const LinearMaterial& material);

/// The same for a Tet4 piece from its first point's gradients (all are equal) and the total
/// weight: the one point the assembly takes for a Tet4 piece (12x12).
std::shared_ptr<const Eigen::Matrix<double, 12, 12>> tet4_piece_stiffness(const std::vector<PiecePoint>& points,
                                                                            const LinearMaterial& material);

/// The value at point q of each slot's phantom function, g (one entry per slot of the tet, set
/// to zero first): N_a on node a's slot and on the slot of the enrichment active for node a.
void phantom_slot_values(const PhantomPiece& piece, std::size_t q, int n, Eigen::VectorXd& g);

/// The same for the gradients, one row per slot: G_a on node a's slot and on its enrichment's.
void phantom_slot_gradients(const PhantomPiece& piece, std::size_t q, int n, Eigen::MatrixX3d& g);

} // namespace kerf
