/// @file read_gmsh.hpp
/// @brief Read a tetrahedral mesh from a Gmsh .msh file (ASCII, format 1, 2.x or 4.1).
#pragma once

#include "kerf/mesh/tet_mesh.hpp"

#include <filesystem>
#include <ostream>

namespace kerf {

/// Reads the tetrahedra of a Gmsh ASCII mesh file, in any of the three layouts still met in
/// the wild: format 1 (`$NOD`/`$ELM`, e.g. SOFA's liver), format 2.x (`$MeshFormat 2.2`,
/// `$Nodes`, `$Elements`) and format 4.1 (nodes and elements grouped in entity blocks).
///
/// - 4-node tetrahedra (Gmsh type 4) become Tet4, 10-node tetrahedra (type 11) Tet10; a file
///   must hold one of the two, not both. Gmsh numbers the last two mid-edge nodes of a Tet10
///   on edges (3,2) and (3,1), VTK and Kerf on (1,3) and (2,3), so those two are swapped.
/// - Points, lines, triangles and quadrangles (boundary and physical-group elements) are
///   skipped without a word; hexahedra, prisms, pyramids and higher-order tets are rejected.
/// - Node tags may be any positive integers, with gaps: they are renumbered 0, 1, 2, ... in
///   the order the nodes appear in the file.
/// - Binary files and format 4.0 are rejected with a message saying how to re-save the file.
///
/// The mesh then goes through check_tet_mesh(), which rejects NaN coordinates and flat tets,
/// reorients inverted ones, and for Tet10 straightens curved edges (Gmsh's default for curved
/// geometry) and rejects misnumbered or folded elements.
///
/// @param file     the .msh file
/// @param warnings where warnings go (one line each), or nullptr to stay quiet
/// @return the mesh: #V by 3 nodes, #T by 4 or #T by 10 tets in Kerf's (VTK's) node order
/// @throws InputError `FILE: FIELD: PROBLEM` for a missing, unreadable or malformed file
TetMesh read_gmsh(const std::filesystem::path& file, std::ostream* warnings);

} // namespace kerf
