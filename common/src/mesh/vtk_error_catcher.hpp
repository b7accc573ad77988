// Private to the kerf library (not under include/): the observer that the VTK readers
// (mesh/read_vtk.cpp) and the VTU writer (io/write_vtu.cpp) attach to hear VTK's complaints.
// It sits in mesh/, the lower of the two areas, so io may use it without mesh depending on io.
#pragma once

#include <vtkCommand.h>

#include <algorithm>
#include <string>
#include <vector>

namespace kerf {

/// Listens to a VTK object's error and warning events. VTK reports problems this way instead
/// of throwing; with an observer attached, VTK hands the message to us instead of printing it.
class VtkMessageCatcher : public vtkCommand {
public:
  /// VTK's factory function, which vtkNew calls.
  static VtkMessageCatcher* New() { return new VtkMessageCatcher; }

  /// Keeps the first error and every warning, each cut down to one line.
  void Execute(vtkObject* /*caller*/, unsigned long event, void* call_data) override {
    const std::string text = one_line(static_cast<const char*>(call_data));
    if (event == vtkCommand::ErrorEvent && error.empty()) error = text;
    if (event == vtkCommand::WarningEvent) warnings.push_back(text);
  }

  std::string error;                 ///< the first error, empty if none
  std::vector<std::string> warnings; ///< every warning, in order; a caller may ignore them

private:
  /// VTK's messages start with "ClassName (0x1234): " and span lines; we keep the words.
  static std::string one_line(const char* message) {
    std::string text = message ? message : "";
    if (const auto colon = text.find("): "); colon != std::string::npos) text.erase(0, colon + 3);
    std::replace_if(text.begin(), text.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
    const auto last = text.find_last_not_of(' ');
    return last == std::string::npos ? std::string() : text.substr(0, last + 1);
  }
};

} // namespace kerf
