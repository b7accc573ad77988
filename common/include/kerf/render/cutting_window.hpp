/// @file cutting_window.hpp
/// @brief The interactive window in which the mouse is the blade: Shift + left drag cuts, a drag alone turns the camera, q closes.
///
/// While Shift and the left button are held, the blade's edge stands along the line of sight
/// through the cursor, from 3 cm in front of the skin to a given depth behind it, so the cut
/// follows the cursor across the picture. The blade is put down once the cursor has moved 8
/// pixels from the press, at the distance from the eye of the skin then under the cursor; for the
/// rest of the stroke the hand holds it at that distance, whatever the tissue under it does. A
/// blade re-placed on the skin at every frame would follow the organ as it sags and the wound as
/// it opens (through the wound, to the far wall): motions of centimetres the hand never made,
/// which set the cut's direction before the hand's stroke, and the sheet then refuses that stroke
/// as folding back (cut/cut_sheet.hpp). Elsewhere the camera
/// turns with the mouse. The interactor is used alone, without one of VTK's interactor styles:
/// their module (InteractionStyle) would bring MPI's C bindings into the build with Debian's
/// VTK 9.1 (CMakeLists.txt); the two things a style would do here, turn the camera and close
/// on q, are a few lines of its source.
#pragma once

#include "kerf/cut/blade_path.hpp"
#include "kerf/io/events_csv.hpp"
#include "kerf/render/organ_view.hpp"

#include <functional>
#include <memory>
#include <optional>

class vtkRenderWindowInteractor;

namespace kerf {

/// The window's interactor, its mouse, and the blade the mouse holds.
class CuttingWindow {
public:
  /// @param view        the on-screen OrganView (kept by reference)
  /// @param blade_depth how far behind the picked surface point the edge reaches (m)
  CuttingWindow(OrganView& view, double blade_depth);
  ~CuttingWindow();
  CuttingWindow(const CuttingWindow&) = delete;
  CuttingWindow& operator=(const CuttingWindow&) = delete;

  /// The blade's world edge while Shift + the left button are held and the cursor has moved since
  /// the press, once the stroke has passed over the organ (a pick of what was last drawn), none
  /// otherwise.
  std::optional<BladeEdge> blade();
  /// Whether Shift + the left button are held (cutting, whether over the organ or not).
  bool cutting() const;
  /// Delivers a scripted event as the window system would (events_csv.hpp).
  void deliver(const ScriptedEvent& event);
  /// Runs the window system's loop until q or the window closes, calling `tick` every
  /// `tick_ms` milliseconds.
  void run(int tick_ms, const std::function<void()>& tick);
  /// Ends run()'s loop, as q does.
  void close();
  /// Whether q was pressed.
  bool closed() const;

private:
  struct Data;
  std::unique_ptr<Data> data_;
};

} // namespace kerf
