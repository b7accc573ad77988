/// @file piece_mesh.hpp
/// @brief Read a cut body's pieces for drawing: a .vtu with the point data `displacement`.
#pragma once

#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>

#include <filesystem>
#include <string>

namespace kerf {

/// Reads a .vtu file as Kerf's programs write them (io/write_vtu.hpp), in particular the XFEM
/// view of a cut body (write_cut_xfem_vtu in xfem/cut_xfem_output.hpp), in which every piece
/// of a cut tet has points of its own, so that the pieces part when they are moved.
///
/// The file gets the checks the mesh reader gives a .vtu (mesh/read_vtk.hpp: its counts before
/// VTK trusts them, its cells before they are walked, VTK's complaints as errors), and then
/// the one thing a picture of a moved body needs: a point array `displacement` with three
/// components (metres). Every other point or cell array is kept as it is.
///
/// @param file the .vtu file
/// @return the grid, with at least one cell and the point array `displacement`
/// @throws InputError `FILE: FIELD: PROBLEM` for a missing, unreadable or malformed file
///         (FIELD `file`, `VTK reader`, ...), a grid without cells (`cells`), or a missing or
///         wrongly shaped displacement (`displacement`)
vtkSmartPointer<vtkUnstructuredGrid> read_piece_mesh(const std::filesystem::path& file);

/// Checks that the grid read from `file` has a cell array called `name` with one component,
/// before a picture is coloured by it (surface_image.hpp).
/// @throws InputError `FILE: NAME: ...`, listing the cell arrays the file has
void require_cell_array(vtkUnstructuredGrid& grid, const std::string& name, const std::filesystem::path& file);

} // namespace kerf
