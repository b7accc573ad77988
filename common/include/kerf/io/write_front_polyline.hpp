/// @file write_front_polyline.hpp
/// @brief Write the crack fronts as VTK poly lines (.vtp), which ParaView opens beside the pieces' .vtu.
#pragma once

#include "kerf/cut/crack_front.hpp"

#include <filesystem>

namespace kerf {

/// Writes every front of `fronts` as one VTK_POLY_LINE cell of an XML PolyData file (.vtp,
/// ASCII, so that it can be read and diffed as text), its points those of the polyline in order
/// (a closed front repeats its first point at the end, as FrontPolyline::points does).
/// Point data: `tangent` (the vertex frame's c) and `normal` (its b, the cut's normal, towards
/// the side Kerf calls above), both unit, so that ParaView's Glyph filter draws the frame the
/// branch functions are measured in. Cell data: `front` (0-based index), `closed` (0 or 1) and
/// `length` (m). No fronts: a valid file with no points. The parent folder is created when
/// missing.
/// @throws InputError `FILE: write: PROBLEM` when the file cannot be written
void write_front_polyline(const std::filesystem::path& file, const CrackFronts& fronts);

} // namespace kerf
