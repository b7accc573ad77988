// The kinked cut chapter 4's model tests share: the ridge z = 0.45 + 0.1 (1 - |2x - 1|) across
// the unit cube, and a point inside a given piece of a tet.
#pragma once

#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/mesh/tet_mesh.hpp"
#include "kerf/mesh/triangle_surface.hpp"

#include <Eigen/Core>
#include <cmath>

namespace ridge_cut {

// The ridge's height above (x, y): it runs along x = 0.5.
inline double height(const Eigen::Vector3d& x) { return 0.45 + 0.1 * (1.0 - std::abs(2.0 * x.x() - 1.0)); }

// The ridge over x, y in [-0.5, 1.5], crossing the unit cube clean through: four triangles
// facing +z. Vertex 2 i + j sits at (x_i, y_j); the quads (i, i + 1) are split along a
// diagonal, counter-clockwise from +z.
inline kerf::TriangleSurface surface() {
  kerf::TriangleSurface s;
  s.vertices.resize(6, 3);
  const double xs[3] = {-0.5, 0.5, 1.5};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 2; ++j) {
      const Eigen::Vector3d p(xs[i], j == 0 ? -0.5 : 1.5, 0.0);
      s.vertices.row(2 * i + j) << p.x(), p.y(), height(p);
    }
  s.triangles.resize(4, 3);
  s.triangles << 0, 2, 3, 0, 3, 1, 2, 4, 5, 2, 5, 3;
  return s;
}

// The side of a point: +1 above the ridge, -1 below.
inline int side_of(const Eigen::Vector3d& x) { return x.z() > height(x) ? 1 : -1; }

// A point inside piece p of tet t (the mean of its first cell's corners), or the tet's centroid
// for a tet no cut meets or that is one piece.
inline Eigen::Vector3d point_in_piece(const kerf::TetMesh& mesh, const kerf::MeshPieces& pieces, Eigen::Index t, int p) {
  const int e = pieces.entry[static_cast<std::size_t>(t)];
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  if (e < 0 || pieces.num_pieces(t) == 1) {
    for (int a = 0; a < 4; ++a) x += mesh.nodes.row(mesh.tets(t, a)).transpose() / 4.0;
    return x;
  }
  const kerf::TetPieces& tp = pieces.tets[static_cast<std::size_t>(e)];
  const kerf::ConvexCell& cell = tp.cells[static_cast<std::size_t>(tp.pieces[static_cast<std::size_t>(p)].cells.front())];
  int count = 0;
  for (const kerf::CellFace& f : cell.faces)
    for (const Eigen::Vector3d& y : f.polygon) x += y, ++count;
  return x / count;
}

} // namespace ridge_cut
