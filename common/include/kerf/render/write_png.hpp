/// @file write_png.hpp
/// @brief Save an RGB image as a PNG file.
#pragma once

#include <vtkImageData.h>

#include <filesystem>

namespace kerf {

/// Writes the image (surface_image.hpp) as a PNG file; the parent folder is created when missing.
/// @throws InputError `FILE: write: PROBLEM` when the file cannot be written
void write_png(const std::filesystem::path& file, vtkImageData& image);

} // namespace kerf
