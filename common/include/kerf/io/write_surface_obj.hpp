/// @file write_surface_obj.hpp
/// @brief Write a triangle surface as a Wavefront .obj file, which read_surface() and ParaView read back.
#pragma once

#include "kerf/mesh/triangle_surface.hpp"

#include <filesystem>

namespace kerf {

/// Writes `surface` as `v x y z` lines (17 significant digits, so that reading it back gives
/// bitwise the same vertices) and 1-based `f i j k` lines, in the surface's order. The parent
/// folder is created when missing.
/// @throws InputError `FILE: write: PROBLEM` when the file cannot be written
void write_surface_obj(const std::filesystem::path& file, const TriangleSurface& surface);

} // namespace kerf
