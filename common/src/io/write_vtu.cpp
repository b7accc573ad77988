#include "kerf/io/write_vtu.hpp"

#include "kerf/app/input_error.hpp"
#include "mesh/vtk_error_catcher.hpp"

#include <vtkCellType.h>
#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <fstream>
#include <stdexcept>
#include <system_error>

namespace kerf {
namespace {

/// Creates the folder a file goes into, so that `--out results/run1` works on a fresh checkout.
void create_parent_folder(const std::filesystem::path& file) {
  const std::filesystem::path parent = file.parent_path();
  if (parent.empty()) return;
  std::error_code failure;
  std::filesystem::create_directories(parent, failure);
  if (failure)
    throw InputError(file.string(), "write",
                     "cannot create the folder " + parent.string() + " (" + failure.message() + ")");
}

/// A VTK array holding a #rows by k Eigen matrix, one tuple per row.
vtkSmartPointer<vtkDoubleArray> to_vtk_array(const std::string& name, const Eigen::MatrixXd& values,
                                    Eigen::Index expected_rows, const char* rows_are) {
  if (name.empty()) throw std::invalid_argument("write_vtu: a field has no name");
  if (values.rows() != expected_rows || values.cols() < 1)
    throw std::invalid_argument("write_vtu: field '" + name + "' is " +
                                std::to_string(values.rows()) + " by " +
                                std::to_string(values.cols()) + ", expected " +
                                std::to_string(expected_rows) + " rows (" + rows_are +
                                ") and at least one column");
  auto array = vtkSmartPointer<vtkDoubleArray>::New();
  array->SetName(name.c_str());
  array->SetNumberOfComponents(static_cast<int>(values.cols()));
  array->SetNumberOfTuples(values.rows());
  for (Eigen::Index r = 0; r < values.rows(); ++r)
    for (Eigen::Index c = 0; c < values.cols(); ++c)
      array->SetTypedComponent(r, static_cast<int>(c), values(r, c));
  return array;
}

/// The shortest decimal text that reads back as exactly `value`.
std::string exact_decimal(double value) {
  std::array<char, 32> text{};
  const auto result = std::to_chars(text.data(), text.data() + text.size(), value);
  return std::string(text.data(), result.ptr);
}

/// A file name made safe for an XML attribute value.
std::string xml_escaped(const std::string& text) {
  std::string escaped;
  for (const char c : text) {
    switch (c) {
    case '&': escaped += "&amp;"; break;
    case '<': escaped += "&lt;"; break;
    case '>': escaped += "&gt;"; break;
    case '"': escaped += "&quot;"; break;
    default: escaped += c;
    }
  }
  return escaped;
}

} // namespace

void write_vtu(const std::filesystem::path& file, const TetMesh& mesh,
               const std::vector<PointField>& point_fields,
               const std::vector<CellField>& cell_fields) {
  vtkNew<vtkUnstructuredGrid> grid;

  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(mesh.num_nodes());
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v)
    points->SetPoint(v, mesh.nodes(v, 0), mesh.nodes(v, 1), mesh.nodes(v, 2));
  grid->SetPoints(points);

  // Kerf's Tet10 node order is VTK's, so the connectivity is copied as it is.
  const int cell_type = mesh.nodes_per_tet() == 10 ? VTK_QUADRATIC_TETRA : VTK_TETRA;
  grid->Allocate(mesh.num_tets());
  std::array<vtkIdType, 10> ids{};
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    for (int a = 0; a < mesh.nodes_per_tet(); ++a) ids[a] = mesh.tets(t, a);
    grid->InsertNextCell(cell_type, mesh.nodes_per_tet(), ids.data());
  }

  for (const PointField& field : point_fields)
    grid->GetPointData()->AddArray(
        to_vtk_array(field.name, field.values, mesh.num_nodes(), "one per node"));
  for (const CellField& field : cell_fields)
    grid->GetCellData()->AddArray(
        to_vtk_array(field.name, field.values, mesh.num_tets(), "one per tetrahedron"));

  create_parent_folder(file);
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  // The catcher keeps the writer's first error (and its warnings, which a write ignores).
  vtkNew<VtkMessageCatcher> catcher;
  writer->AddObserver(vtkCommand::ErrorEvent, catcher);
  writer->AddObserver(vtkCommand::WarningEvent, catcher);
  writer->SetFileName(file.string().c_str());
  writer->SetInputData(grid);
  writer->SetDataModeToAppended(); // raw binary after the XML header: small and fast
  writer->EncodeAppendedDataOff();
  writer->SetCompressorTypeToZLib();
  const int written = writer->Write();
  if (!catcher->error.empty()) throw InputError(file.string(), "write", catcher->error);
  if (written != 1) throw InputError(file.string(), "write", "VTK could not write the file");
}

void write_pvd(const std::filesystem::path& file,
               const std::vector<std::pair<double, std::filesystem::path>>& time_and_vtu_file) {
  create_parent_folder(file);
  std::ofstream out(file);
  if (!out) throw InputError(file.string(), "write", "cannot open the file for writing");

  // ParaView resolves the names relative to the .pvd's folder, so we write them that way.
  const std::filesystem::path folder =
      std::filesystem::absolute(file).parent_path().lexically_normal();
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <Collection>\n";
  for (const auto& [time, vtu] : time_and_vtu_file) {
    std::filesystem::path name =
        std::filesystem::absolute(vtu).lexically_normal().lexically_relative(folder);
    if (name.empty()) name = std::filesystem::absolute(vtu); // e.g. another drive on Windows
    out << "    <DataSet timestep=\"" << exact_decimal(time) << "\" group=\"\" part=\"0\" file=\""
        << xml_escaped(name.generic_string()) << "\"/>\n";
  }
  out << "  </Collection>\n"
      << "</VTKFile>\n";
  out.flush();
  if (!out) throw InputError(file.string(), "write", "writing the file failed (disk full?)");
}

} // namespace kerf
