/// @file camera_view.hpp
/// @brief Where the camera of a picture stands: azimuth and elevation about the body, z up, distance fitted.
#pragma once

#include <vtkRenderer.h>

namespace kerf {

/// The camera on a sphere about the centre of the body's bounding box, looking at the centre,
/// with the z axis up on the screen. Kerf's bodies stand on z = 0 (the beam is clamped there),
/// so z up draws them as they stand. The default is a three-quarter view from the side of
/// x = 0 and y = 0, where the chapters' cuts enter the beam, a little from above.
struct CameraView {
  double azimuth = -135; ///< a (degrees): the camera's direction in the x-y plane, from +x towards +y
  double elevation = 20; ///< e (degrees): the camera's height above the x-y plane, in (-90, 90)
  double zoom = 1;      ///< > 1 comes closer than the fitted distance, < 1 backs off
};

/// Puts the renderer's camera in the direction (cos e cos a, cos e sin a, sin e) from the centre
/// of what the renderer shows, at the distance at which all of it fits in the picture, then
/// zooms by view.zoom. Call it after the body has been added to the renderer.
///
/// @throws std::invalid_argument for |e| >= 90 degrees (z could not be up) or zoom <= 0: the
///         calling program checks what its user gave
void place_camera(vtkRenderer& renderer, const CameraView& view);

} // namespace kerf
