// Private to the kerf library (not under include/): what the mesh and surface readers need of
// a file before they parse it, its extension and its bytes.
#pragma once

#include "kerf/app/input_error.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace kerf {

/// The extension of a file name in lower case, ".vtu" for "Liver.VTU": formats are chosen by
/// extension whatever its case.
inline std::string lower_extension(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

/// The whole content of a file, bytes as they are; InputError naming `name` if the file is
/// missing, a folder, or cannot be read.
inline std::string file_bytes(const std::filesystem::path& file, const std::string& name) {
  if (!std::filesystem::exists(file)) throw InputError(name, "file", "does not exist");
  if (std::filesystem::is_directory(file)) throw InputError(name, "file", "is a folder");
  std::ifstream in(file, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (!in) throw InputError(name, "file", "cannot be read");
  return bytes.str();
}

} // namespace kerf
