/// @file surface_image.hpp
/// @brief Draw a surface off-screen into an image, coloured by |u| or by a cell array, with a colour bar.
#pragma once

#include "kerf/render/camera_view.hpp"

#include <vtkImageData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <array>
#include <string>

class vtkRenderWindow;

namespace kerf {

/// What the picture looks like.
struct PictureSettings {
  /// "displacement": |u| per point on a blue-to-red scale; or the name of a cell array of the
  /// surface (for the XFEM view: "piece", -1 for a tet drawn whole, 0, 1, ... for the pieces
  /// of a cut tet), one colour per value when its values are whole numbers from -1 to 10
  /// (-1 light grey, 0 blue, 1 orange, ...: a value keeps its colour from picture to
  /// picture), a scale otherwise.
  std::string colour_by = "displacement";
  CameraView camera;  ///< where the camera stands
  int width = 1200;   ///< pixels
  int height = 900;   ///< pixels
};

/// The background colour of every picture (RGB): white, as the book's pages are.
inline constexpr std::array<unsigned char, 3> picture_background = {255, 255, 255};

/// Draws the surface with VTK's OpenGL renderer into an off-screen window of the given size,
/// lit by a light at the camera, with a colour bar at the right edge, and reads the pixels back.
///
/// VTK 9.1 as Debian builds it draws through X, also off-screen: without a display (the
/// environment variable DISPLAY) it would abort, so we refuse to start instead; headless
/// machines run the drawing under `xvfb-run -a`.
///
/// @param surface  the surface (warped_surface.hpp), with the array settings.colour_by names
/// @param settings colour, camera and size
/// @return an RGB image of width by height pixels, row 0 at the bottom (VTK's order)
/// @throws InputError `environment: DISPLAY: ...` without a display
/// @throws std::invalid_argument for a colour array the surface does not have or a size below
///         1 pixel: the calling program checks what its user gave (require_cell_array in
///         piece_mesh.hpp)
vtkSmartPointer<vtkImageData> render_surface_image(vtkPolyData& surface, const PictureSettings& settings);

/// Draws `window` and reads its pixels back: RGB, row 0 at the bottom (VTK's order), a copy that
/// outlives the window. What render_surface_image and chapter 7's OrganView both end with.
vtkSmartPointer<vtkImageData> window_picture(vtkRenderWindow& window);

} // namespace kerf
