/// @file triangle_surface.hpp
/// @brief A cut surface given as a triangle mesh: vertex positions and 0-based triangles.
#pragma once

#include <Eigen/Core>

namespace kerf {

/// A surface made of flat triangles, the form in which a user hands Kerf a cut that is not a
/// plane (from chapter 4 on; read_surface() reads one from a file).
///
/// Once it has passed check_triangle_surface() (every reader calls it), a surface keeps these
/// promises, which the geometry of cuts builds on:
/// - no two vertices share a position, and every vertex belongs to a triangle;
/// - no triangle is degenerate (its three corners are not collinear, decided exactly) and no
///   two triangles have the same three corners;
/// - every edge belongs to one triangle (a boundary edge, part of the cut's front) or two;
/// - the triangles are oriented consistently: two triangles that share an edge traverse it in
///   opposite directions, so the normals (x1 - x0) x (x2 - x0) all point to one side, the side
///   Kerf calls above (H = +1).
struct TriangleSurface {
  Eigen::MatrixX3d vertices;  ///< #V by 3 vertex positions in metres, one row per vertex
  Eigen::MatrixX3i triangles; ///< #F by 3 vertex indices, 0-based, one row per triangle

  /// Number of vertices #V.
  Eigen::Index num_vertices() const { return vertices.rows(); }
  /// Number of triangles #F.
  Eigen::Index num_triangles() const { return triangles.rows(); }
};

} // namespace kerf
