#include "kerf/mesh/read_mesh.hpp"

#include "kerf/app/input_error.hpp"
#include "kerf/mesh/read_gmsh.hpp"
#include "kerf/mesh/read_medit.hpp"
#include "kerf/mesh/read_vtk.hpp"
#include "mesh/file_bytes.hpp"

#include <string>

namespace kerf {

TetMesh read_mesh(const std::filesystem::path& file, std::ostream* warnings) {
  const std::string extension = lower_extension(file);
  if (extension == ".msh") return read_gmsh(file, warnings);
  if (extension == ".vtu" || extension == ".vtk") return read_vtk(file, warnings);
  if (extension == ".mesh") return read_medit(file, warnings);
  throw InputError(file.string(), "extension",
                   "'" + file.extension().string() +
                       "' is not a mesh format Kerf reads; use .msh (Gmsh ASCII 1, 2 or 4.1), "
                       ".vtu (VTK XML), .vtk (VTK legacy) or .mesh (Medit ASCII)");
}

} // namespace kerf
