/// @file scene_mesh.hpp
/// @brief Build the mesh a scene asks for, and turn its regions into checked node lists.
#pragma once

#include "kerf/fem/dof_map.hpp"
#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/mesh/tet_mesh.hpp"
#include "kerf/scene/scene.hpp"

#include <ostream>
#include <string>
#include <vector>

namespace kerf {

/// The scene's mesh: the box mesher or a file (scaled), promoted to Tet10 when order is 2.
/// File problems are InputErrors naming the mesh file; warnings (reoriented tets) go to `warnings`.
TetMesh make_scene_mesh(const Scene& scene, std::ostream* warnings);

/// The nodes of `region` in `mesh`, as nodes_in_region does, but a node index past the mesh
/// or a region with no node is an InputError naming the scene file and `field`.
std::vector<int> scene_region_nodes(const Scene& scene, const TetMesh& mesh, const NodeRegion& region,
                                    const std::string& field);

/// The scene's Dirichlet conditions as node lists with their displacements: a plain entry is one
/// list, an entry with a rotation gives every node its own displacement (Q - I)(X - c) + t.
/// Regions are checked as scene_region_nodes does.
/// With load factor `lambda` (quasi-static ramps), a rotation turns by lambda times its angle and
/// every translation is scaled by lambda.
/// @throws std::logic_error for a "williams" entry, which prescribes the cut body's enrichments
///         too: a cut body's program asks scene_cut_dirichlet_nodes (scene_xfem_dofs.hpp)
std::vector<DirichletNodes> scene_dirichlet_nodes(const Scene& scene, const TetMesh& mesh, double lambda = 1.0);

/// The conditions of the scene's Dirichlet entry i alone (what scene_dirichlet_nodes gives for it).
std::vector<DirichletNodes> scene_dirichlet_entry_nodes(const Scene& scene, const TetMesh& mesh, std::size_t i, double lambda = 1.0);

/// The prescribed displacements (3#V, zero elsewhere) at load factor lambda: the path along
/// which a quasi-static solve ramps the scene's Dirichlet conditions (turns by their angle).
Eigen::VectorXd scene_prescribed_displacements(const Scene& scene, const TetMesh& mesh, double lambda);

/// The scene's Dirichlet conditions (scene_dirichlet_nodes) and, after them, the nodes that
/// belong to no tet, held fixed with one warning: such a node has no stiffness at all, and
/// holding it changes nothing else.
std::vector<DirichletNodes> scene_held_nodes(const Scene& scene, const TetMesh& mesh, std::ostream* warnings);

/// The DOF map of the scene's Dirichlet conditions, ready to solve with: nodes that belong to no
/// tet are held fixed (with a warning), and a map that leaves a rigid motion of any piece of the
/// body free (a singular stiffness matrix) is an InputError saying how many motions are free.
/// We check before any factorisation, because a factorisation of a singular matrix may well
/// "succeed" with round-off pivots and return garbage.
DofMap scene_dof_map(const Scene& scene, const TetMesh& mesh, std::ostream* warnings);

/// The scene's external loads as nodal forces (3#V): gravity over the volume and each traction
/// spread by area over the boundary faces in its region (kerf::add_uniform_traction). A traction
/// region with no boundary face is an InputError.
Eigen::VectorXd scene_external_loads(const Scene& scene, const TetMesh& mesh, const BoundaryFaces& boundary);

} // namespace kerf
