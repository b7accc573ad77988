/// @file read_medit.hpp
/// @brief Read a tetrahedral mesh from a Medit .mesh file (ASCII), as written by TetGen, MMG or CGAL.
#pragma once

#include "kerf/mesh/tet_mesh.hpp"

#include <filesystem>
#include <ostream>

namespace kerf {

/// Reads the `Vertices` and `Tetrahedra` sections of an ASCII Medit mesh.
///
/// The file is free-format: keywords and numbers are separated by any whitespace, `#` starts
/// a comment. It starts with `MeshVersionFormatted`, has `Dimension 3`, and ends with `End`.
/// Every vertex and tet carries a trailing reference number, which we read and drop. Vertex
/// indices count from 1. Triangles, edges, corners, ridges, normals and the like are skipped;
/// hexahedra, prisms and pyramids are rejected. Medit meshes are Tet4 only.
///
/// @param file     the .mesh file
/// @param warnings where warnings go (one line each), or nullptr to stay quiet
/// @return the mesh: #V by 3 nodes, #T by 4 tets
/// @throws InputError `FILE: FIELD: PROBLEM` for a missing, unreadable or malformed file
TetMesh read_medit(const std::filesystem::path& file, std::ostream* warnings);

} // namespace kerf
