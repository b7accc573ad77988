/// @file tet_mesh.hpp
/// @brief The tetrahedral mesh every chapter works on: node positions and Tet4 or Tet10 connectivity.
#pragma once

#include <Eigen/Core>

namespace kerf {

/// #V by 3 node positions, one row per node (row-major so a row is one contiguous point).
using NodeMatrix = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
/// #T by 4 (Tet4) or #T by 10 (Tet10) node indices, 0-based, one row per tetrahedron.
using TetMatrix = Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// A conforming tetrahedral mesh of linear (Tet4) or quadratic (Tet10) elements.
///
/// Node order inside a tet follows VTK and CalculiX (C3D4, C3D10): corners 0..3 with positive
/// orientation, det[x1-x0, x2-x0, x3-x0] > 0, then for Tet10 the mid-edge nodes of the edges
/// (0,1), (1,2), (0,2), (0,3), (1,3), (2,3). Readers convert other orders (Gmsh) into this one.
struct TetMesh {
  NodeMatrix nodes; ///< #V by 3 node positions in metres
  TetMatrix tets;   ///< #T by 4 or #T by 10 connectivity

  /// Number of nodes #V.
  Eigen::Index num_nodes() const { return nodes.rows(); }
  /// Number of tetrahedra #T.
  Eigen::Index num_tets() const { return tets.rows(); }
  /// 4 for Tet4, 10 for Tet10.
  int nodes_per_tet() const { return static_cast<int>(tets.cols()); }
  /// Polynomial order of the shape functions: 1 for Tet4, 2 for Tet10.
  int order() const { return tets.cols() == 10 ? 2 : 1; }
};

/// The positions of the four corners of tet t, one row each (also the corners of a Tet10).
inline Eigen::Matrix<double, 4, 3> tet_corners(const TetMesh& mesh, Eigen::Index t) {
  Eigen::Matrix<double, 4, 3> X;
  for (int a = 0; a < 4; ++a) X.row(a) = mesh.nodes.row(mesh.tets(t, a));
  return X;
}

/// The displacements of tet t's first n nodes (n = 4 or 10), one row each, from a node-major
/// vector u (component p of node v at 3 v + p).
template <int n>
Eigen::Matrix<double, n, 3> tet_node_displacements(const TetMesh& mesh, const Eigen::VectorXd& u, Eigen::Index t) {
  Eigen::Matrix<double, n, 3> u_e;
  for (int a = 0; a < n; ++a) u_e.row(a) = u.template segment<3>(3 * mesh.tets(t, a)).transpose();
  return u_e;
}

/// The local corner pairs of the six tet edges, in the order of the Tet10 mid-edge nodes 4..9.
inline constexpr int tet_edge_corners[6][2] = {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}};

/// The face opposite corner a, listed so that its normal points away from corner a when the
/// tet is positively oriented (see check_tet_mesh.hpp).
inline constexpr int tet_outward_face_corners[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

/// The local Tet10 node on the edge between corners i and j (4..9), -1 if i and j are no edge.
inline int tet10_edge_node(int i, int j) {
  for (int e = 0; e < 6; ++e)
    if ((tet_edge_corners[e][0] == i && tet_edge_corners[e][1] == j) || (tet_edge_corners[e][0] == j && tet_edge_corners[e][1] == i))
      return 4 + e;
  return -1;
}

} // namespace kerf
