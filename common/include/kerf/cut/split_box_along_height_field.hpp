/// @file split_box_along_height_field.hpp
/// @brief The box meshed to follow a curved cut z = z_c + h(x, y) clean through it, and opened along it: chapter 4's reference.
#pragma once

#include "kerf/cut/height_field_surface.hpp"
#include "kerf/cut/split_mesh_along_cut.hpp"
#include "kerf/mesh/triangle_surface.hpp"

#include <Eigen/Core>

namespace kerf {

/// A box mesh opened along a curved node layer, and that layer as the cut surface.
struct HeightFieldSplitMesh {
  /// The opened mesh with SplitMesh's contract: the mapped box nodes first (make_box_mesh()'s
  /// numbering, then for Tet10 tet10_from_tet4()'s mid-edge nodes), then one duplicate per node
  /// of the layer, in increasing order of the original, at the same position; the tets below
  /// the layer use the duplicates, the tets above the originals.
  SplitMesh split;
  /// The layer's faces, oriented with normals to +z (out of the part below): the
  /// piecewise-linear interpolant of z = z_c + h on the box's x-y grid. Vertex s is the layer's
  /// corner node layer (nx + 1)(ny + 1) + s of the mesh, at the same position; the triangles
  /// are those of height_field_surface(h, z_c, min, max, {nx, ny}), in the same order, so that
  /// this is exactly the surface an XFEM run on the unmapped box is given.
  TriangleSurface cut_surface;
  int layer = 0; ///< the index k (0 < k < nz) of the box's node layer that was moved onto the cut
};

/// Meshes the box [min, max] so that its faces follow the cut z = z_c + h(x, y) through its
/// whole cross-section, and disconnects the two parts along the cut.
///
/// Why: chapter 4 compares XFEM on box meshes that ignore a curved cut with plain FEM on a mesh
/// that follows it and is opened along it (Schoch et al., section 6.1's "perfectly remeshed" cut),
/// as chapter 3 did for a plane with split_mesh_along_cut().
///
/// Construction, in four steps:
/// 1. make_box_mesh(min, max, cells); the node layer k nearest to z_c (never a face of the box)
///    is put at z_c exactly, and the layers below and above it are spaced evenly again, as
///    chapter 3 fits its layer to a cut plane (a piecewise-linear map of z that keeps every tet
///    positive). Its x and y are those of height_field_surface(), exactly;
/// 2. every node moves vertically, z -> z + h(x, y) b(z), with the blend b(z) = (z - z_0) /
///    (z_c - z_0) below the layer and (z_1 - z) / (z_1 - z_c) above (z_0 = min z, z_1 = max z):
///    1 on the layer, whose nodes land exactly on z_c + h(x, y) (the double z_c + h, as in
///    height_field_surface()), 0 on the faces z = z_0 and z = z_1, which stay flat. Nodes move
///    only in z, so the side faces stay in their planes and the mapped mesh fills the box;
/// 3. for order 2, tet10_from_tet4() of the mapped Tet4 mesh: mid-edge nodes on straight edges;
/// 4. the layer's nodes (its corners and, for Tet10, the mid-edge nodes of its edges) are
///    duplicated for the tets below, as split_mesh_along_cut() does; the cut runs through the
///    whole cross-section, so there is no front and no node stays shared.
///
/// Why every tet stays positive, and by how much its volume changes. A Kuhn tet walks from one
/// corner of its cell to the opposite one in three steps along the three axes; the corners of
/// its z step share x and y, say (x_a, y_a), a node of the grid. The move is the linear
/// interpolant of the nodal shifts, so its Jacobian is the identity plus e_z g^T, with g the
/// gradient of the interpolated shift, and its determinant is 1 + g_z. Along the z step, g_z is
/// the difference quotient h(x_a, y_a) (b(z_k+1) - b(z_k)) / (z_k+1 - z_k), and b is linear in
/// each cell layer, so the tet's volume is multiplied exactly by
///     1 + h(x_a, y_a) / (z_c - z_0)  below the layer,   1 - h(x_a, y_a) / (z_1 - z_c)  above.
/// Every tet stays positive iff -(z_c - z_0) < h < z_1 - z_c at every grid node: for the beam
/// (z_c - z_0 = z_1 - z_c = 0.1 m) and amplitudes of a few mm, every volume changes by a few
/// per cent at most. The function checks this bound and refuses heights outside it.
///
/// What it does to volumes: the mapped mesh still fills the box exactly (a positive
/// piecewise-affine map that keeps the box's boundary on itself), so the total volume is the
/// box's for every h, zero mean or not. The split moves volume between the parts: the part
/// below holds the prism under the cut surface, (x_1 - x_0)(y_1 - y_0)(z_c - z_0) plus, over
/// each triangle of cut_surface, its projected area times the mean of h at its corners.
///
/// @param min      lower corner of the box (m)
/// @param max      upper corner of the box (m), componentwise larger than min
/// @param cells    nx, ny, nz cells; nz at least 2 (a layer strictly inside)
/// @param z_c      the cut's reference height, min z < z_c < max z
/// @param h        the cut's height above z_c, evaluated at the grid's (x, y); finite
/// @param order    1 (Tet4) or 2 (Tet10)
/// @return the opened mesh, the map from duplicates to originals, the cut surface and the layer
/// @throws std::invalid_argument for an order other than 1 or 2, cells below 1 (nz below 2), an
///         empty box, z_c outside (min z, max z), an empty h, or a height at a grid node that is
///         not finite or not strictly between -(z_c - min z) and max z - z_c (a tet would flip);
///         the message names the node
HeightFieldSplitMesh split_box_along_height_field(const Eigen::Vector3d& min, const Eigen::Vector3d& max, const Eigen::Vector3i& cells,
                                                  double z_c, const HeightField& h, int order);

} // namespace kerf
