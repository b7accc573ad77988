/// @file surface_enrichment.hpp
/// @brief Which nodes triangle-mesh cuts enrich, and how often: one enrichment per extra connected part of a node's support (Koschier section 4.3).
#pragma once

#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/mesh/tet_mesh.hpp"

#include <vector>

namespace kerf {

/// The enrichment of a mesh by cut surfaces.
///
/// The rule. The support of node i is the set of tets that hold it (its one-ring for a corner,
/// the tets around its edge for a Tet10 mid-edge node). Cut it along the cut surfaces and count
/// its connected parts, C_0 .. C_{r-1}, the pieces of its tets glued through faces the cut does
/// not cover (mesh_pieces.hpp). The node gets r - 1 enrichments, one for each part except its
/// own, the "home" part C_h in which the node lies:
///
///   psi_i^k(x) = 1 on C_k, 0 elsewhere   (k != h),
///
/// and the field is u(x) = sum_i N_i(x) (u_i + sum_k psi_i^k(x) a_i^k).
///
/// This is Koschier's eq. 10 and the enrichment test of section 4.3, stated through the parts
/// rather than through signs:
/// - a cut that crosses the support completely makes two parts: one enrichment, whose span with
///   N_i is that of chapter 3's shifted Heaviside N_i (H - H_i) / 2 (eq. 44), which is +-N_i on
///   the far side and 0 on the node's own: only the sign of a_i can differ (here a_i is always
///   the far side's value minus the home side's);
/// - a cut that ends inside the support (its front passes through a tet of it) leaves one part:
///   no enrichment. A cut cannot advance inside an element (Koschier section 8's limitation;
///   chapter 5 adds crack-tip functions for this);
/// - two cuts through one support, or one surface folded through it (Koschier Fig. 4), make
///   three or more parts: a node gets one enrichment per extra part. Two cuts that cross each
///   other inside a support make four parts and three enrichments, which with N_i span every
///   piecewise constant on the four (a junction enrichment in the sense of Daux et al. 2000;
///   Koschier's one-per-cut rule cannot represent it and refuses crossing cuts).
/// The shift (psi = 0 on the home part) keeps the Kronecker property u(x_i) = u_i.
///
/// The home part of a node on a cut (a cut through the node, which exact predicates decide):
/// the node touches two or more parts. Kerf takes the part above the cut (the side its
/// triangles' normals point to), as Schoch et al. count nodes "above the crack and on the crack
/// line" as above (eqs. 58-59); failing that (a fold through the node), the lowest-numbered.
/// The choice changes the meaning of a_i, never the space of fields.
struct SurfaceEnrichment {
  /// #V + 1 offsets: node i's enrichments are first_enrichment[i] .. first_enrichment[i + 1] - 1.
  std::vector<int> first_enrichment;
  /// The node of each enrichment.
  std::vector<int> enrichment_node;
  /// For tets with a node that has enrichments: active[t] holds, for each local node a and
  /// piece p of t, at [a * pieces + p], the enrichment whose psi is 1 there, or -1 (home part).
  /// Empty for other tets (no enrichment acts in them).
  std::vector<std::vector<int>> active;
  int enriched_nodes = 0;       ///< nodes with at least one enrichment
  int most_enrichments = 0;     ///< the largest number of enrichments of one node

  Eigen::Index num_enrichments() const { return static_cast<Eigen::Index>(enrichment_node.size()); }
  /// The number of enrichments of node i.
  int enrichments_of(Eigen::Index i) const {
    return first_enrichment[static_cast<std::size_t>(i) + 1] - first_enrichment[static_cast<std::size_t>(i)];
  }
  /// The enrichment active at local node a of tet t on its piece p (-1: none).
  int active_enrichment(const MeshPieces& pieces, Eigen::Index t, int a, int p) const {
    const std::vector<int>& list = active[static_cast<std::size_t>(t)];
    return list.empty() ? -1 : list[static_cast<std::size_t>(a * pieces.num_pieces(t) + p)];
  }
};

/// Finds the parts of every node's support and numbers the enrichments (node by node, the
/// parts in the order of their lowest piece).
/// @param mesh   Tet4 or Tet10 mesh
/// @param pieces cut_mesh_into_pieces(mesh, cuts)
SurfaceEnrichment make_surface_enrichment(const TetMesh& mesh, const MeshPieces& pieces);

} // namespace kerf
