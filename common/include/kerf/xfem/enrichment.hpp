/// @file enrichment.hpp
/// @brief Which nodes the shifted Heaviside enrichment (Schoch et al. eq. 44) reaches, the side of every node and
///        tet, and the volume fractions V_a / V, V_b / V of every tet: everything chapter 3 decides once per cut.
#pragma once

#include "kerf/cut/clip_tet.hpp"
#include "kerf/cut/level_set.hpp"
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/cut/tet_cut_classification.hpp"
#include "kerf/mesh/tet_mesh.hpp"

#include <vector>

namespace kerf {

/// The choices a user may make about the enrichment.
struct EnrichmentSettings {
  /// A cut tet whose smaller piece holds less than this fraction of its volume is not split:
  /// the corners on that small side are moved onto the cut (their level set values set to 0),
  /// which turns the sliver into a cut along a face, edge or corner. See clip_tet.hpp for why.
  double minimum_volume_fraction = default_minimum_volume_fraction;
  /// ... but no corner is moved by more than this fraction of the shortest mesh edge at it.
  /// In a well-shaped tet a piece of fraction 1e-4 ends within about 0.05 of an edge length of
  /// its corners, so the limit does not bite there; in a flat tet or next to much smaller
  /// elements moving the node would distort the cut (and the neighbours' pieces) by more than
  /// the sliver costs. Such a sliver is kept: the results of chapter 3 show that its
  /// ill-conditioning is a scaling, which a Jacobi preconditioner removes.
  double maximum_snap_fraction = 0.1;
};

/// How a tet relates to the cut, as far as the enrichment is concerned.
enum class TetSide : signed char {
  below = -1, ///< entirely on the negative side (corners with Lambda <= 0): H = -1 all over it
  cut = 0,    ///< split by the cut into two pieces of positive volume (eq. 73, within the rectangle)
  above = 1,  ///< entirely on the positive side (corners with Lambda >= 0): H = +1 all over it
  beyond = 2, ///< split by the cut's PLANE outside the rectangle: beyond the cut's front, no jump in it, and
              ///< so no sides: the material is whole there, and no enriched node touches it (rule 1)
};

/// The enrichment of a Tet4 mesh by one planar cut.
///
/// Which nodes are enriched. The enriched function of node i is Phi_i Psi_i with
/// Psi_i = (H(x) - H_i) / 2 (eq. 44). We enrich node i exactly when the cut splits the support
/// of Phi_i (the tets around i) into two parts of positive volume, and the jump of H inside
/// that support lies on the cut. As three rules, checked in this order:
/// 1. no tet around i is `beyond` the front. There the plane crosses the tet but the cut does
///    not, so the material is whole and the displacement continuous; yet Phi_i Psi_i would jump
///    across the plane inside that tet, and across the face it shares with a cut neighbour.
///    Enriching i would put a crack where there is none and make the space non-conforming.
/// 2. every interior face through i that lies in the cut plane (all corners at Lambda = 0,
///    a tet above on one side and one below on the other) lies inside the rectangle, so that a
///    cut running exactly along mesh faces stops where the rectangle stops;
/// 3. the tets around i hold volume on both sides of the cut. Otherwise Phi_i Psi_i would be
///    0 or -Phi_i everywhere: no new function, and a singular system.
///
/// This rule is Kerf's own, and differs from both papers'. Schoch et al. (eq. 73 and section 4.3)
/// enriches every node of every cut element, partially cut ones included, and lets a partial
/// cut "continue through" the element. Paulus et al. (section 3.3) give the nodes of partially cut
/// elements branch (crack-tip) functions and sign-enriches only the nodes of completely cut
/// elements that touch no partially cut one. Kerf sign-enriches the nodes of partially cut tets
/// too (split by the whole plane, as Schoch et al. do), but leaves unenriched every node that
/// touches a tet the plane crosses outside the rectangle, which is a different set, one element
/// further out than Paulus et al.'s branch nodes. Chapter 5 gives these `front` nodes branch
/// functions.
///
/// What that makes of the front. The simulated cut ends at the last row of enriched nodes:
/// the opening fades to zero across the first tets of unenriched nodes. That row depends on
/// where the front falls among the nodes, not continuously on the front: as the front moves
/// through an element the simulated cut stays put and then jumps by a whole element (chapter 3's
/// results chart the jump). It can end up to one element short of the rectangle or reach up
/// to one element past it, depending on whether the tets at the front are partially cut.
/// Chapter 5's tip enrichment is the cure.
///
/// Sides and signs. H_i = +1 where Lambda_i > 0 and -1 where Lambda_i < 0. A node on the cut
/// counts as above, as in eqs. 58-59 ("above the crack and on the crack line"), except a node
/// that the minimum-fraction rule moved onto the cut: it keeps the side it came from, so the
/// snapping does not pull nodes towards one side. (H_i only decides which side's field u_i is;
/// span{Phi_i, Phi_i Psi_i} is the same for either sign.)
struct Enrichment {
  LevelSet level_set;                          ///< nodal Lambda after the minimum-fraction snapping
  MeshCutClassification classification;       ///< of that level set against the rectangle
  std::vector<int> node_sign;                  ///< #V values H_i = +1 or -1
  std::vector<int> enriched_index;             ///< #V: k if node i carries enriched DOFs a_k, else -1
  std::vector<int> enriched_nodes;             ///< N_enr node indices, in increasing order
  std::vector<TetSide> tet_side;               ///< #T
  std::vector<double> fraction_above;          ///< #T values V_a / V (1 above, 0 below, in (0, 1) when cut,
                                               ///< NaN beyond the front: such a tet has no sides; use piece_fraction)
  std::vector<ClippedTet> pieces;              ///< #T; filled for cut tets only, empty otherwise
  std::vector<int> snapped;                    ///< the nodes the minimum-fraction rule moved onto the cut
  int snapped_nodes = 0;                       ///< snapped.size()
  double largest_snap = 0.0;                   ///< the largest |Lambda_i| so set to 0 (m)
  int kept_slivers = 0;                        ///< tets below the minimum fraction kept, as snapping would move a node too far
  int front_nodes = 0;                         ///< nodes left unenriched by rule 1
  int cut_tets = 0;                            ///< tets with TetSide::cut
  double minimum_volume_fraction = 0.0;        ///< the threshold used

  Eigen::Index num_enriched() const { return static_cast<Eigen::Index>(enriched_nodes.size()); }
  /// V_side / V of tet t for side +1 (above) or -1 (below): 1 or 0 for a tet on one side, the
  /// piece's fraction for a cut tet. The one answer to "how much of tet t is on this side",
  /// for stiffness, mass and loads alike. A tet beyond the front has no sides: asking is a
  /// logic error (std::logic_error), since no enriched node touches it.
  double piece_fraction(Eigen::Index t, int side) const;
  double fraction_below(Eigen::Index t) const { return piece_fraction(t, -1); }
};

/// Computes the enrichment of a Tet4 mesh by one rectangle cut.
/// @param mesh     a Tet4 mesh (Tet10 XFEM needs chapter 4's quadrature; std::invalid_argument otherwise)
/// @param cut      the rectangle
/// @param settings the minimum volume fraction
Enrichment make_enrichment(const TetMesh& mesh, const RectangleCut& cut, const EnrichmentSettings& settings = {});

} // namespace kerf
