/// @file mesh_implicit_domain.hpp
/// @brief A Tet4 mesh of the region phi(x) < 0 by CGAL's Mesh_3 (Delaunay refinement, then sliver removal).
///
/// Mesh_3 refines a Delaunay triangulation until every surface triangle and every tet meets the
/// size and shape bounds below, with the surface vertices on phi = 0 (found by bisection along
/// Delaunay edges); then it optimises: optional global smoothing (ODT, Lloyd), then the sliver
/// perturber and the exuder, which move vertices or reweight them to remove flat tets. We keep
/// every CGAL header inside the .cpp file: Mesh_3 takes long to compile, and its users need not.
#pragma once

#include "kerf/mesh/tet_mesh.hpp"

#include <Eigen/Core>
#include <cstddef>
#include <functional>

namespace kerf {

/// The bounds Mesh_3 refines to, all lengths in metres (Mesh_criteria_3's names).
struct ImplicitMeshSizing {
  double cell_size = 0.01;             ///< upper bound of a tet's circumradius
  double cell_radius_edge_ratio = 2.0; ///< upper bound of circumradius / shortest edge of a tet
  double facet_size = 0.01;            ///< upper bound of a surface triangle's surface Delaunay ball radius
  double facet_distance = 0.001;       ///< upper bound of the distance of a surface triangle's circumcentre to phi = 0
  double facet_angle = 25.0;           ///< lower bound of a surface triangle's angles (degrees, at most 30 for termination)
  /// Mesh_3 stops (and we throw) once the triangulation holds this many vertices: a size far
  /// too small for the shape then ends in an error instead of filling the memory.
  std::size_t max_vertices = 2'000'000;
};

/// Which of Mesh_3's optimisers run after the refinement. Each is deterministic here: the global
/// smoothers stop after a number of iterations, the perturber and the exuder without a time limit
/// (Mesh_3's default limit, the refinement's own time, would make the output depend on the machine).
struct ImplicitMeshOptimisation {
  int odt_iterations = 0;      ///< iterations of ODT smoothing (0: none)
  int lloyd_iterations = 0;    ///< iterations of Lloyd smoothing (0: none)
  bool perturb = true;         ///< run the sliver perturber
  bool exude = true;           ///< run the sliver exuder
  /// The perturber and exuder aim for no dihedral angle below this (degrees), and on the liver
  /// reach it. At 10k tets a mesh with 12, 15, 18, 20 degrees takes 0.13, 0.16, 0.27, 0.45 s in
  /// all, without either 0.10 s (smallest angle 0.4 degrees): 15 costs little.
  double sliver_bound = 15.0;
};

/// Meshes the region phi(x) < 0 with Tet4, by Mesh_3 from an implicit function.
///
/// The result is the same for the same inputs: CGAL's random generators (the domain's, which
/// shoots the rays for the initial surface points, and the default one) are seeded with 0 first.
/// Tets are positively oriented (det[x1-x0, x2-x0, x3-x0] > 0) and ordered along a Hilbert curve
/// through their centroids (CGAL::hilbert_sort), so that tets and nodes near each other in space
/// are near each other in memory; only the vertices of tets are kept, numbered in the order the
/// tets first use them.
///
/// @param phi             the implicit function, negative inside, positive on the bounding sphere
/// @param centre          the centre of the bounding sphere, a point with phi < 0 (m)
/// @param bounding_radius the radius of a sphere around centre that contains the region (m)
/// @param sizing          the refinement bounds
/// @param optimisation    which optimisers run
/// @throws std::invalid_argument when a size is not positive, phi(centre) >= 0 or phi <= 0 at
///         a sample point of the sphere (Mesh_3 would search for the surface without end);
///         std::runtime_error when Mesh_3 reaches sizing.max_vertices or makes no tets
TetMesh mesh_implicit_domain(const std::function<double(const Eigen::Vector3d&)>& phi, const Eigen::Vector3d& centre,
                             double bounding_radius, const ImplicitMeshSizing& sizing,
                             const ImplicitMeshOptimisation& optimisation = {});

} // namespace kerf
