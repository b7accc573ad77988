// Private to the kerf library (not under include/): the check read_vtk.cpp and
// read_vtk_triangles.cpp run on a .vtu or .vtp file before VTK's XML reader sees it.
#pragma once

#include <string>

namespace kerf {

/// Checks the count attributes of a VTK XML file before VTK's reader trusts them.
///
/// VTK 9.1's XML reader parses `NumberOfComponents="44444444444444444443"` without a word and
/// then loops over that many components, for minutes. So every NumberOfComponents,
/// NumberOfPoints, NumberOfCells and NumberOfTuples attribute, and polydata's NumberOfVerts,
/// NumberOfLines, NumberOfStrips and NumberOfPolys, in the XML part of the file
/// (before any appended binary data) must be a non-negative integer that fits in 32 bits, and a
/// number of components may not exceed the file's size in bytes.
///
/// @param text the whole file
/// @param file the file name used in messages
/// @throws InputError `FILE: ATTRIBUTE: PROBLEM` for the first bad attribute
void check_vtu_counts(const std::string& text, const std::string& file);

} // namespace kerf
