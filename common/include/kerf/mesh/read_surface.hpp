/// @file read_surface.hpp
/// @brief Read a cut surface (a triangle mesh) from a file, choosing the reader by the file's extension.
#pragma once

#include "kerf/mesh/triangle_surface.hpp"

#include <filesystem>
#include <ostream>

namespace kerf {

/// Reads a triangle surface with the reader its extension names (case does not matter):
///
/// - `.obj` (Wavefront): `v x y z` vertices and `f` faces of 3 or more corners, each corner
///   written `i`, `i/t`, `i//n` or `i/t/n`, counted from 1, or backwards from the last vertex
///   read when negative; polygons are split into a fan of triangles around their first corner.
///   Texture coordinates, normals, groups, materials, lines and points are skipped; other
///   statements (free-form geometry) are refused;
/// - `.stl`, binary or ASCII: binary if the file is exactly 84 + 50 N bytes long for the count
///   N its header gives (many binary files start with "solid" too, so the first word cannot
///   decide), ASCII if it starts with "solid"; the normals in the file are ignored;
/// - `.off`: `OFF`, the counts, then the vertices and the faces (0-based, fan-triangulated);
/// - `.vtp`, `.vtu`, `.vtk` (VTK XML polydata, XML unstructured grid, legacy polydata or
///   unstructured grid) through VTK's readers, with the checks read_vtk() makes before VTK
///   trusts a file's counts; triangles, quads, polygons and strips are read, vertex and line
///   cells skipped, volume cells refused.
///
/// Every count a file announces is checked against the file's size before anything is
/// allocated for it, so a corrupt count gives an InputError, not a huge allocation.
///
/// The coordinates are multiplied by `scale`, then the surface goes through
/// check_triangle_surface(): vertices at exactly the same position are merged (STL stores
/// every triangle's corners apart), unused ones dropped, degenerate and duplicate triangles,
/// non-manifold edges and non-orientable surfaces refused, and the triangles oriented
/// consistently with the first of each connected component. One warning line says how many
/// triangles were flipped, if any.
///
/// @param file     the surface file
/// @param scale    what the coordinates are multiplied by (e.g. 0.001 for a file in mm), finite and > 0
/// @param warnings where warnings go (one line each), or nullptr to stay quiet
/// @return the checked surface: #V by 3 vertices, #F by 3 triangles
/// @throws InputError `FILE: FIELD: PROBLEM` for an unsupported extension (the message lists
///         the supported ones), a bad scale, a missing, unreadable or malformed file, FIELD
///         naming the line, section, vertex or triangle
TriangleSurface read_surface(const std::filesystem::path& file, double scale = 1.0, std::ostream* warnings = nullptr);

} // namespace kerf
