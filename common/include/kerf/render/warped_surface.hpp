/// @file warped_surface.hpp
/// @brief The surface a picture of a cut body shows: its pieces moved by their displacement, optionally clipped by a plane.
#pragma once

#include <Eigen/Core>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>

#include <optional>

namespace kerf {

/// A plane n . (x - o) = 0 through the moved body; the part on the side n points to is kept.
struct ClipPlane {
  Eigen::Vector3d origin; ///< o, a point of the plane (m, in the moved configuration)
  Eigen::Vector3d normal; ///< n, pointing into the part that is kept (any nonzero length)
};

/// Name of the point array warped_surface adds: |u|, the length of the displacement (m).
inline constexpr const char* displacement_magnitude_name = "displacement_magnitude";

/// The outer surface of the body after every point has moved from x to x + s u(x).
///
/// The pieces of a cut tet have points of their own (piece_mesh.hpp), so each piece's faces on
/// the cut are outer faces: once the pieces have moved apart, the surface shows the cut open.
/// With a clip plane the moved body is cut first (the cells it crosses are clipped, not
/// dropped), so that the surface shows the section, and the gap where the section crosses it.
///
/// @param grid  the body, with the point array `displacement` (#points by 3, m)
/// @param scale s, the factor on the displacement: 1 draws the body as it moved, 0 unmoved
/// @param clip  the plane, or none to draw the whole body
/// @return the surface, with the grid's point arrays (interpolated on a clip), its cell
///         arrays, and the point array displacement_magnitude_name (|u| of the file, unscaled)
vtkSmartPointer<vtkPolyData> warped_surface(vtkUnstructuredGrid& grid, double scale,
                                            const std::optional<ClipPlane>& clip);

} // namespace kerf
