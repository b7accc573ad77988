/// @file boundary_faces.hpp
/// @brief The triangles on the surface of a tet mesh, oriented outward: where tractions act.
#pragma once

#include "kerf/mesh/tet_mesh.hpp"
#include "kerf/mesh/triangle_surface.hpp"

#include <vector>

namespace kerf {

/// The boundary of a tet mesh: every face that belongs to exactly one tet.
struct BoundaryFaces {
  /// #F by 3 (Tet4 mesh) or #F by 6 (Tet10 mesh) node indices. Corners first, ordered so that
  /// (x1 - x0) x (x2 - x0) points out of the body; for six-node faces the mid-edge nodes of the
  /// edges (0,1), (1,2), (2,0) follow (VTK's quadratic-triangle order).
  TetMatrix faces;
  std::vector<int> tet;        ///< the tet each face belongs to
  std::vector<int> local_face; ///< which face of that tet: the index of the corner opposite it
};

/// Finds the faces that only one tet owns. Cost O(#T) with a hash map keyed by sorted corners.
BoundaryFaces boundary_faces(const TetMesh& mesh);

/// The boundary as a triangle surface of its own: the corners of the faces, renumbered over the
/// nodes they use (chapter 7 draws a mesh read from a file by it).
TriangleSurface boundary_surface(const TetMesh& mesh);

/// Area of face f (its corners; mid-edge nodes lie on straight edges and do not change it).
double face_area(const TetMesh& mesh, const BoundaryFaces& boundary, Eigen::Index f);

} // namespace kerf
