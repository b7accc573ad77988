/// @file scene_cuts.hpp
/// @brief The scene's cuts as triangle surfaces: rectangles as two triangles, surface files read and checked.
#pragma once

#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/mesh/tet_mesh.hpp"
#include "kerf/mesh/triangle_surface.hpp"
#include "kerf/scene/scene.hpp"

#include <ostream>
#include <vector>

namespace kerf {

/// Every entry of the scene's "cuts", in order: a rectangle becomes the two triangles of
/// rectangle_surface() (a bad rectangle is an InputError naming "cuts[i].rectangle"), a surface
/// is read by read_surface() with its scale (a bad file is an InputError naming that file and
/// what is wrong in it; its warnings, such as merged vertices, go to `warnings`).
std::vector<TriangleSurface> scene_cut_surfaces(const Scene& scene, std::ostream* warnings);

/// The pieces of every tet of `mesh` that `cuts` meet (cut_mesh_into_pieces), and one warning
/// for every surface that meets no tet, `FILE: cuts[i]: the surface does not meet the mesh`
/// (surface i of `cuts`, numbered as the scene's cuts, and any the program added after them).
MeshPieces scene_mesh_pieces(const Scene& scene, const TetMesh& mesh, const CutSurfaces& cuts, std::ostream* warnings);

} // namespace kerf
