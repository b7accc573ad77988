/// @file semi_progressive_cut.hpp
/// @brief Gutierrez and Ramos's semi-progressive cut: which mesh edges a moving blade has crossed, and which tets it has crossed through.
///
/// A progressive cut that splits an element as soon as the blade enters it makes many tiny
/// faces; Gutierrez and Ramos (section 3.3, Figs. 6 and 14) wait "until the tool crosses the whole
/// element". They keep lists L1, L2, L3 of the tets with 1, 2, 3 crossed edges and cut a tet of
/// L3. We keep their idea with three changes of our own:
/// - crossings belong to the mesh's *edges*, not to (tet, edge) pairs: an edge is crossed once,
///   its crossing point recorded then and never moved, so a blade that trembles back over an
///   edge cannot cut twice (G's "three intersections must be in different edges");
/// - a tet is crossed when its crossed edges and its corners on the sheet separate its four
///   corners, not at the third crossed edge: a planar sheet crosses 3 edges isolating a corner, or
///   4 edges splitting the corners 2:2, and G's rule would fire on the third of those 4;
/// - the search uses an AABB tree of the edges, not G's neighbourhood levels around a reference tet
///   (which need a tuning constant the paper does not give).
///
/// Degenerate contacts, all decided with CGAL's exact predicates (no tolerance):
/// - a swept triangle is closed: an edge that meets it on its boundary (the blade's edge stopped
///   exactly on a mesh edge) is crossed;
/// - a triangle through an edge's end (a node) does not cross that edge: it puts the node *on the
///   sheet*. For the separation test a corner on the sheet belongs to neither side, so a sheet
///   through a corner that crosses the opposite face's edges still crosses the tet, and a sheet
///   that only touches a corner (grazing) crosses nothing;
/// - an edge lying in a triangle's plane is not crossed (the sheet slides along it); its ends that
///   lie in the closed triangle are on the sheet. So a sheet in a plane of mesh faces crosses no
///   tet: it separates tets only along faces, which this edge-based test cannot see (chapter 4's
///   MeshPieces does, through the glue across faces).
#pragma once

#include "kerf/cut/swept_quad.hpp"
#include "kerf/mesh/tet_mesh.hpp"

#include <Eigen/Core>
#include <array>
#include <memory>
#include <vector>

namespace kerf {

/// Where the sheet crossed one mesh edge. Whether it is crossed is decided exactly; the point is
/// computed in doubles, s = h_a / (h_a - h_b) from the ends' heights over the triangle's plane.
struct EdgeCrossing {
  double parameter = 0.0;                          ///< s in [0, 1] with point = (1 - s) x_a + s x_b, a < b the edge's nodes
  Eigen::Vector3d point = Eigen::Vector3d::Zero(); ///< m, in the reference configuration
};

/// How one mesh edge meets one swept triangle: the edge half of the crossing test, decided with
/// exact predicates (no tolerance), as the file's comment lists the degenerate contacts.
struct EdgeTriangleContact {
  /// End k (x_a, x_b) lies in the closed triangle: in its plane, inside it or on its boundary.
  /// Such an end is *on the sheet*; the edge is not crossed there.
  std::array<bool, 2> end_on_sheet{false, false};
  /// The ends lie strictly on opposite sides of the triangle's plane and the segment meets the
  /// plane in the closed triangle (a point on the triangle's boundary counts).
  bool crossed = false;
  /// Where it is crossed: s = h_a / (h_a - h_b) in [0, 1] from the ends' heights over the plane
  /// (in doubles), the point (1 - s) x_a + s x_b; 0 where not crossed.
  double parameter = 0.0;
};

/// The edge test of the semi-progressive cut: how the segment x_a x_b meets the triangle.
/// @param triangle a non-degenerate triangle of the swept sheet (m, reference configuration)
EdgeTriangleContact edge_triangle_contact(const SweptTriangle& triangle, const Eigen::Vector3d& x_a, const Eigen::Vector3d& x_b);

/// The tet test of the semi-progressive cut (Kerf's own; it replaces Gutierrez and Ramos's "third
/// crossed edge", section 3.3): whether the sheet has crossed a tet. The corners that are not on
/// the sheet, joined by the tet's edges that are not crossed and have neither end on the sheet,
/// fall into two or more groups. A planar sheet separates them with 3 crossed edges around a
/// corner or with 4 splitting the corners 2:2; a corner on the sheet belongs to neither side, so
/// a sheet through a corner that crosses the opposite face's edges crosses the tet, and one that
/// only touches a corner (grazing) does not.
/// @param edge_crossed    per edge of the tet, in the order of tet_edge_corners
/// @param corner_on_sheet per corner 0..3
bool tet_corners_separated(const std::array<bool, 6>& edge_crossed, const std::array<bool, 4>& corner_on_sheet);

/// The running state of one cut through a mesh: the crossed edges, the nodes on the sheet and the
/// crossed tets, updated one swept sheet (a frame's quad) at a time.
///
/// Everything lives in the reference configuration: the triangles handed in must already be
/// pulled back from the world, if the mesh has moved (Koschier et al. 2017, Fig. 2).
class SemiProgressiveCut {
public:
  /// Builds the edge structure once: the #E unique edges of the corners (a Tet10's edges are
  /// straight, so its corners suffice), the tets around each edge, the tets around each node,
  /// and an AABB tree of the edges as segments. O(#T log #T).
  explicit SemiProgressiveCut(const TetMesh& mesh);
  ~SemiProgressiveCut();
  SemiProgressiveCut(SemiProgressiveCut&&) noexcept;
  SemiProgressiveCut& operator=(SemiProgressiveCut&&) noexcept;

  /// Adds a piece of swept sheet (e.g. swept_quad of one frame) and returns the tets that became
  /// crossed in this call, in increasing order.
  ///
  /// Cost: for each triangle one query of the edge tree, O(log #E + k) with k the edges whose
  /// boxes meet the triangle's box (only those get the exact tests), then the tets around the
  /// newly crossed edges and newly touched nodes are re-examined, O(1) each. So a call costs what
  /// the triangles' neighbourhood holds, never #E or #T.
  std::vector<int> add_swept_triangles(const std::vector<SweptTriangle>& triangles);

  /// Number of unique edges #E.
  int num_edges() const;
  /// The two nodes of edge e, the smaller first.
  std::array<int, 2> edge_nodes(int e) const;
  /// The six edges of tet t, in the order of tet_edge_corners.
  std::array<int, 6> tet_edges(int t) const;

  /// Whether edge e has been crossed.
  bool edge_crossed(int e) const;
  /// Where edge e was crossed (the first time); only for a crossed edge.
  const EdgeCrossing& edge_crossing(int e) const;
  /// How many of tet t's edges are crossed, 0..6: G's lists L1, L2, L3 are the tets with 1, 2, 3.
  int num_crossed_edges(int t) const;
  /// Whether node v lies on the sheet (in a swept triangle, exactly).
  bool node_on_sheet(int v) const;
  /// Number of edges crossed so far.
  int num_crossed_edges_total() const;
  /// Number of nodes on the sheet so far.
  int num_nodes_on_sheet() const;

  /// Whether tet t has been crossed.
  bool tet_crossed(int t) const;
  /// The crossed tets so far, in the order they became crossed (within one call, increasing).
  const std::vector<int>& crossed_tets() const;
  /// Where the sheet meets tet t's edges: the crossing points of its crossed edges (in the order
  /// of tet_edge_corners) followed by its corners on the sheet. For a crossed tet cut by one plane
  /// these are the corners of its cut polygon (a triangle or a quad), unordered.
  std::vector<Eigen::Vector3d> cut_points(int t) const;

private:
  struct Data;
  std::unique_ptr<Data> data_;
};

} // namespace kerf
