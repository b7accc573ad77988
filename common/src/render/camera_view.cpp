#include "kerf/render/camera_view.hpp"

#include <vtkCamera.h>

#include <cmath>
#include <stdexcept>

namespace kerf {

void place_camera(vtkRenderer& renderer, const CameraView& view) {
  if (!(std::abs(view.elevation) < 90.0)) throw std::invalid_argument("place_camera: elevation must lie in (-90, 90) degrees");
  if (!(view.zoom > 0.0)) throw std::invalid_argument("place_camera: zoom must be positive");
  const double a = view.azimuth * M_PI / 180.0, e = view.elevation * M_PI / 180.0;
  double bounds[6];
  renderer.ComputeVisiblePropBounds(bounds);
  const double centre[3] = {0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]), 0.5 * (bounds[4] + bounds[5])};

  // Only the direction matters here: ResetCamera keeps it and moves the camera along it to the
  // distance at which the bounding sphere of the props fills the view angle.
  vtkCamera* camera = renderer.GetActiveCamera();
  camera->SetFocalPoint(centre);
  camera->SetPosition(centre[0] + std::cos(e) * std::cos(a), centre[1] + std::cos(e) * std::sin(a), centre[2] + std::sin(e));
  camera->SetViewUp(0.0, 0.0, 1.0);
  renderer.ResetCamera();
  camera->Zoom(view.zoom);
  renderer.ResetCameraClippingRange();
}

} // namespace kerf
