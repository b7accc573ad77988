/// @file tet_stiffness.hpp
/// @brief Element stiffness matrices of Tet4 (12x12) and Tet10 (30x30) in linear elasticity, eq. (30).
#pragma once

#include "kerf/fem/linear_material.hpp"

#include <Eigen/Core>

namespace kerf {

/// Adds weight times the integrand of eq. (30) to the element stiffness K (3n x 3n, node-major
/// DOFs 3a + p), given the physical shape gradients g (n x 3, row a = grad N_a) at one point:
///
///   dF_ip / dP_jq = mu g_iq g_jp + mu delta_pq (g_i . g_j) + lambda g_ip g_jq.
///
/// This is the form the paper derives in appendix 7.1 (eq. 96); it equals B^T C B with the
/// Voigt matrix of eq. (6), and it is cheaper: no 6 x 3n B matrix is formed.
///
/// Any number of rows: an enriched element's (chapter 5) has one per function, its gradients
/// those of the enrichment functions; K is then a dynamic-size matrix of 3 rows(g) squared.
template <typename Gradients, typename Stiffness>
void add_stiffness_integrand(const Gradients& g, double weight, double mu, double lambda, Stiffness& K) {
  for (Eigen::Index i = 0; i < g.rows(); ++i)
    for (Eigen::Index j = 0; j < g.rows(); ++j) {
      const Eigen::RowVector3d gi = g.row(i), gj = g.row(j);
      Eigen::Matrix3d block = mu * gj.transpose() * gi + lambda * gi.transpose() * gj;
      block.diagonal().array() += mu * gi.dot(gj);
      K.template block<3, 3>(3 * i, 3 * j) += weight * block;
    }
}

/// The sum of add_stiffness_integrand over many points at once, from the products of the
/// gradients A = sum_q w_q vec(g_q) vec(g_q)^T (3S x 3S, vec(g) = (g_0x, g_0y, g_0z, g_1x, ...)):
///
///   K_(i p),(j q) = mu A_(i q),(j p) + lambda A_(i p),(j q) + mu delta_pq sum_r A_(i r),(j r).
///
/// A is one matrix product over the points (a BLAS-3 operation), where the point-by-point sum
/// costs S^2 small blocks per point: chapter 5's front rules have thousands of points per piece.
inline Eigen::MatrixXd stiffness_from_gradient_products(const Eigen::MatrixXd& A, double mu, double lambda) {
  const Eigen::Index S = A.rows() / 3;
  Eigen::MatrixXd K(3 * S, 3 * S);
  for (Eigen::Index i = 0; i < S; ++i)
    for (Eigen::Index j = 0; j < S; ++j) {
      const Eigen::Matrix3d a = A.block<3, 3>(3 * i, 3 * j);
      Eigen::Matrix3d block = mu * a.transpose() + lambda * a;
      block.diagonal().array() += mu * a.trace();
      K.block<3, 3>(3 * i, 3 * j) = block;
    }
  return K;
}

/// The fixed-size form, n nodes: the compiler unrolls it for a Tet4 and a Tet10.
template <int n>
void add_stiffness_integrand(const Eigen::Matrix<double, n, 3>& g, double weight, double mu, double lambda,
                             Eigen::Matrix<double, 3 * n, 3 * n>& K) {
  add_stiffness_integrand<Eigen::Matrix<double, n, 3>, Eigen::Matrix<double, 3 * n, 3 * n>>(g, weight, mu, lambda, K);
}

/// Tet4 element stiffness (eq. 30 with constant gradients, times the volume), 12x12.
/// @param X 4x3 corner positions, positively oriented: det[x1-x0, x2-x0, x3-x0] > 0, or
///          std::invalid_argument (see positive_jacobian.hpp)
Eigen::Matrix<double, 12, 12> tet4_stiffness(const Eigen::Matrix<double, 4, 3>& X, const LinearMaterial& material);

/// Tet10 element stiffness, 30x30: eq. (30) integrated with the 4-point degree-2 rule, which
/// is exact for straight-edged Tet10 (their gradients are linear, the integrand quadratic).
/// @param X 10x3 node positions (Kerf's Tet10 order) with det J > 0 at the four points, or
///          std::invalid_argument (see positive_jacobian.hpp)
Eigen::Matrix<double, 30, 30> tet10_stiffness(const Eigen::Matrix<double, 10, 3>& X, const LinearMaterial& material);

} // namespace kerf
