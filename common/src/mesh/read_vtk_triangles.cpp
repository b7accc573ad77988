#include "mesh/surface_parsers.hpp"

#include "kerf/app/input_error.hpp"
#include "mesh/file_bytes.hpp"
#include "mesh/vtk_error_catcher.hpp"
#include "mesh/vtk_legacy_mesh_part.hpp"
#include "mesh/vtk_reader_checks.hpp"
#include "mesh/vtu_counts.hpp"

#include <vtkCellArray.h>
#include <vtkCellType.h>
#include <vtkCellTypes.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataReader.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkUnstructuredGridReader.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <limits>
#include <tuple>
#include <vector>

namespace kerf {
namespace {

/// Gathers the triangles of a VTK dataset's cells, with the messages naming the file.
class TriangleGatherer {
public:
  explicit TriangleGatherer(const std::string& file) : file_(file) {}

  /// Adds the triangles of one cell of VTK type `type` with point ids `ids`; `field` names the
  /// cell in messages ("cell 3", "polygon 3").
  void add_cell(int type, vtkIdList& ids, const std::string& field) {
    const vtkIdType n = ids.GetNumberOfIds();
    const auto id = [&ids](vtkIdType a) { return static_cast<int>(ids.GetId(a)); };
    switch (type) {
      case VTK_TRIANGLE:
      case VTK_QUAD:
      case VTK_POLYGON: {
        const vtkIdType needed = type == VTK_TRIANGLE ? 3 : type == VTK_QUAD ? 4 : -1;
        if ((needed > 0 && n != needed) || n < 3)
          throw InputError(file_, field, std::string(vtkCellTypes::GetClassNameFromTypeId(type)) + " with " +
                                             std::to_string(n) + " points");
        // A polygon becomes a fan around its first point, which keeps its orientation.
        for (vtkIdType a = 1; a + 1 < n; ++a) triangles_.push_back({id(0), id(a), id(a + 1)});
        return;
      }
      case VTK_TRIANGLE_STRIP:
        if (n < 3) throw InputError(file_, field, "a triangle strip with " + std::to_string(n) + " points");
        // Every other triangle of a strip runs backwards; swapping its first two points
        // orients all of them as the first.
        for (vtkIdType a = 0; a + 2 < n; ++a)
          triangles_.push_back(a % 2 == 0 ? std::array{id(a), id(a + 1), id(a + 2)}
                                          : std::array{id(a + 1), id(a), id(a + 2)});
        return;
      case VTK_EMPTY_CELL:
      case VTK_VERTEX:
      case VTK_POLY_VERTEX:
      case VTK_LINE:
      case VTK_POLY_LINE:
        return; // points and curves, a drawing's marks on the surface: nothing to cut with
      default:
        throw InputError(file_, field,
                         std::string("cell type ") + vtkCellTypes::GetClassNameFromTypeId(type) +
                             " is not supported; a cut surface is made of VTK_TRIANGLE, VTK_QUAD, "
                             "VTK_POLYGON or VTK_TRIANGLE_STRIP cells");
    }
  }

  /// The surface of the gathered triangles on the points of `points`.
  TriangleSurface surface(vtkPoints* points) const {
    if (!points || points->GetNumberOfPoints() == 0) throw InputError(file_, "points", "the file has no points");
    if (points->GetNumberOfPoints() > std::numeric_limits<int>::max())
      throw InputError(file_, "points", "more points than Kerf's 32-bit indices can number");
    std::vector<std::array<double, 3>> vertices(static_cast<std::size_t>(points->GetNumberOfPoints()));
    for (vtkIdType v = 0; v < points->GetNumberOfPoints(); ++v) points->GetPoint(v, vertices[static_cast<std::size_t>(v)].data());
    return surface_from_lists(vertices, triangles_);
  }

private:
  const std::string& file_;
  std::vector<std::array<int, 3>> triangles_;
};

/// The triangles of an unstructured grid.
TriangleSurface grid_triangles(vtkUnstructuredGrid& grid, const std::string& file) {
  check_grid_cells(grid, file);
  TriangleGatherer gatherer(file);
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < grid.GetNumberOfCells(); ++c) {
    grid.GetCellPoints(c, ids);
    gatherer.add_cell(grid.GetCellType(c), *ids, "cell " + std::to_string(c));
  }
  return gatherer.surface(grid.GetPoints());
}

/// The triangles of polydata: its polygons and strips (its vertices and lines are skipped).
TriangleSurface polydata_triangles(vtkPolyData& polydata, const std::string& file) {
  const vtkIdType num_points = polydata.GetNumberOfPoints();
  check_cell_array(polydata.GetVerts(), num_points, file, "vertex cell");
  check_cell_array(polydata.GetLines(), num_points, file, "line");
  check_cell_array(polydata.GetPolys(), num_points, file, "polygon");
  check_cell_array(polydata.GetStrips(), num_points, file, "strip");
  TriangleGatherer gatherer(file);
  vtkNew<vtkIdList> ids;
  for (const auto& [cells, type, name] : {std::tuple{polydata.GetPolys(), VTK_POLYGON, "polygon"},
                                          std::tuple{polydata.GetStrips(), VTK_TRIANGLE_STRIP, "strip"}}) {
    if (!cells) continue;
    for (vtkIdType c = 0; c < cells->GetNumberOfCells(); ++c) {
      cells->GetCellAtId(c, ids);
      gatherer.add_cell(type, *ids, std::string(name) + " " + std::to_string(c));
    }
  }
  return gatherer.surface(polydata.GetPoints());
}

/// True if a checked legacy file's DATASET line (the fourth) names polydata.
bool is_legacy_polydata(const std::string& text) {
  std::size_t line_start = 0;
  for (int line = 0; line < 3; ++line) line_start = text.find('\n', line_start) + 1;
  std::string dataset = text.substr(line_start, text.find('\n', line_start) - line_start);
  std::transform(dataset.begin(), dataset.end(), dataset.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return dataset.find("POLYDATA") != std::string::npos;
}

/// Runs an XML reader, hands its helper parsers our observer, and returns its output.
template <class Reader>
vtkSmartPointer<vtkDataObject> run_xml_reader(const std::string& name, VtkMessageCatcher& catcher, std::ostream* warnings) {
  vtkNew<Reader> reader;
  // The XML reader parses with helper objects of its own; these setters hand them our
  // observer, so that their complaints reach us too.
  reader->SetParserErrorObserver(&catcher);
  reader->SetReaderErrorObserver(&catcher);
  reader->SetFileName(name.c_str());
  return run_vtk_reader(*reader, catcher, name, warnings);
}

/// Runs a legacy reader on the checked part of a file, from memory.
template <class Reader>
vtkSmartPointer<vtkDataObject> run_legacy_reader(const std::string& part, const std::string& name,
                                                 VtkMessageCatcher& catcher, std::ostream* warnings) {
  vtkNew<Reader> reader;
  reader->ReadFromInputStringOn();
  reader->SetBinaryInputString(part.data(), static_cast<int>(part.size()));
  return run_vtk_reader(*reader, catcher, name, warnings);
}

} // namespace

TriangleSurface read_vtk_triangles(const std::filesystem::path& file, std::ostream* warnings) {
  const std::string name = file.string();
  const std::string bytes = file_bytes(file, name);
  const std::string extension = lower_extension(file);
  vtkNew<VtkMessageCatcher> catcher;
  vtkSmartPointer<vtkDataObject> data;
  if (extension == ".vtp" || extension == ".vtu") {
    check_vtu_counts(bytes, name);
    data = extension == ".vtp" ? run_xml_reader<vtkXMLPolyDataReader>(name, *catcher, warnings)
                               : run_xml_reader<vtkXMLUnstructuredGridReader>(name, *catcher, warnings);
  } else {
    // VTK reads the checked part from memory, never the file itself (vtk_legacy_mesh_part.hpp).
    const std::string part = vtk_legacy_mesh_part(bytes, name, VtkLegacyDataset::unstructured_grid_or_polydata);
    if (part.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
      throw InputError(name, "file", "a legacy .vtk surface above 2 GB is not supported; save it as .vtp");
    data = is_legacy_polydata(part) ? run_legacy_reader<vtkPolyDataReader>(part, name, *catcher, warnings)
                                    : run_legacy_reader<vtkUnstructuredGridReader>(part, name, *catcher, warnings);
  }
  if (auto* polydata = vtkPolyData::SafeDownCast(data)) return polydata_triangles(*polydata, name);
  if (auto* grid = vtkUnstructuredGrid::SafeDownCast(data)) return grid_triangles(*grid, name);
  throw InputError(name, "VTK reader", "the file holds neither polydata nor an unstructured grid");
}

} // namespace kerf
