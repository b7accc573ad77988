/// @file moment_fitting.hpp
/// @brief Moment fitting on fixed points of the tet (Koschier eqs. 16-17) with exact moments: the rule "exact".
///
/// Koschier's idea: keep the points fixed (the same reference points for every cut tet) and fit
/// only the weights, per piece, so that the rule integrates a basis P_1..P_M of polynomials
/// exactly (eq. 17):
///
///   sum_j P_i(xi_j) w_j = int_piece P_i,   i = 1..M.
///
/// The matrix A_ij = P_i(xi_j) (M x N) does not depend on the cut, so its pseudo-inverse is
/// computed once per (degree, point set) and reused for every piece of every tet; a piece then
/// costs its M moments and one (N x M) product. We take N > M points (an underdetermined
/// system) and the minimum-norm weights w = A^+ b (Koschier section 5, step 4).
///
/// The moments b come from polyhedron_moments.hpp, exactly (as Mirtich 1996 does for rigid
/// bodies), so the rule integrates every polynomial of degree <= `degree`
/// over the piece to round-off, on planar, kinked and folded cuts alike. Points lie where the
/// reference tet has them, mostly outside a small piece: see piece_quadrature_rule.hpp for what
/// the integrand must be there (the piece's smooth extension, Koschier eq. 16).
#pragma once

#include "kerf/quadrature/piece_quadrature_rule.hpp"
#include "kerf/quadrature/simplex_polynomials.hpp"

#include <string>

namespace kerf {

/// The fixed part of eq. 17 for one degree: basis, points, and A's pseudo-inverse.
struct MomentFittingSystem {
  int degree = 0;
  OrthonormalBasis3d basis;                      ///< M orthonormal polynomials on the reference tet
  std::vector<Eigen::Vector3d> points;           ///< the N reference points xi_j
  std::string point_set;                         ///< how the points were chosen, for reports
  Eigen::MatrixXd pseudo_inverse;                ///< A^+, N x M (singular values below cutoff x the largest dropped)
  int rank = 0;                                  ///< A's numerical rank: M when the points are unisolvent
  double condition = 0.0;                        ///< sigma_max / sigma_min of A (the kept ones)
  static constexpr double cutoff = 1e-12;        ///< relative SVD cut-off (not in the paper)
};

/// The reference points of the fit of `degree` (1 <= degree <= 6):
/// - degree <= 2: the 24 points of Keast's symmetric degree-6 rule (Koschier's 24 volume points,
///   the paper names only Zhang et al. 2009; 24 is the size of that symmetric rule), for M = 4 or 10;
/// - degree >= 3: Stroud's conical product with n = degree + 1 points in each collapsed direction
///   ((degree + 1)^3 points: 64 for M = 20, 125 for degree 4 with M = 35). n = degree would not do:
///   a product of n Gauss-Jacobi points in u = xi_1 has (u - u_1)...(u - u_n), a polynomial of
///   degree n, vanishing at every point.
std::vector<Eigen::Vector3d> moment_fitting_points(int degree, std::string* description = nullptr);

/// Eq. 17's matrix and pseudo-inverse for `degree`, built on first use and kept (thread-safe).
const MomentFittingSystem& tet_moment_fitting_system(int degree);

/// The weights of the fit in reference coordinates for the moments b (M values, the integrals
/// of the basis over the piece mapped onto the reference tet): A^+ b.
Eigen::VectorXd fit_reference_weights(const MomentFittingSystem& system, const Eigen::VectorXd& basis_moments);

/// The rule "exact": the moments of the piece by the divergence theorem, fitted on the system
/// of `degree`, mapped to physical coordinates (w = w_ref |det J|).
PieceQuadratureRule exact_moment_fitting_rule(const Eigen::Matrix<double, 4, 3>& X, const TetPieces& pieces, int piece,
                                              int degree);

} // namespace kerf
