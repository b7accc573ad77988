#include "kerf/mesh/read_vtk.hpp"

#include "kerf/app/input_error.hpp"
#include "kerf/mesh/check_tet_mesh.hpp"
#include "mesh/file_bytes.hpp"
#include "mesh/vtk_error_catcher.hpp"
#include "mesh/vtk_legacy_mesh_part.hpp"
#include "mesh/vtk_reader_checks.hpp"
#include "mesh/vtu_counts.hpp"

#include <vtkAlgorithm.h>
#include <vtkCellArray.h>
#include <vtkCellType.h>
#include <vtkCell.h>
#include <vtkCellTypes.h>
#include <vtkGenericCell.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkUnstructuredGridReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

namespace kerf {
namespace {

/// Runs a reader whose output is an unstructured grid and returns the grid.
vtkSmartPointer<vtkUnstructuredGrid> run_reader(vtkAlgorithm& reader, VtkMessageCatcher& catcher,
                                                const std::string& file, std::ostream* warnings) {
  auto* grid = vtkUnstructuredGrid::SafeDownCast(run_vtk_reader(reader, catcher, file, warnings));
  if (!grid) throw InputError(file, "VTK reader", "the file holds no unstructured grid");
  return grid;
}

/// Copies the points and the tetrahedra of a VTK grid into a TetMesh.
TetMesh mesh_from_grid(vtkUnstructuredGrid& grid, const std::string& file) {
  TetMesh mesh;
  if (!grid.GetPoints() || grid.GetNumberOfPoints() == 0)
    throw InputError(file, "points", "the file has no points");
  check_grid_cells(grid, file);
  mesh.nodes.resize(grid.GetNumberOfPoints(), 3);
  for (vtkIdType v = 0; v < grid.GetNumberOfPoints(); ++v) {
    double x[3];
    grid.GetPoint(v, x);
    mesh.nodes.row(v) << x[0], x[1], x[2];
  }

  // First pass: decide which cells to keep and check that they are all of one order.
  std::vector<vtkIdType> kept;
  int kept_type = VTK_EMPTY_CELL;
  for (vtkIdType c = 0; c < grid.GetNumberOfCells(); ++c) {
    const int type = grid.GetCellType(c);
    if (type == VTK_TETRA || type == VTK_QUADRATIC_TETRA) {
      if (kept_type != VTK_EMPTY_CELL && kept_type != type)
        throw InputError(file, "cell " + std::to_string(c),
                         "the mesh mixes VTK_TETRA and VTK_QUADRATIC_TETRA; Kerf needs one order");
      kept_type = type;
      kept.push_back(c);
      continue;
    }
    // The dimension comes from a cell of the type alone, not from grid.GetCell(), which would
    // also gather the cell's points and faces from what the file says they are.
    const auto cell = vtkSmartPointer<vtkCell>::Take(vtkGenericCell::InstantiateCell(type));
    if (type != VTK_EMPTY_CELL && cell && cell->GetCellDimension() == 3)
      throw InputError(file, "cell " + std::to_string(c),
                       std::string("cell type ") + vtkCellTypes::GetClassNameFromTypeId(type) +
                           " is not supported; Kerf reads VTK_TETRA and VTK_QUADRATIC_TETRA");
  }

  const int per_tet = kept_type == VTK_QUADRATIC_TETRA ? 10 : 4;
  mesh.tets.resize(static_cast<Eigen::Index>(kept.size()), per_tet);
  vtkNew<vtkIdList> ids;
  for (std::size_t t = 0; t < kept.size(); ++t) {
    grid.GetCellPoints(kept[t], ids);
    if (ids->GetNumberOfIds() != per_tet)
      throw InputError(file, "cell " + std::to_string(kept[t]),
                       "expected " + std::to_string(per_tet) + " points, found " +
                           std::to_string(ids->GetNumberOfIds()));
    for (int a = 0; a < per_tet; ++a) {
      // check_grid_cells() checked the range; clamping keeps an id past 2^31 from wrapping around.
      const vtkIdType id = std::clamp<vtkIdType>(ids->GetId(a), -1, std::numeric_limits<int>::max());
      mesh.tets(static_cast<Eigen::Index>(t), a) = static_cast<int>(id);
    }
  }
  return mesh;
}

} // namespace

TetMesh read_vtk(const std::filesystem::path& file, std::ostream* warnings) {
  const std::string name = file.string();
  const std::string bytes = file_bytes(file, name);

  vtkNew<VtkMessageCatcher> catcher;
  vtkSmartPointer<vtkUnstructuredGrid> grid;
  if (lower_extension(file) == ".vtu") {
    check_vtu_counts(bytes, name);
    vtkNew<vtkXMLUnstructuredGridReader> reader;
    // The XML reader parses with helper objects of its own; these setters hand them our
    // observer, so that their complaints reach us too.
    reader->SetParserErrorObserver(catcher);
    reader->SetReaderErrorObserver(catcher);
    reader->SetFileName(name.c_str());
    grid = run_reader(*reader, *catcher, name, warnings);
  } else {
    // VTK reads the checked part from memory, never the file itself (vtk_legacy_mesh_part.hpp).
    const std::string mesh_part = vtk_legacy_mesh_part(bytes, name, VtkLegacyDataset::unstructured_grid);
    if (mesh_part.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
      throw InputError(name, "file", "a legacy .vtk mesh above 2 GB is not supported; save it as .vtu");
    vtkNew<vtkUnstructuredGridReader> reader;
    reader->ReadFromInputStringOn();
    reader->SetBinaryInputString(mesh_part.data(), static_cast<int>(mesh_part.size()));
    grid = run_reader(*reader, *catcher, name, warnings);
  }

  TetMesh mesh = mesh_from_grid(*grid, name);
  check_tet_mesh(mesh, name, warnings);
  return mesh;
}

} // namespace kerf
