/// @file branch_enrichment.hpp
/// @brief Which nodes get the crack-tip (branch) functions and which the sign (Heaviside) enrichment, by Paulus's topological rule or by a radius (Paulus section 3.3; Laborde et al. 2005).
///
/// Chapter 4 enriches a node once per extra part its support is cut into (surface_enrichment.hpp):
/// a node whose support holds the front is not split and gets nothing, so the cut ends at the
/// last row of enriched nodes. Chapter 5 gives the nodes near the front the four branch functions
/// of branch_functions.hpp (12 extra DOFs each) and keeps chapter 4's enrichment for the others.
///
/// Only corner nodes carry branch functions, with the corners' linear hats as their partition of
/// unity, on a Tet10 too: with the Tet10's quadratic shape functions the products would be
/// linearly dependent (branch_enrichment.cpp derives the two identities that make them so).
///
/// The two rules for "near the front":
/// - **topological** (Paulus section 3.3): a node is branch enriched if it belongs to a tet the
///   front passes through. Paulus says "a partially cut element"; Kerf takes every tet that
///   holds a piece of the front of positive length (front_in_tet), which is the partially cut
///   tets and, when the front runs exactly along a face or an edge, the tets on both sides of it
///   (where no tet is partially cut and Paulus's rule would enrich nothing);
/// - **geometric** (Laborde et al. 2005, Bechet et al. 2005): every node within the
///   radius r_e of the front, and the topological ones as well, so that the two sets are nested
///   even when r_e is smaller than the elements (a tet the front crosses always has branch nodes).
/// The sign nodes are chapter 4's enriched nodes that are not branch enriched (a node is never
/// both, Paulus Fig. 2). Paulus's rule "nodes of completely cut elements" agrees: a node of a
/// completely cut tet whose support holds no piece of the front has its support split, so chapter
/// 4 enriches it; one whose support holds a piece of the front is branch enriched by both rules.
///
/// Blending tets (Paulus et al., section 5.2): tets with some, not all, nodes branch enriched. The tets with a
/// branch node are where the model integrates the branch functions (uncut blending tets
/// included: Paulus's "uncut blending element").
///
/// In a blending tet the branch nodes' hats no longer sum to one, so the enrichment there is not
/// F itself but a part of it, which the standard shape functions cannot make up: the
/// blending error (Chessa et al. 2003). Fries's corrected XFEM (2008) cures it by
/// multiplying the functions by the ramp
///
///   R(x) = sum_{i in I*} lambda_i(x)        (I*: the branch nodes chosen above)
///
/// and enriching every corner of the blending tets with R F (BlendingCorrection::corrected):
/// then sum_v lambda_v R F = R F holds in every tet, F where all corners are in I* and falling
/// linearly to zero across the blending tets, and nothing of F leaks into the tets beyond them
/// (R = 0 there). The extra corners, the ramp nodes, keep their sign enrichments: such a node
/// behind the front carries both (its shift R(x_v) F(x_v) is 0, since R(x_v) = 0).
#pragma once

#include "kerf/cut/crack_front.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/mesh/tet_mesh.hpp"
#include "kerf/xfem/surface_enrichment.hpp"

#include <Eigen/Core>
#include <vector>

namespace kerf {

/// Which nodes near the front get the branch functions.
enum class TipEnrichmentRule : signed char {
  topological, ///< the nodes of the tets the front passes through (Paulus section 3.3)
  geometric,   ///< every node within a radius of the front, and the topological ones
};

/// How the tets with some, not all, corners branch enriched are treated (the header's comment).
enum class BlendingCorrection : signed char {
  none,      ///< Paulus's: the branch nodes' functions as they are, the blending error kept
  corrected, ///< Fries 2008: every function times the ramp R, every corner of a blending tet enriched
};

/// What a node carries beyond its standard DOFs.
enum class NodeEnrichmentKind : signed char {
  none,   ///< nothing
  sign,   ///< chapter 4's enrichments (one or more; 3 DOFs each)
  branch, ///< the four branch functions (12 DOFs): a node of I*
};

/// The enrichment of a mesh whose cuts may end inside it.
struct BranchEnrichment {
  /// #V: a node of I* is `branch`; a ramp node (BlendingCorrection::corrected) keeps the kind of
  /// its sign enrichments, `sign` or `none`, and has a branch slot all the same.
  std::vector<NodeEnrichmentKind> kind;
  BlendingCorrection blending_correction = BlendingCorrection::none;
  /// #V: the branch slot k of a node with branch functions, a node of I* or a ramp node (its
  /// functions F_1..F_4 are enrichments 4k .. 4k+3 of the branch block), -1 for the others.
  std::vector<int> branch_slot;
  std::vector<int> branch_node;         ///< N_B: the node of each slot
  /// N_B: R(x_i) F_l(x_i) at each slot's node, for the shift N_i (R F_l(x) - R F_l(x_i)): with
  /// theta = +pi for a node lying on the cut, the side chapter 4 gives such a node (above).
  /// R(x_i) is 1 at a node of I* (and everywhere without the correction), 0 at a ramp node.
  std::vector<Eigen::Vector4d> node_values;
  /// #V: +1 for a node lying on a cut, so that theta = +pi there (CrackFronts::polar's cut_side),
  /// 0 for the others. Only branch nodes are looked at. "On a cut" is a corner of a cut polygon
  /// of a piece of one of its tets: a cut through the node, or a cut plane that holds a face of
  /// a tet around it within chapter 4's snap (1e-12 of the tet's size: a box mesh's nodes
  /// y = 0.09999999999999998 are on the cut y = 0.1). Such a node's standard DOF holds
  /// the face above: a field discontinuous across the cut, prescribed there, must take that
  /// face's value, not the one atan2 gives the round-off in x_b (figures/05_crack_tip/failures.md).
  std::vector<int> cut_side;
  std::vector<char> front_tet;          ///< #T: a piece of the front lies in it (front_in_tet)
  std::vector<char> has_branch_nodes;   ///< #T: some corner of it is branch enriched
  std::vector<char> blending;           ///< #T: some, but not all, of its corners are branch enriched
  /// Chapter 4's enrichment with the branch nodes' enrichments taken out (renumbered, `active`
  /// pointing to the remaining ones): what the model uses for the sign DOFs.
  SurfaceEnrichment sign;

  /// The number of branch slots: the nodes of I* and, corrected, the ramp nodes.
  int num_branch_nodes() const { return static_cast<int>(branch_node.size()); }
  /// The number of ramp nodes: slots whose node is not in I* (0 without the correction).
  int num_ramp_nodes() const { return num_branch_nodes() - count(NodeEnrichmentKind::branch); }
  /// The number of nodes of each kind.
  int count(NodeEnrichmentKind k) const;
};

/// Classifies every node of `mesh` (Paulus et al., section 3.3).
/// @param mesh     Tet4 or Tet10 mesh
/// @param pieces   cut_mesh_into_pieces(mesh, cuts)
/// @param fronts   find_crack_fronts(mesh, cuts)
/// @param rule     topological or geometric
/// @param radius   r_e of the geometric rule (m), >= 0; ignored by the topological rule
/// @param blending none, or Fries's correction (the ramp nodes get branch slots too)
/// @throws std::invalid_argument for a negative or non-finite radius
BranchEnrichment make_branch_enrichment(const TetMesh& mesh, const MeshPieces& pieces, const CrackFronts& fronts,
                                        TipEnrichmentRule rule, double radius = 0.0,
                                        BlendingCorrection blending = BlendingCorrection::none);

} // namespace kerf
