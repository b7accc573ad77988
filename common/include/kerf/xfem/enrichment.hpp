/// @file enrichment.hpp
/// @brief Which nodes the shifted Heaviside enrichment (Paper 000 eq. 44) reaches, the side of every node and
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
};

/// How a tet relates to the cut, as far as the enrichment is concerned.
enum class TetSide : signed char {
  below = -1, ///< entirely on the negative side (corners with Lambda <= 0): H = -1 all over it
  cut = 0,    ///< split by the cut into two pieces of positive volume (eq. 73, within the rectangle)
  above = 1,  ///< entirely on the positive side (corners with Lambda >= 0): H = +1 all over it
  beyond = 2, ///< split by the cut's PLANE outside the rectangle: beyond the cut's front, no jump in it
};

/// The enrichment of a Tet4 mesh by one planar cut.
///
/// Which nodes are enriched. The enriched function of node i is Phi_i Psi_i with
/// Psi_i = (H(x) - H_i) / 2 (eq. 44). We enrich node i exactly when the cut splits the support
/// of Phi_i (the tets around i) into two parts of positive volume, and the jump of H inside
/// that support lies on the cut:
/// 1. no tet around i is `beyond` the front. There the plane crosses the tet but the cut does
///    not, so H has no value; such nodes are the crack-front nodes that chapter 5 gives
///    branch functions (Paper 003 section 3.3: "sign enriched" versus "branch enriched" nodes);
/// 2. every interior face through i that lies in the cut plane (all corners at Lambda = 0,
///    a tet above on one side and one below on the other) lies inside the rectangle, so that a
///    cut running exactly along mesh faces stops where the rectangle stops;
/// 3. the tets around i hold volume on both sides of the cut. Otherwise Phi_i Psi_i would be
///    0 or -Phi_i everywhere: no new function, and a singular system.
///
/// The chapter's simplification (Paper 000 section 4.3: "we let a cutting surface which
/// partially intersects an element continue through it"): a partially cut tet is split by the
/// whole plane, as if the rectangle reached through it. Rule 1 then leaves its nodes on the
/// front side unenriched, so the opening fades to zero at the first row of unenriched nodes.
/// Where the cut runs along mesh faces and its front falls between two rows of nodes, rule 2
/// ends the opening at the last row inside the rectangle. Either way the simulated cut
/// differs from the rectangle by less than one element.
///
/// Sides and signs. H_i = +1 where Lambda_i >= 0 and -1 where Lambda_i < 0: a node on the cut
/// counts as above, as in eqs. 58-59 ("above the crack and on the crack line").
struct Enrichment {
  LevelSet level_set;                          ///< nodal Lambda after the minimum-fraction snapping
  MeshCutClassification classification;       ///< of that level set against the rectangle
  std::vector<int> node_sign;                  ///< #V values H_i = +1 or -1
  std::vector<int> enriched_index;             ///< #V: k if node i carries enriched DOFs a_k, else -1
  std::vector<int> enriched_nodes;             ///< N_enr node indices, in increasing order
  std::vector<TetSide> tet_side;               ///< #T
  std::vector<double> fraction_above;          ///< #T values V_a / V (1 above, 0 below, in (0, 1) when cut)
  std::vector<ClippedTet> pieces;              ///< #T; filled for cut tets only, empty otherwise
  int snapped_nodes = 0;                       ///< nodes the minimum-fraction rule moved onto the cut
  double largest_snap = 0.0;                   ///< the largest |Lambda_i| so set to 0 (m)
  int front_nodes = 0;                         ///< nodes left unenriched by rule 1
  int cut_tets = 0;                            ///< tets with TetSide::cut
  double minimum_volume_fraction = 0.0;        ///< the threshold used

  Eigen::Index num_enriched() const { return static_cast<Eigen::Index>(enriched_nodes.size()); }
  double fraction_below(Eigen::Index t) const { return 1.0 - fraction_above[static_cast<std::size_t>(t)]; }
};

/// Computes the enrichment of a Tet4 mesh by one rectangle cut.
/// @param mesh     a Tet4 mesh (Tet10 XFEM needs chapter 4's quadrature; std::invalid_argument otherwise)
/// @param cut      the rectangle
/// @param settings the minimum volume fraction
Enrichment make_enrichment(const TetMesh& mesh, const RectangleCut& cut, const EnrichmentSettings& settings = {});

} // namespace kerf
