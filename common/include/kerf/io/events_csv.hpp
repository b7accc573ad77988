/// @file events_csv.hpp
/// @brief A script of mouse and key events for a window, so that an interactive mode can be tested: read from a CSV file.
///
/// The header names the clock the rows are keyed by, then the event: `step,event,x,y,shift`
/// (chapter 7's window, whose timer fires once a step) or `time,event,x,y,shift` (chapter 8's,
/// paced by the wall clock: seconds since the window opened). `event` is press, move or release
/// (the left mouse button) or key_q; x and y are pixels from the window's lower left corner;
/// shift is 0 or 1. Rows come in increasing step or time.
#pragma once

#include <filesystem>
#include <vector>

namespace kerf {

/// What the rows are keyed by: the first column's name.
enum class EventClock { step, time };

/// A window event.
enum class WindowEvent { press, move, release, key_q };

/// One row of the script.
struct ScriptedEvent {
  double at = 0.0;        ///< the step (an integer >= 1) or the time (s, >= 0) it is delivered at
  WindowEvent event = WindowEvent::move;
  int x = 0, y = 0;       ///< pixels from the lower left corner
  bool shift = false;     ///< Shift held
};

/// Reads a script.
/// @throws InputError naming the file and the row's field for a missing header, a field that is
///         not a number, an unknown event, or a key out of order
std::vector<ScriptedEvent> read_events_csv(const std::filesystem::path& file, EventClock clock);

} // namespace kerf
