/// @file height_field_surface.hpp
/// @brief A curved cut z = z_c + h(x, y) over a rectangle, as a triangle surface: chapter 4's blades written in code.
#pragma once

#include "kerf/mesh/triangle_surface.hpp"

#include <Eigen/Core>
#include <functional>

namespace kerf {

/// A height h(x, y) in metres above a reference plane z = z_c, at the point (x, y) in metres.
using HeightField = std::function<double(double x, double y)>;

/// Triangulates the graph z = z_c + h(x, y) over the rectangle [min_x, max_x] x [min_y, max_y].
///
/// The rectangle is divided into cells[0] by cells[1] equal cells; vertex (i, j), at
/// x_i = min_x + (i / nx) (max_x - min_x), y_j = min_y + (j / ny) (max_y - min_y), is row
/// i + (nx + 1) j (x fastest, as make_box_mesh() numbers the nodes of a layer) and lies exactly
/// on the graph: its z is the double z_c + h(x_i, y_j). Each cell is split along its diagonal
/// from (i, j) to (i + 1, j + 1), the diagonal make_box_mesh() uses for the faces of a node layer,
/// into the triangles (i,j) (i+1,j) (i+1,j+1) and (i,j) (i+1,j+1) (i,j+1), in that order, cell
/// after cell (x fastest). Both traverse their projection counter-clockwise seen from above, so
/// the normals (x1 - x0) x (x2 - x0) have a positive z component whatever h is: "above" is +z.
///
/// The surface is the piecewise-linear interpolant of the graph on that grid: exact for a
/// plane, and for a kink (a ridge) when the kink lies on grid lines. It passes
/// check_triangle_surface() unchanged (its projection onto the plane z = 0 is a valid
/// triangulation of the rectangle, so nothing is degenerate, repeated, welded or flipped), with
/// one component and 2 (nx + ny) boundary edges, all on the rectangle's sides.
///
/// @param h      the height above z_c, called once per vertex; its values must be finite
/// @param z_c    the reference plane's height (m)
/// @param min    (min_x, min_y) of the rectangle (m)
/// @param max    (max_x, max_y), componentwise larger than min
/// @param cells  nx, ny, each at least 1
/// @return (nx + 1)(ny + 1) vertices and 2 nx ny triangles
/// @throws std::invalid_argument if h is empty or returns a value that is not finite, a cell
///         count is below 1 or max does not exceed min
TriangleSurface height_field_surface(const HeightField& h, double z_c, const Eigen::Vector2d& min, const Eigen::Vector2d& max,
                                     const Eigen::Vector2i& cells);

} // namespace kerf
