/// @file piece_quadrature_rule.hpp
/// @brief A quadrature rule for one piece of a cut tet, in physical coordinates, and the six ways chapter 4 builds one.
///
/// A tet cut by a triangle mesh falls into pieces (tet_pieces.hpp). On each piece the XFEM
/// integrands are smooth (every enrichment psi is constant there), so each piece gets a rule
/// of its own: int_piece f dV ~ sum_q w_q f(x_q) (Koschier eq. 16 with the per-subdomain weights
/// w_{i,j}).
///
/// Points may lie outside the piece, even outside the tet: moment fitting puts its points where
/// the reference tet has them whatever the cut. The integrand at such a point is then the
/// piece's SMOOTH EXTENSION h_i, not the true (discontinuous) integrand: evaluate every psi with
/// the value it has on this piece, whichever side of the cut x_q lies on (eq. 16
/// leaves this open; this is its only consistent reading). Evaluating the true h there is wrong.
#pragma once

#include "kerf/cut/tet_pieces.hpp"

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

namespace kerf {

/// int_piece f dV ~ sum_q weights[q] f(points[q]).
struct PieceQuadratureRule {
  std::vector<Eigen::Vector3d> points; ///< x_q in physical coordinates (m); may lie outside the piece
  std::vector<double> weights;         ///< w_q (m^3); moment-fitted weights may be negative
};

/// The rule for piece `piece` of a cut tet with corners X, exact to `degree` on that piece: what
/// the XFEM model asks for every piece it integrates (cut_xfem_model.hpp), so that any rule can
/// be plugged in (scene_quadrature.hpp makes one from the scene's "quadrature" field).
using PieceRuleFunction = std::function<PieceQuadratureRule(const Eigen::Matrix<double, 4, 3>& X, const TetPieces& pieces,
                                                             int piece, int degree)>;

/// The ways of building a piece's rule that chapter 4 compares (Koschier et al. 2017, Table 1,
/// and the sub-tetrahedra of Schoch et al. 2013 and Paulus et al.).
enum class QuadratureRuleKind {
  exact,          ///< moment fitting on fixed points with exact moments (moment_fitting.hpp): exact to `degree`
  subtets,        ///< Gauss on every tet of the piece's convex cells (Schoch, Paulus): exact to `degree`
  moment_fitting, ///< Koschier's moment fitting with fitted face and interface rules (koschier_moment_fitting.hpp)
  volume_ratio,   ///< the whole tet's Gauss rule scaled by V_piece / V (Schoch eqs. 54-63): exact for constants only
  lattice,        ///< Paulus's oversampling: centroids of n^3 congruent sub-tets that lie in the piece
  regular,        ///< Kaufmann's regular sampling: cell centres of an n^3 grid on the tet's bounding box
};

/// "exact", "subtets", "moment_fitting", "volume_ratio", "lattice", "regular".
const char* to_string(QuadratureRuleKind kind);

/// The kind named `name` (one of to_string's names); throws std::invalid_argument otherwise.
QuadratureRuleKind parse_quadrature_rule_kind(const std::string& name);

/// What a rule needs beyond the piece.
struct PieceRuleOptions {
  int degree = 2;            ///< degree of exactness (exact, subtets, moment_fitting: 1 or 2, volume_ratio)
  int lattice_divisions = 5; ///< lattice: n, giving n^3 sub-tets (Paulus: the smallest n with n^3 > nIntPts)
  int regular_cells = 50;    ///< regular: n cells per side of the bounding box (Kaufmann, Koschier Table 1: 50)
};

/// The rule of kind `kind` for piece `piece` of the tet X cut by `triangles` into `pieces`
/// (the result of split_tet_by_triangles(X, triangles); only moment_fitting reads `triangles`).
PieceQuadratureRule piece_quadrature_rule(QuadratureRuleKind kind, const Eigen::Matrix<double, 4, 3>& X,
                                          const std::vector<CutTriangle>& triangles, const TetPieces& pieces, int piece,
                                          const PieceRuleOptions& options = {});

/// What a rule gives for the integrals of 1, x, y, z, x^2, y^2, z^2, xy, yz, xz (in this order,
/// m^3 ... m^5): the piece's volume, first and second moments as the rule sees them.
Eigen::Matrix<double, 10, 1> piece_moments(const PieceQuadratureRule& rule);

/// sum_q w_q f(x_q): the rule applied to an integrand given as a function of the point.
double integrate(const PieceQuadratureRule& rule, const std::function<double(const Eigen::Vector3d&)>& f);

/// The number of points with a nonzero weight (Koschier Table 1's "#QP").
int count_points(const PieceQuadratureRule& rule);

} // namespace kerf
