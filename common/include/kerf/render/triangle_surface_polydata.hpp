/// @file triangle_surface_polydata.hpp
/// @brief A triangle surface as VTK polydata for render_surface_image: smooth (vertex normals) or faceted.
#pragma once

#include "kerf/mesh/triangle_surface.hpp"

#include <Eigen/Core>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

namespace kerf {

/// How the triangles are lit.
enum class Shading : signed char {
  smooth, ///< one normal per vertex, the area-weighted mean of its triangles' normals: the light varies smoothly across edges
  faceted ///< one normal per triangle (each triangle gets its own copies of its corners): the facets show
};

/// Name of the cell array triangle_surface_polydata adds: the `label` it was given, the same on
/// every triangle (render_surface_image colours whole numbers -1..10 apart: -1 light grey).
inline constexpr const char* surface_label_name = "surface";

/// The triangles of `surface` as polydata with point normals, the point array
/// displacement_magnitude_name (warped_surface.hpp) and the cell array surface_label_name.
///
/// @param surface      outward-oriented triangles (the normals point out of the body)
/// @param shading      smooth or faceted
/// @param displacement_magnitude |u| per vertex (#V), or empty for zeros
/// @param label        the value of the cell array surface_label_name
/// @throws std::invalid_argument when displacement_magnitude is neither empty nor #V long
vtkSmartPointer<vtkPolyData> triangle_surface_polydata(const TriangleSurface& surface, Shading shading,
                                                       const Eigen::VectorXd& displacement_magnitude = {}, int label = -1);

} // namespace kerf
