/// @file organ_view.hpp
/// @brief Chapter 7's picture: the organ's visual surface and the walls of its cut, smooth-shaded, from a camera that stays put; off-screen for the frames, in a window for the interactive mode.
///
/// render_surface_image (surface_image.hpp) makes a window per picture and fits the camera to
/// what it shows. A film needs the opposite: one window for all frames, so a frame costs a
/// render and a read-back and not a new OpenGL context, and one camera, fitted once to the organ
/// at rest, so the organ moves in the picture rather than the picture around the organ.
#pragma once

#include "kerf/cut/blade_path.hpp"
#include "kerf/mesh/triangle_surface.hpp"
#include "kerf/render/camera_view.hpp"
#include "kerf/scene/scene.hpp"

#include <vtkSmartPointer.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

class vtkImageData;
class vtkRenderWindow;
class vtkRenderer;

namespace kerf {

/// How the organ is drawn.
struct OrganViewSettings {
  int width = 960, height = 720; ///< pixels
  CameraView camera;             ///< fitted to the organ at rest, then fixed
  bool on_screen = false;        ///< a window on the display (the interactive mode) instead of off-screen
};

/// The settings of the scene's "render" field: its size and camera.
OrganViewSettings organ_view_settings(const RenderSpec& render, bool on_screen);

/// One render window showing two surfaces: the organ's skin (liver red) and the cut's walls
/// (the paler red of cut tissue), both smooth-shaded; and the blade, when given, in steel.
class OrganView {
public:
  /// @param at_rest  the skin before anything moves: the camera is fitted to it once
  /// @param settings size, camera, on or off screen
  /// @throws InputError `environment: DISPLAY: ...` without a display (VTK 9.1 draws through X)
  OrganView(const TriangleSurface& at_rest, const OrganViewSettings& settings);
  ~OrganView();
  OrganView(const OrganView&) = delete;
  OrganView& operator=(const OrganView&) = delete;
  /// Replaces what is shown (the camera stays): the skin, the walls of the cut, and the blade's
  /// edge if given, drawn as a thin steel bar along it (1.5 mm square).
  void show(const TriangleSurface& skin, const TriangleSurface& cut_walls, const std::optional<BladeEdge>& blade = std::nullopt);
  /// Text in the picture's upper left corner, one or more lines (empty: none): the interactive
  /// window's instructions, step time and real-time factor.
  void caption(const std::string& text);
  /// Draws, and returns the picture: RGB, row 0 at the bottom (VTK's order).
  vtkSmartPointer<vtkImageData> picture();
  /// Draws and writes the picture as a PNG.
  void write_png(const std::filesystem::path& file);
  /// The window and its renderer, for the interactive mode's interactor.
  vtkRenderWindow& window();
  vtkRenderer& renderer();

private:
  struct Data;
  std::unique_ptr<Data> data_;
};

} // namespace kerf
