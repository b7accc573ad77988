#include "kerf/render/warped_surface.hpp"

#include <vtkDataSetSurfaceFilter.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPlane.h>
#include <vtkPointData.h>
#include <vtkTableBasedClipDataSet.h>
#include <vtkWarpVector.h>

namespace kerf {
namespace {

/// |u| per point, computed before the warp so that it is the file's displacement, not s u.
vtkNew<vtkDoubleArray> displacement_magnitude(vtkDataArray& u) {
  vtkNew<vtkDoubleArray> magnitude;
  magnitude->SetName(displacement_magnitude_name);
  magnitude->SetNumberOfTuples(u.GetNumberOfTuples());
  for (vtkIdType i = 0; i < u.GetNumberOfTuples(); ++i) {
    double value[3];
    u.GetTuple(i, value);
    magnitude->SetValue(i, Eigen::Vector3d(value[0], value[1], value[2]).norm());
  }
  return magnitude;
}

} // namespace

vtkSmartPointer<vtkPolyData> warped_surface(vtkUnstructuredGrid& grid, double scale,
                                            const std::optional<ClipPlane>& clip) {
  // A shallow copy shares the points and arrays with the caller's grid; the new array is added
  // to the copy only, so the caller's grid is not changed.
  vtkNew<vtkUnstructuredGrid> body;
  body->ShallowCopy(&grid);
  vtkDataArray* u = body->GetPointData()->GetArray("displacement");
  body->GetPointData()->AddArray(displacement_magnitude(*u));

  vtkNew<vtkWarpVector> warp;
  warp->SetInputData(body);
  warp->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "displacement");
  warp->SetScaleFactor(scale);

  vtkNew<vtkDataSetSurfaceFilter> surface;
  // The clip cuts the cells it crosses into smaller ones (the table-based clip keeps linear
  // cells linear), so the section is a flat face instead of a staircase of whole tets.
  vtkNew<vtkTableBasedClipDataSet> clipper;
  vtkNew<vtkPlane> plane;
  if (clip) {
    plane->SetOrigin(clip->origin.data());
    plane->SetNormal(clip->normal.data());
    clipper->SetInputConnection(warp->GetOutputPort());
    clipper->SetClipFunction(plane);
    surface->SetInputConnection(clipper->GetOutputPort());
  } else {
    surface->SetInputConnection(warp->GetOutputPort());
  }
  surface->Update();
  vtkSmartPointer<vtkPolyData> result = surface->GetOutput();
  return result;
}

} // namespace kerf
