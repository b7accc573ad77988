/// @file clip_tet.hpp
/// @brief Split one tet by a plane into sub-tetrahedra above and below it (Schoch et al. section 5.2's element subdivision).
#pragma once

#include "kerf/cut/tet_cut_classification.hpp"

#include <Eigen/Core>
#include <vector>

namespace kerf {

/// The two parts of a tet on either side of the plane Lambda = 0, each as a list of
/// sub-tetrahedra, and the polygon in which the plane cuts the tet.
///
/// Schoch et al. (section 5.2): "the two subelements obtained from this subdivision process are not
/// necessarily tetrahedra anymore, which is why we choose to again subdivide these subelements
/// until they represent smaller tetrahedra, such that on the subelement-level we can apply the
/// same functions on them as on the element level."
struct ClippedTet {
  TetCutCase tet_case = TetCutCase::uncut;        ///< the sign pattern's case
  std::vector<Eigen::Matrix<double, 4, 3>> above; ///< sub-tets where Lambda >= 0, each 4x3, positively oriented
  std::vector<Eigen::Matrix<double, 4, 3>> below; ///< sub-tets where Lambda <= 0, each 4x3, positively oriented
  /// The section of the tet by the plane, for a separated tet only (empty otherwise): 3 or 4
  /// points in order around the polygon, counter-clockwise seen from above, so that
  /// (p1 - p0) x (p2 - p0) points to the positive side.
  std::vector<Eigen::Vector3d> section;
  double V_a = 0.0; ///< volume above, the sum of the `above` sub-tet volumes (m^3)
  double V_b = 0.0; ///< volume below (m^3); V_a + V_b = V to round-off
};

/// Signed volume det[x1 - x0, x2 - x0, x3 - x0] / 6 of the tet with corners X (4x3, rows).
double signed_tet_volume(const Eigen::Matrix<double, 4, 3>& X);

/// Clips a straight-edged tet by the plane on which the linear interpolant of `lambda` vanishes.
///
/// The crossing point on an edge with values lambda_p > 0 > lambda_m is
/// x_p + lambda_p / (lambda_p - lambda_m) (x_m - x_p) (the intercept theorem of section 5.2),
/// always interpolated from the + end, so that two tets sharing the edge get bitwise the same
/// point and their sections meet exactly on a shared face.
///
/// The pieces, by case (see TetCutCase for the table of all 15 sign patterns):
/// - cut_one_vertex_apart: a tet at the lone corner, and a prism (3 tets) on the other side;
/// - cut_two_two: two prisms, 3 tets each;
/// - cut_through_vertex: a tet on the side of the lone corner, a pyramid (2 tets) on the other;
/// - cut_through_edge: one tet on each side;
/// - uncut and touched_*: the whole tet on the side of its nonzero corners, nothing on the other;
/// - all_zero: the whole tet above, nothing below (a convention: such a tet is flat, or smaller
///   than the snap tolerance, and is never enriched).
///
/// @param X      4 by 3 corner positions (m), one row per corner, any orientation
/// @param lambda the four corner values of the level set, already snapped (exact 0 = on the plane)
/// @return the pieces, the section and V_a, V_b
ClippedTet clip_tet(const Eigen::Matrix<double, 4, 3>& X, const Eigen::Vector4d& lambda);

/// The area of a planar polygon given by its corners in order (0 for fewer than 3 points).
double polygon_area(const std::vector<Eigen::Vector3d>& polygon);

/// The default threshold for minimum_volume_fraction_met(): 1e-4.
///
/// Why a threshold at all: for the shifted Heaviside enrichment, the enriched shape function
/// of a node on the big side lives only on the small piece, so its diagonal stiffness entry
/// scales with the piece's volume fraction, and the condition number of the enriched block grows
/// like 1 / fraction. Schoch et al. (section 5.2) guard against this with "a minimum distance
/// between an element node and a cut, until which we define the element not to be cut"; a
/// volume fraction says the same thing independent of the element's size. 1e-4 keeps the
/// condition number within about four orders of magnitude of the uncut element's. The number
/// is stated here; chapter 3 charts the condition number against the fraction.
inline constexpr double default_minimum_volume_fraction = 1e-4;

/// Whether the smaller piece of a cut tet is large enough to be enriched.
/// @param fraction_a       V_a / V
/// @param fraction_b       V_b / V
/// @param minimum_fraction the threshold, default_minimum_volume_fraction unless a study varies it
/// @return min(fraction_a, fraction_b) >= minimum_fraction; false for an uncut tet (a fraction is 0)
bool minimum_volume_fraction_met(double fraction_a, double fraction_b,
                                 double minimum_fraction = default_minimum_volume_fraction);

} // namespace kerf
