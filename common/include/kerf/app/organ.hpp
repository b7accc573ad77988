/// @file organ.hpp
/// @brief The organ a cutting program works on: its reference mesh and what every model of its cut shares.
///
/// Chapters 7 and 8 cut the scene's mesh (the liver by default, made by Mesh_3 with the size
/// --tets asks for) again and again; what depends on the mesh alone is found once here: its
/// boundary, the face adjacency the cut's pieces are glued by, a point locator of the reference
/// mesh (for the blade's pull-back and the probes), the held nodes, and two lengths.
#pragma once

#include "kerf/fem/dof_map.hpp"
#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/mesh/point_locator.hpp"
#include "kerf/mesh/tet_mesh.hpp"
#include "kerf/mesh/tet_neighbours.hpp"
#include "kerf/mesh/triangle_surface.hpp"
#include "kerf/scene/scene.hpp"

#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace kerf {

/// The reference mesh and its shared structures. Not copied nor moved: the locator refers to
/// the mesh.
struct Organ {
  /// The scene's mesh (`tets`, if given, overrides the liver's size; refused for a mesh read
  /// from a file) and what is shared. Warnings (held regions with no node, a mesh's repairs) go
  /// to `warnings`.
  /// @throws InputError `command line: --tets` for a size out of range or a mesh read from a file
  Organ(Scene& scene, std::optional<int> tets, std::ostream* warnings);
  Organ(const Organ&) = delete;
  Organ& operator=(const Organ&) = delete;

  TetMesh mesh;
  BoundaryFaces boundary;
  std::shared_ptr<const TetNeighbours> neighbours;
  std::unique_ptr<PointLocator> locator;
  std::vector<DirichletNodes> held; ///< the scene's held nodes
  double volume = 0.0;              ///< sum of |det J| / 6 (m^3)
  double mean_edge = 0.0;           ///< the mean length of the tets' edges (m)
  std::string summary;              ///< one line: nodes, tets, how the mesh was made and in what time, its quality
};

/// The refusals every program that cuts with a blade shares (chapters 7 and 8): a fixed cut (the
/// blade makes the cut), an integrator other than Newmark's (`step` says whose step it is), a
/// density that is not positive, and, unless the mouse is the blade (`interactive`), a scene
/// without a "blade" field.
/// @throws InputError naming the scene file and the field
void require_blade_scene(const Scene& scene, const std::string& program, const std::string& step, bool interactive);

/// The surface a picture of the organ shows: the scene's render.surface (read_surface; SOFA's
/// liver comes with a smooth one), for the built-in liver a fine mesh of its implicit surface
/// (Mesh_3's surface mesher, triangles of render.visual_size, several times finer than the tets'
/// boundary), or else the mesh's own boundary.
TriangleSurface scene_visual_surface(const Scene& scene, const TetMesh& mesh);

} // namespace kerf
