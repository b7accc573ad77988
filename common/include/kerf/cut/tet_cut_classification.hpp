/// @file tet_cut_classification.hpp
/// @brief How a cut meets a tet: the case of its sign pattern (Schoch et al. section 5.2, eq. 73) and, for a bounded
///        rectangle, whether it is uncut, touched, partially or completely cut (Paulus et al. section 3.3).
#pragma once

#include "kerf/cut/level_set.hpp"
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/mesh/tet_mesh.hpp"

#include <Eigen/Core>
#include <array>
#include <vector>

namespace kerf {

/// The ways a plane can meet a tet, decided by the signs of its four (snapped) corner values.
///
/// Each corner is +, - or 0, so there are 3^4 = 81 sign patterns; up to a permutation of the
/// corners they are the multisets of size 4 from {+, -, 0}, of which there are
/// C(4 + 3 - 1, 4) = 15. Counting (#+, #-, #0):
///
/// | #  | pattern | (#+,#-,#0) | geometry                                           | case                 |
/// |----|---------|------------|----------------------------------------------------|----------------------|
/// |  1 | + + + + | (4,0,0)    | entirely above                                     | uncut                |
/// |  2 | - - - - | (0,4,0)    | entirely below                                     | uncut                |
/// |  3 | + + + 0 | (3,0,1)    | plane touches one corner                           | touched_vertex       |
/// |  4 | - - - 0 | (0,3,1)    | plane touches one corner                           | touched_vertex       |
/// |  5 | + + 0 0 | (2,0,2)    | plane contains one edge                            | touched_edge         |
/// |  6 | - - 0 0 | (0,2,2)    | plane contains one edge                            | touched_edge         |
/// |  7 | + 0 0 0 | (1,0,3)    | plane contains one face                            | touched_face         |
/// |  8 | - 0 0 0 | (0,1,3)    | plane contains one face                            | touched_face         |
/// |  9 | 0 0 0 0 | (0,0,4)    | all corners on the plane: a flat tet, or one       | all_zero             |
/// |    |         |            | smaller than the snap tolerance                    |                      |
/// | 10 | + - - - | (1,3,0)    | one corner apart: triangle section; tet + prism    | cut_one_vertex_apart |
/// | 11 | - + + + | (3,1,0)    | one corner apart: triangle section; tet + prism    | cut_one_vertex_apart |
/// | 12 | + + - - | (2,2,0)    | two against two: quadrilateral section; 2 prisms   | cut_two_two          |
/// | 13 | + - - 0 | (1,2,1)    | through one corner, the others split 1-2: triangle | cut_through_vertex   |
/// |    |         |            | section; tet + pyramid                             |                      |
/// | 14 | - + + 0 | (2,1,1)    | as 13 with the sides swapped                       | cut_through_vertex   |
/// | 15 | + - 0 0 | (1,1,2)    | through one edge, the other two corners apart:     | cut_through_edge     |
/// |    |         |            | triangle section; two tets                         |                      |
///
/// Patterns 10-15 hold both a + and a - corner and are genuinely cut: min Lambda * max Lambda < 0,
/// which is eq. 73's set M_Lambda of cut elements. Patterns 1-9 are not cut; 3-8 are "only
/// touched along an edge or a face" (or a corner). Schoch et al. count "8 different ways, 4 of which
/// actually leave the element only touched" without listing them; we read them as our eight
/// non-degenerate cases up to the choice of side: the four cut ones, and four that are not cut
/// (uncut, touched at a corner, along an edge, along a face). The paper's own example,
/// (+ - 0 -), is pattern 13.
///
/// Decision on all_zero (pattern 9): it is not cut (eq. 73 gives 0 < 0, false), it is counted
/// apart so that a report shows it, and clip_tet() puts the whole tet above. A valid mesh has
/// it only when tets are smaller than the snap tolerance.
enum class TetCutCase {
  uncut,
  touched_vertex,
  touched_edge,
  touched_face,
  all_zero,
  cut_one_vertex_apart,
  cut_two_two,
  cut_through_vertex,
  cut_through_edge,
};

/// Number of TetCutCase values, for arrays indexed by the case.
inline constexpr int tet_cut_case_count = 9;

/// The case of one tet from its four snapped level set values (exact zeros mean "on the plane").
TetCutCase classify_tet_cut(const Eigen::Vector4d& lambda);

/// Eq. 73: whether the plane separates the tet (both signs present), i.e. one of the four cut_* cases.
inline bool is_cut(TetCutCase c) { return c >= TetCutCase::cut_one_vertex_apart; }

/// The enumerator's name, "cut_two_two" and so on, for reports and messages.
const char* to_string(TetCutCase c);

/// How a BOUNDED cut (a rectangle, not its whole plane) meets an element, after Paulus et al.
/// section 3.3: an edge is cut if it meets the closed cut, a face is completely cut if two of
/// its edges are cut, and the element is uncut (no cut edges), partially cut (cut edges, but
/// fewer than three completely cut faces: the cut's boundary runs through the element) or
/// completely cut through (three or more completely cut faces).
///
/// What we decided where the plane passes through corners (Lambda_i = 0):
/// - A tet the plane does not separate (patterns 1-9 above) is never cut. It is `touched` if one
///   of its corners on the plane projects into the rectangle, otherwise `uncut`. (A rectangle
///   that touches a face or edge of the tet without covering any of its corners is reported
///   uncut; touched elements are not enriched, so nothing downstream depends on it.)
/// - For a separated tet, the plane's section is a triangle or quadrilateral whose corners, the
///   "cut points", are the crossings of edges with a + and a - end and the corners with
///   Lambda = 0. Every separated face (one with both signs) is crossed by a segment between two
///   cut points, and it is completely cut when both lie in the rectangle. Without zeros this is
///   Paulus et al.'s rule word for word: the cut points are the cut edges. With zeros, a corner on
///   the plane stands for the edges through it.
/// - The element is completely cut when ALL its separated faces are completely cut, which is
///   the same as: every cut point lies in the rectangle. For patterns 10-13 this is Paulus et al.'s
///   ">= 3 completely cut faces" (a tet of pattern 10/11 or 13/14 has exactly 3 separated faces;
///   one of pattern 12 has 4, and each cut point lies on two of them, so one point outside
///   leaves 2, never 3). Pattern 15 has only 2 separated faces, so ">= 3" could never hold and
///   we use "all" instead.
/// - Partially cut: not all cut points in the closed rectangle, and the section overlaps the
///   rectangle in more than partial_cut_minimum_area_fraction of the section's own area: a
///   tet whose section only touches the rectangle's edge, the cut's front, or overlaps it in a
///   strip of round-off width, lies beyond the cut, not on it. Uncut: otherwise (the plane cuts
///   the tet, the rectangle misses it). Measuring the overlap, not counting cut points, also
///   catches a rectangle corner poking into a large section.
enum class ElementCutState { uncut, touched, partially_cut, completely_cut };

/// The smallest share of a section's area the rectangle must cover for the tet to be partially
/// cut. Why relative, and why 1e-4:
/// - Relative to the section, not an absolute strip width, so that a whole column of tets along
///   the front cannot flip between partially cut and beyond when the front moves by round-off
///   (an absolute width of the snap tolerance, about 1e-12 of the mesh, was flipped by a move
///   of a few nanometres), and so that the decision is the same on every mesh size.
/// - 1e-4 is the minimum volume fraction of the enrichment (default_minimum_volume_fraction):
///   a piece below it is not kept as a piece of its own, and an overlap below it is not kept as
///   a cut. It lies far above round-off (1e-16 relative, so an overlap caused by round-off is
///   some 1e-12 of the section at most) and far below any overlap that carries a visible part of
///   the cut (for a front parallel to an edge of the section, 1e-4 of the area is a strip of
///   about 1e-4 of the section's width).
/// Where the front falls inside that margin the tet is beyond, and the simulated cut is as if
/// the front stood on the section's edge: a change of the cut's length below 1e-4 of an element.
inline constexpr double partial_cut_minimum_area_fraction = 1e-4;

/// The enumerator's name, for reports.
const char* to_string(ElementCutState s);

/// Classifies one straight-edged tet against a rectangle cut.
/// @param X         4 by 3 corner positions (m), one row per corner
/// @param lambda    the four snapped level set values of those corners (m)
/// @param cut       the rectangle whose plane produced lambda
/// @param tolerance how far outside the rectangle a cut point may lie and count as inside (m);
///                  the level set's snap tolerance is the natural choice
ElementCutState classify_element_cut(const Eigen::Matrix<double, 4, 3>& X, const Eigen::Vector4d& lambda,
                                     const RectangleCut& cut, double tolerance);

/// The classification of every tet of a mesh, and the counts to report.
struct MeshCutClassification {
  std::vector<TetCutCase> tet_case;                   ///< #T sign-pattern cases
  std::vector<ElementCutState> state;                 ///< #T states against the rectangle
  std::array<int, tet_cut_case_count> case_counts{};  ///< how many tets fall in each TetCutCase
  std::array<int, 4> state_counts{};                  ///< how many tets fall in each ElementCutState

  int count(TetCutCase c) const { return case_counts[static_cast<std::size_t>(c)]; }
  int count(ElementCutState s) const { return state_counts[static_cast<std::size_t>(s)]; }
};

/// Classifies every tet of `mesh` (its four corners; Tet10 edges are straight, so the corners
/// decide) using the nodal level set, and counts each class.
/// @param mesh      Tet4 or Tet10 mesh
/// @param level_set make_level_set(mesh, cut, ...), #V values
/// @param cut       the rectangle; its closure decides partially versus completely cut, with
///                  level_set.snap_tolerance as the tolerance
MeshCutClassification classify_mesh_cut(const TetMesh& mesh, const LevelSet& level_set, const RectangleCut& cut);

} // namespace kerf
