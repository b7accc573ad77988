#include "kerf/render/triangle_surface_polydata.hpp"

#include "kerf/render/warped_surface.hpp"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkIntArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>

#include <Eigen/Geometry>
#include <stdexcept>

namespace kerf {

vtkSmartPointer<vtkPolyData> triangle_surface_polydata(const TriangleSurface& surface, Shading shading,
                                                       const Eigen::VectorXd& displacement_magnitude, int label) {
  const Eigen::Index V = surface.num_vertices(), F = surface.num_triangles();
  if (displacement_magnitude.size() != 0 && displacement_magnitude.size() != V)
    throw std::invalid_argument("triangle_surface_polydata: one |u| per vertex, or none");
  const auto magnitude = [&](Eigen::Index v) { return displacement_magnitude.size() == 0 ? 0.0 : displacement_magnitude(v); };
  const auto corner = [&](Eigen::Index f, int a) -> Eigen::Vector3d { return surface.vertices.row(surface.triangles(f, a)).transpose(); };
  // (x1 - x0) x (x2 - x0): twice the area times the outward unit normal.
  const auto area_normal = [&](Eigen::Index f) -> Eigen::Vector3d {
    return (corner(f, 1) - corner(f, 0)).cross(corner(f, 2) - corner(f, 0));
  };

  auto points = vtkSmartPointer<vtkPoints>::New();
  auto normals = vtkSmartPointer<vtkDoubleArray>::New();
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  auto u = vtkSmartPointer<vtkDoubleArray>::New();
  u->SetName(displacement_magnitude_name);
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  if (shading == Shading::smooth) {
    // Summing the unnormalised face normals weights each face by its area.
    Eigen::MatrixX3d vertex_normals = Eigen::MatrixX3d::Zero(V, 3);
    for (Eigen::Index f = 0; f < F; ++f)
      for (int a = 0; a < 3; ++a) vertex_normals.row(surface.triangles(f, a)) += area_normal(f).transpose();
    for (Eigen::Index v = 0; v < V; ++v) {
      points->InsertNextPoint(surface.vertices(v, 0), surface.vertices(v, 1), surface.vertices(v, 2));
      const Eigen::Vector3d n = vertex_normals.row(v).normalized();
      normals->InsertNextTuple3(n.x(), n.y(), n.z());
      u->InsertNextValue(magnitude(v));
    }
    for (Eigen::Index f = 0; f < F; ++f) {
      const vtkIdType ids[3] = {surface.triangles(f, 0), surface.triangles(f, 1), surface.triangles(f, 2)};
      cells->InsertNextCell(3, ids);
    }
  } else {
    for (Eigen::Index f = 0; f < F; ++f) {
      const Eigen::Vector3d n = area_normal(f).normalized();
      vtkIdType ids[3];
      for (int a = 0; a < 3; ++a) {
        const Eigen::Vector3d x = corner(f, a);
        ids[a] = points->InsertNextPoint(x.x(), x.y(), x.z());
        normals->InsertNextTuple3(n.x(), n.y(), n.z());
        u->InsertNextValue(magnitude(surface.triangles(f, a)));
      }
      cells->InsertNextCell(3, ids);
    }
  }
  auto labels = vtkSmartPointer<vtkIntArray>::New();
  labels->SetName(surface_label_name);
  for (Eigen::Index f = 0; f < F; ++f) labels->InsertNextValue(label);

  auto polydata = vtkSmartPointer<vtkPolyData>::New();
  polydata->SetPoints(points);
  polydata->SetPolys(cells);
  polydata->GetPointData()->SetNormals(normals);
  polydata->GetPointData()->AddArray(u);
  polydata->GetCellData()->AddArray(labels);
  return polydata;
}

} // namespace kerf
