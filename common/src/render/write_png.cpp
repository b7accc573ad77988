#include "kerf/render/write_png.hpp"

#include "kerf/app/input_error.hpp"
#include "mesh/vtk_error_catcher.hpp"

#include <vtkNew.h>
#include <vtkPNGWriter.h>

#include <string>
#include <system_error>

namespace kerf {

void write_png(const std::filesystem::path& file, vtkImageData& image) {
  const std::string name = file.string();
  std::error_code error;
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path(), error);
  if (error) throw InputError(name, "write", "cannot create the folder: " + error.message());
  // The writer reports a file it cannot open as an error event, not an exception.
  vtkNew<VtkMessageCatcher> catcher;
  vtkNew<vtkPNGWriter> writer;
  writer->AddObserver(vtkCommand::ErrorEvent, catcher);
  writer->SetFileName(name.c_str());
  writer->SetInputData(&image);
  writer->Write();
  if (!catcher->error.empty() || writer->GetErrorCode() != 0)
    throw InputError(name, "write", catcher->error.empty() ? "the PNG writer failed" : catcher->error);
}

} // namespace kerf
