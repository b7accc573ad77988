#include "kerf/io/write_front_polyline.hpp"

#include "kerf/app/input_error.hpp"
#include "mesh/vtk_error_catcher.hpp"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataWriter.h>

#include <system_error>
#include <vector>

namespace kerf {

void write_front_polyline(const std::filesystem::path& file, const CrackFronts& fronts) {
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> lines;
  vtkNew<vtkDoubleArray> tangent, normal, length;
  tangent->SetName("tangent");
  tangent->SetNumberOfComponents(3);
  normal->SetName("normal");
  normal->SetNumberOfComponents(3);
  length->SetName("length");
  vtkNew<vtkIntArray> index, closed;
  index->SetName("front");
  closed->SetName("closed");
  for (std::size_t f = 0; f < fronts.polylines.size(); ++f) {
    const FrontPolyline& front = fronts.polylines[f];
    std::vector<vtkIdType> ids;
    double front_length = 0.0;
    for (std::size_t k = 0; k < front.points.size(); ++k) {
      const Eigen::Vector3d& x = front.points[k];
      ids.push_back(points->InsertNextPoint(x.x(), x.y(), x.z()));
      tangent->InsertNextTuple3(front.tangents[k].x(), front.tangents[k].y(), front.tangents[k].z());
      normal->InsertNextTuple3(front.normals[k].x(), front.normals[k].y(), front.normals[k].z());
      if (k > 0) front_length += (x - front.points[k - 1]).norm();
    }
    lines->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
    index->InsertNextValue(static_cast<int>(f));
    closed->InsertNextValue(front.closed ? 1 : 0);
    length->InsertNextValue(front_length);
  }
  vtkNew<vtkPolyData> data;
  data->SetPoints(points);
  data->SetLines(lines);
  data->GetPointData()->AddArray(tangent);
  data->GetPointData()->AddArray(normal);
  data->GetCellData()->AddArray(index);
  data->GetCellData()->AddArray(closed);
  data->GetCellData()->AddArray(length);

  if (const std::filesystem::path parent = file.parent_path(); !parent.empty()) {
    std::error_code failure;
    std::filesystem::create_directories(parent, failure);
    if (failure) throw InputError(file.string(), "write", "cannot create the folder " + parent.string() + " (" + failure.message() + ")");
  }
  vtkNew<vtkXMLPolyDataWriter> writer;
  vtkNew<VtkMessageCatcher> catcher;
  writer->AddObserver(vtkCommand::ErrorEvent, catcher);
  writer->AddObserver(vtkCommand::WarningEvent, catcher);
  writer->SetFileName(file.string().c_str());
  writer->SetInputData(data);
  writer->SetDataModeToAscii(); // a few points: text costs nothing and can be read back by eye
  const int written = writer->Write();
  if (!catcher->error.empty()) throw InputError(file.string(), "write", catcher->error);
  if (written != 1) throw InputError(file.string(), "write", "VTK could not write the file");
}

} // namespace kerf
