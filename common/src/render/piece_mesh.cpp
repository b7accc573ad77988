#include "kerf/render/piece_mesh.hpp"

#include "kerf/app/input_error.hpp"
#include "mesh/file_bytes.hpp"
#include "mesh/vtk_error_catcher.hpp"
#include "mesh/vtk_reader_checks.hpp"
#include "mesh/vtu_counts.hpp"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <string>

namespace kerf {

vtkSmartPointer<vtkUnstructuredGrid> read_piece_mesh(const std::filesystem::path& file) {
  const std::string name = file.string();
  if (lower_extension(file) != ".vtu") throw InputError(name, "file", "expected a .vtu file (VTK XML unstructured grid)");
  check_vtu_counts(file_bytes(file, name), name);

  // As the mesh reader does (mesh/read_vtk.cpp): our observer hears the XML parser's and the
  // reader's complaints, and the first error becomes an InputError naming the file.
  vtkNew<VtkMessageCatcher> catcher;
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetParserErrorObserver(catcher);
  reader->SetReaderErrorObserver(catcher);
  reader->SetFileName(name.c_str());
  vtkSmartPointer<vtkUnstructuredGrid> grid =
      vtkUnstructuredGrid::SafeDownCast(run_vtk_reader(*reader, *catcher, name, nullptr));
  if (!grid) throw InputError(name, "VTK reader", "the file holds no unstructured grid");
  check_grid_cells(*grid, name);
  if (grid->GetNumberOfCells() == 0) throw InputError(name, "cells", "the file has no cells to draw");

  vtkDataArray* u = grid->GetPointData()->GetArray("displacement");
  if (!u) throw InputError(name, "displacement", "no point array 'displacement' (a body's moves are needed to draw it moved)");
  if (u->GetNumberOfComponents() != 3)
    throw InputError(name, "displacement", "expected 3 components per point, found " + std::to_string(u->GetNumberOfComponents()));
  return grid;
}

void require_cell_array(vtkUnstructuredGrid& grid, const std::string& name, const std::filesystem::path& file) {
  vtkCellData* cells = grid.GetCellData();
  vtkDataArray* array = cells->GetArray(name.c_str());
  if (array && array->GetNumberOfComponents() == 1) return;
  std::string arrays;
  for (int i = 0; i < cells->GetNumberOfArrays(); ++i)
    if (const char* array_name = cells->GetArrayName(i)) arrays += (arrays.empty() ? "" : ", ") + std::string(array_name);
  const std::string problem = array ? "the cell array has " + std::to_string(array->GetNumberOfComponents()) + " components, expected 1"
                                    : "no cell array of that name (the file has: " + (arrays.empty() ? std::string("none") : arrays) + ")";
  throw InputError(file.string(), name, problem);
}

} // namespace kerf
