/// @file koschier_moment_fitting.hpp
/// @brief Koschier's moment fitting as printed (section 5, eqs. 14-21), with corrections to the printed equations: moments from fitted face and interface rules.
///
/// The volume rule is the one of moment_fitting.hpp (24 fixed points, orthonormal quadratics,
/// eq. 17, pseudo-inverse reused); what differs is the right-hand side. Koschier never
/// integrates over the piece: by the divergence theorem (eq. 18)
///
///   int_piece P_j = int_{tet faces, piece part} P^A_j . n  (1)  +  int_{cut, piece side} P^A_j . n  (2),
///
/// and both surface integrals come from rules that are themselves fitted:
/// (1) on each tet face, a 2D moment fit: 19 fixed points of the face (Dunavant's symmetric
///     degree-9 rule's points), an orthonormal basis of degree `degree` + 1 on the triangle, and
///     the moments of the face's part in the piece from its edges (Green's theorem, Gauss-Legendre
///     on each edge: Koschier's "1D, exact" level);
/// (2) on the cut, the interface rule (eqs. 19-20): 6 points on each relevant cut triangle (the
///     abscissae of the symmetric 6-point degree-4 triangle rule), the triangles NOT clipped to
///     the tet (points may lie outside), weights fitted so that the rule integrates the normal
///     flux of a divergence-free vector basis p^D_1..p^D_{M_D} of degree `degree` + 1
///     (M_D = 50 for degree 2), whose moments follow from (1) alone (eq. 21, corrected below).
///
/// Corrections to the printed equations:
/// - eq. 18: P^A_j = (1/3) (int P_j dxi_1, int P_j dxi_2, int P_j dxi_3); as printed, without the
///   1/3, div P^A_j = 3 P_j;
/// - eq. 21: the first integral is over the piece (a volume integral) and vanishes because
///   div p^D = 0, so int_cut p^D . n = - int_{faces} chi_i p^D . n, computed with the face rules;
/// - eq. 16: the integrand at a point outside the piece is the piece's smooth extension
///   (piece_quadrature_rule.hpp);
/// - the face rules and p^D have degree `degree` + 1 (P^A . n is cubic for quadratic P), not
///   stated in the paper.
///
/// The divergence-free basis: curl(m e_k) for every monomial m of degree 1..degree + 2 and axis
/// k spans the divergence-free fields of degree <= degree + 1 (the polynomial de Rham sequence
/// is exact); we orthonormalise them in L2 of the reference tet and keep the eigenvalues above
/// 1e-12 of the largest (50 fields for degree 2). Müller, Kummer and Oberlack's construction,
/// which Koschier cites, is not reproduced; any basis of the same space gives the same fit up
/// to round-off.
///
/// Subdivision (Koschier: "until there are about twice as many points as basis vectors"): the
/// largest sub-triangle is split into four at its edge midpoints until 6 x (sub-triangles)
/// >= 2 M_D; a child whose bounding box misses the tet's is dropped, since it is no longer a
/// "relevant" primitive (Koschier uses the triangles that meet the element).
///
/// Accuracy: (1) is exact for polynomials of degree `degree` + 1 (the face moments are exact
/// and the face fit has full rank). For a planar interface, (2) is exact too: on a plane every
/// polynomial of degree <= degree + 1 is the normal flux of a divergence-free field. So on a
/// planar cut the rule is exact to round-off (amplified by the interface system's conditioning,
/// see the tests). On a kinked or curved cut the interface rule is fitted to divergence-free
/// fluxes only, and P^A . n need not be one of them, so exactness is not guaranteed. Measured
/// (tests/common/test_piece_quadrature.cpp, figures/04_cut_quadrature/table1.md): on two planes
/// meeting along a line (a right-angled and two oblique kinks) the rule is still exact to
/// ~1e-15; on an icosphere of radius 0.5 (many planes) its error against the tessellated
/// polyhedron's integrals is some 1e-2 at level 1 and falls by ~4 per level (2e-5 at level 6),
/// about a tenth of the tessellation's own error against the ball.
#pragma once

#include "kerf/quadrature/piece_quadrature_rule.hpp"

namespace kerf {

/// What the fits of one piece came to, for reports.
struct KoschierFitReport {
  int volume_rank = 0;             ///< rank of eq. 17's matrix (10 for degree 2)
  int face_rank = 0;               ///< smallest rank of the face fits used (10 for degree 2)
  int interface_basis = 0;         ///< M_D, the divergence-free fields (50 for degree 2)
  int interface_triangles = 0;     ///< sub-triangles after the subdivision (both sides of a partial cut counted)
  int interface_points = 0;        ///< 6 per sub-triangle
  int interface_rank = 0;          ///< numerical rank of eq. 20's matrix at the cut-off
  double interface_condition = 0;  ///< sigma_max / smallest kept sigma of eq. 20's matrix
  static constexpr double cutoff = 1e-12; ///< relative SVD cut-off for eq. 20 (not in the paper)
};

/// Koschier's rule for `piece` (degree 1 or 2: the volume fit of moment_fitting.hpp, face and
/// interface fits of degree + 1). The points are the 24 of the volume fit, as in "exact": only
/// the moments differ.
/// @param triangles the cut triangles, unclipped, as given to split_tet_by_triangles
PieceQuadratureRule koschier_moment_fitting_rule(const Eigen::Matrix<double, 4, 3>& X, const std::vector<CutTriangle>& triangles,
                                                 const TetPieces& pieces, int piece, int degree,
                                                 KoschierFitReport* report = nullptr);

} // namespace kerf
