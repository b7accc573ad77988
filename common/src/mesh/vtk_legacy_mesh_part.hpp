// Private to the kerf library (not under include/): the check read_vtk.cpp and
// read_vtk_triangles.cpp run on a legacy .vtk file before VTK's own reader sees it.
#pragma once

#include <string>

namespace kerf {

/// The legacy datasets a caller reads: tet meshes come as unstructured grids, cut surfaces as
/// either an unstructured grid of triangles or polydata.
enum class VtkLegacyDataset {
  unstructured_grid,            ///< `DATASET UNSTRUCTURED_GRID`: POINTS, CELLS, CELL_TYPES
  unstructured_grid_or_polydata ///< that, or `DATASET POLYDATA`: POINTS, POLYGONS or TRIANGLE_STRIPS (and VERTICES, LINES)
};

/// The part of a legacy .vtk file that VTK's reader may see, checked: the header, the points
/// and the cells, without the point and cell data.
///
/// VTK 9.1's legacy reader trusts its input. A CELLS line without its counts, a count larger
/// than the file, a cell list shorter than announced or a word that is not a number where it
/// reads one sends it down error paths that dereference null pointers or free memory twice.
/// So, before it reads a byte:
///
/// - the fourth line must be `DATASET UNSTRUCTURED_GRID` (or, if `datasets` allows it,
///   `DATASET POLYDATA`) and nothing else;
/// - an unstructured grid must have a POINTS, a CELLS and a CELL_TYPES line, polydata a POINTS
///   and a POLYGONS or TRIANGLE_STRIPS line, each with its counts, each count at most the file's size in bytes
///   (every item takes at least one byte). Polydata's VERTICES, LINES, POLYGONS and
///   TRIANGLE_STRIPS are cell lists laid out as CELLS is, and are checked as CELLS is;
/// - in an ASCII file, the data after them must be what they announce: 3 finite coordinates
///   per point (within float's range for `float`), and for the cells either count-prefixed
///   lists of integer ids that fill exactly the announced size (format before 5) or OFFSETS
///   and CONNECTIVITY lists of integers of the announced lengths (format 5), then one cell type
///   in [0, 255] per cell; in a binary file, the count-prefixed cell lists (format before 5)
///   must fill exactly the announced size, since VTK walks them trusting each count;
/// - a FIELD block (field data of the whole grid) must hold arrays of known types with as many
///   values as they announce, finite ones in ASCII; VTK dereferences a null pointer when one of
///   them cannot be read. In a binary file only fixed-width numeric arrays are accepted;
/// - everything from the first POINT_DATA or CELL_DATA line on is cut off: Kerf reads no
///   fields, and those sections are where the reader is most easily crashed.
///
/// @param text the whole file
/// @param file the file name used in messages
/// @param datasets the datasets the caller reads
/// @return the start of `text` that holds the header, the points and the cells
/// @throws InputError `FILE: line N: PROBLEM` for the first problem found
std::string vtk_legacy_mesh_part(const std::string& text, const std::string& file, VtkLegacyDataset datasets);

} // namespace kerf
