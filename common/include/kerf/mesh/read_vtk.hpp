/// @file read_vtk.hpp
/// @brief Read a tetrahedral mesh from a VTK unstructured grid: XML .vtu or legacy .vtk.
#pragma once

#include "kerf/mesh/tet_mesh.hpp"

#include <filesystem>
#include <ostream>

namespace kerf {

/// Reads the tetrahedra of a VTK unstructured grid with VTK's own readers: the XML format
/// (`.vtu`, ASCII, binary or appended, compressed or not) or the legacy format (`.vtk`,
/// `DATASET UNSTRUCTURED_GRID`, ASCII or binary).
///
/// - VTK_TETRA cells become Tet4, VTK_QUADRATIC_TETRA cells Tet10 (VTK's node order is Kerf's);
///   a file must hold one of the two, not both.
/// - Cells of dimension 0, 1 or 2 (vertices, lines, triangles, quads) are skipped without a
///   word; other 3D cells (hexahedra, wedges, pyramids, ...) are rejected.
/// - Every point of the file becomes a node, in the file's order, so point indices in the
///   file and in the mesh agree. Point and cell data are not read; in a legacy file VTK does
///   not even see them, and the points and cells are checked before VTK reads them (counts
///   against the file's size, and in ASCII the data against the counts), because VTK 9.1's
///   legacy reader crashes on a missing count or a short list instead of reporting it.
/// - In a .vtu file, the count attributes (NumberOfPoints, NumberOfComponents, ...) must be
///   integers that fit in 32 bits, which VTK's XML reader does not check.
/// - Cell offsets must increase from 0 to the length of the connectivity, with one cell type
///   per cell (VTK's readers do not check this, and walking such cells crashes).
///
/// VTK's readers do not throw: they report problems as events. We listen to the reader's
/// error and warning events (so VTK prints nothing on its own), turn the first error into an
/// InputError, and pass warnings on, one line each.
///
/// @param file     the .vtu or .vtk file
/// @param warnings where warnings go (one line each), or nullptr to stay quiet
/// @return the mesh: #V by 3 nodes, #T by 4 or #T by 10 tets
/// @throws InputError `FILE: FIELD: PROBLEM` for a missing, unreadable or malformed file
TetMesh read_vtk(const std::filesystem::path& file, std::ostream* warnings);

} // namespace kerf
