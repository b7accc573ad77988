#include "mesh/vtk_reader_checks.hpp"

#include "kerf/app/input_error.hpp"

#include <vtkCommand.h>
#include <vtkExecutive.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkUnsignedCharArray.h>

namespace kerf {

vtkSmartPointer<vtkDataObject> run_vtk_reader(vtkAlgorithm& reader, VtkMessageCatcher& catcher,
                                              const std::string& file, std::ostream* warnings) {
  // Errors come from the reader and, when the reader fails, from the pipeline executive that
  // ran it ("Algorithm ... returned failure"): we listen to both.
  reader.AddObserver(vtkCommand::ErrorEvent, &catcher);
  reader.AddObserver(vtkCommand::WarningEvent, &catcher);
  reader.GetExecutive()->AddObserver(vtkCommand::ErrorEvent, &catcher);
  reader.GetExecutive()->AddObserver(vtkCommand::WarningEvent, &catcher);
  reader.Update();
  if (warnings)
    for (const auto& warning : catcher.warnings)
      *warnings << "warning: " << file << ": " << warning << "\n";
  if (!catcher.error.empty()) throw InputError(file, "VTK reader", catcher.error);
  if (reader.GetErrorCode() != 0)
    throw InputError(file, "VTK reader", "the file could not be read (VTK error code " +
                                             std::to_string(reader.GetErrorCode()) + ")");
  vtkSmartPointer<vtkDataObject> output = reader.GetOutputDataObject(0);
  if (!output) throw InputError(file, "VTK reader", "the reader returned no data");
  return output;
}

void check_cell_array(vtkCellArray* cells, vtkIdType num_points, const std::string& file,
                      const std::string& cell_name) {
  if (!cells || cells->GetNumberOfCells() == 0) return;
  if (!cells->IsValid())
    throw InputError(file, cell_name + "s", "the cell offsets do not increase from 0 to the number of "
                                            "point ids in the connectivity");
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < cells->GetNumberOfCells(); ++c) {
    cells->GetCellAtId(c, ids);
    for (vtkIdType a = 0; a < ids->GetNumberOfIds(); ++a)
      if (ids->GetId(a) < 0 || ids->GetId(a) >= num_points)
        throw InputError(file, cell_name + " " + std::to_string(c),
                         "node index " + std::to_string(ids->GetId(a)) + " is outside [0, " +
                             std::to_string(num_points) + ")");
  }
}

void check_grid_cells(vtkUnstructuredGrid& grid, const std::string& file) {
  if (grid.GetNumberOfCells() == 0) return;
  vtkCellArray* cells = grid.GetCells();
  if (!cells) throw InputError(file, "cells", "the grid announces cells but has no cell array");
  check_cell_array(cells, grid.GetNumberOfPoints(), file, "cell");
  vtkUnsignedCharArray* types = grid.GetCellTypesArray();
  const vtkIdType num_types = types ? types->GetNumberOfValues() : 0;
  if (num_types != cells->GetNumberOfCells())
    throw InputError(file, "cell types", "the file gives " + std::to_string(num_types) +
                                             " cell types for " +
                                             std::to_string(cells->GetNumberOfCells()) + " cells");
}

} // namespace kerf
