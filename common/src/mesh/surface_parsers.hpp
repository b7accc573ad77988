// Private to the kerf library (not under include/): the parsers behind read_surface(), one per
// format. Each turns a file into a surface as the file states it; read_surface() then scales
// it and puts it through check_triangle_surface(), so none of them checks geometry.
#pragma once

#include "kerf/mesh/triangle_surface.hpp"

#include <array>
#include <filesystem>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace kerf {

/// The vertices and triangles that a parser gathered, as a surface.
TriangleSurface surface_from_lists(const std::vector<std::array<double, 3>>& vertices,
                                   const std::vector<std::array<int, 3>>& triangles);

/// Wavefront OBJ: `v x y z` vertices (with an optional weight w, or a colour r g b, which are
/// read as numbers and dropped), `f i j k ...` faces (fan-triangulated), each index
/// `i`, `i/t`, `i//n` or `i/t/n`, counted from 1, or from -1 backwards from the last vertex
/// read. `vt`, `vn`, `vp`, `g`, `o`, `s`, `usemtl`, `mtllib`, `l` and `p` lines are skipped;
/// any other statement (free-form curves and surfaces among them) is refused.
TriangleSurface parse_obj(std::string_view text, const std::string& file);

/// Object File Format: `OFF`, then `#V #F #E`, #V lines `x y z`, #F lines `n i_0 ... i_{n-1}`
/// (0-based, fan-triangulated; a colour after the indices is ignored). The counts must fit
/// the file's size before anything is allocated for them.
TriangleSurface parse_off(std::string_view text, const std::string& file);

/// STL, binary or ASCII. A file is binary when its size is exactly 84 + 50 N bytes for the
/// triangle count N in bytes 80-83, whatever its first bytes say (many binary writers start
/// the 80-byte header with "solid" too); otherwise it must be ASCII and start with "solid".
/// Each triangle brings its own three vertices (check_triangle_surface() welds them); the
/// stored normals are ignored, the order of the vertices decides the orientation.
TriangleSurface parse_stl(std::string_view bytes, const std::string& file);

/// A VTK file of triangles read with VTK's readers: `.vtp` (XML polydata), `.vtu` (XML
/// unstructured grid) or `.vtk` (legacy, POLYDATA or UNSTRUCTURED_GRID; checked by
/// vtk_legacy_mesh_part() before VTK sees it). Quads and polygons are fan-triangulated,
/// triangle strips split into their triangles, vertex and line cells skipped, other cells
/// (3D, quadratic) refused.
TriangleSurface read_vtk_triangles(const std::filesystem::path& file, std::ostream* warnings);

} // namespace kerf
