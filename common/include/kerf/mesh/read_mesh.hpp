/// @file read_mesh.hpp
/// @brief Read a tetrahedral mesh from a file, choosing the reader by the file's extension.
#pragma once

#include "kerf/mesh/tet_mesh.hpp"

#include <filesystem>
#include <ostream>

namespace kerf {

/// Reads a mesh file with the reader its extension names (case does not matter):
/// `.msh` read_gmsh(), `.vtu` and `.vtk` read_vtk(), `.mesh` read_medit().
///
/// @param file     the mesh file
/// @param warnings where warnings go (one line each), or nullptr to stay quiet
/// @return the checked mesh (see check_tet_mesh())
/// @throws InputError for an unsupported extension (the message lists the supported ones),
///         and whatever the chosen reader throws
TetMesh read_mesh(const std::filesystem::path& file, std::ostream* warnings);

} // namespace kerf
