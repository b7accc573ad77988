/// @file split_mesh_along_cut.hpp
/// @brief Open a mesh that conforms to a rectangular cut by duplicating the nodes on the cut: chapter 3's reference solution.
#pragma once

#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/mesh/tet_mesh.hpp"

#include <vector>

namespace kerf {

/// A mesh opened along a cut, and where its new nodes come from.
struct SplitMesh {
  /// The split mesh: the original nodes first (same indices), then one duplicate per node on
  /// the cut, at the same position; the tets below the cut use the duplicates.
  TetMesh mesh;
  /// The original node of each duplicate: node original_#V + k copies node duplicate_of[k].
  /// Its size is duplicated_nodes; entries are in increasing order of the original index.
  std::vector<int> duplicate_of;
  int duplicated_nodes = 0; ///< number of duplicates, mesh.num_nodes() - original #V
};

/// Disconnects the elements on either side of a planar rectangular cut in a mesh whose faces
/// already follow the cut, by giving the tets below the cut their own copies of the nodes on it.
///
/// Why: XFEM's answer to "what does the cut body do" needs a reference that does not use XFEM.
/// Schoch et al. (section 6.1) validate against "input files where the cut is already perfectly
/// remeshed, i.e., where the elements on either side of the cut are disconnected and aligned
/// with the cut's course". A mesh with a node layer on the cut plane is aligned with it;
/// duplicating the nodes on the cut disconnects it, and a plain FEM solve (or CalculiX) on the
/// result is the reference chapter 3 compares to.
///
/// The rule, with "on the plane" meaning |signed distance| <= tolerance:
/// - a node is duplicated iff it is on the plane, its projection is in the rectangle (closed,
///   enlarged by `tolerance`), and it is not on the cut's front, the part of the rectangle's
///   boundary that lies inside the body, where the material is still whole;
/// - "not on the front" is decided from the mesh, not from distances to the rectangle's edges:
///   at least one interior face (shared by two tets) lies in the plane and contains the node, and
///   every such face has all its corners' projections in the rectangle. A node on the front also
///   touches plane faces beyond the rectangle, where the body is uncut; a node where the
///   rectangle's edge meets the body's surface does not, and is duplicated, so the cut runs out
///   of the body there. A Tet10 mid-edge node follows the same rule through the faces it is one
///   of the six nodes of. A node of a tet with corners strictly on both sides of the plane
///   (allowed beyond the rectangle only) is on the front too: the material goes on across the
///   plane there, even where the mesh has no plane faces beyond the front;
/// - every tet whose centroid is below the plane (signed distance < 0) takes the duplicates of
///   its duplicated nodes. Node order inside each tet, hence its orientation, is unchanged.
///
/// @param mesh      Tet4 or Tet10 mesh with straight edges
/// @param cut       the rectangle; "below" is the side opposite its normal
/// @param tolerance distance (m) within which a node counts as on the plane, and by which the
///                  rectangle is enlarged (for "in the rectangle") or shrunk (for the check below)
/// @return the split mesh and the map from duplicates to originals
/// @throws std::invalid_argument if the mesh does not conform to the cut: a tet has corners
///         strictly above and strictly below the plane (beyond `tolerance`) and its section by
///         the plane overlaps the rectangle shrunk by `tolerance`; the message names the tet.
///         Also for a negative tolerance or a mesh that is neither Tet4 nor Tet10.
SplitMesh split_mesh_along_cut(const TetMesh& mesh, const RectangleCut& cut, double tolerance);

} // namespace kerf
