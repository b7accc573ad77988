// Private to the kerf library (not under include/): running a VTK reader so that its complaints
// become InputErrors, and the checks of what it read that make its cells safe to walk. Shared
// by the tet mesh reader (read_vtk.cpp) and the surface reader (read_vtk_triangles.cpp).
#pragma once

#include "mesh/vtk_error_catcher.hpp"

#include <vtkAlgorithm.h>
#include <vtkCellArray.h>
#include <vtkDataObject.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>

#include <ostream>
#include <string>

namespace kerf {

/// Runs `reader` with `catcher` listening to it and to its executive, passes the warnings on
/// (one line each) and turns the first error into an InputError naming `file`.
/// @return the reader's output, which is not null
vtkSmartPointer<vtkDataObject> run_vtk_reader(vtkAlgorithm& reader, VtkMessageCatcher& catcher,
                                              const std::string& file, std::ostream* warnings);

/// Refuses a cell array that cannot be walked safely. VTK's readers take a file's offsets on
/// trust: an offset that goes backwards, or past the end of the connectivity, reaches
/// GetCellAtId() as a negative length and crashes it, and a point id out of range would make
/// any later look-up of the cell's points read outside the points.
/// @param cells      the cells (null or empty passes)
/// @param num_points the number of points the ids must stay below
/// @param cell_name  what one cell is called in messages ("cell", "polygon"), with "s" for many
void check_cell_array(vtkCellArray* cells, vtkIdType num_points, const std::string& file,
                      const std::string& cell_name);

/// check_cell_array() on a grid's cells, and a cell type per cell: a type list of the wrong
/// length makes GetCellType() read past its end.
void check_grid_cells(vtkUnstructuredGrid& grid, const std::string& file);

} // namespace kerf
