/// @file check_tet_mesh.hpp
/// @brief Validate a mesh read from a file: finite coordinates, indices in range, no flat tets, positive orientation, straight Tet10.
#pragma once

#include "kerf/mesh/tet_mesh.hpp"

#include <ostream>
#include <string>
#include <vector>

namespace kerf {

/// Checks a mesh that came from outside and repairs what can be repaired safely.
///
/// - every coordinate must be finite, every index in [0, #V): otherwise InputError;
/// - a tet whose volume is below 1e-12 times the volume of a cube with the mean edge length
///   is rejected by index (InputError: it would make the stiffness matrix singular);
/// - a tet with negative volume is reoriented (corners 1 and 2 swapped, and for Tet10 the
///   mid-edge nodes that go with them); each one is counted and one warning line is written.
///
/// Tet10 are then checked for straight edges, because the library assumes them everywhere
/// outside the stiffness (loads from the corner volume, face areas from the corners, the affine
/// maps of the point locator and the L2 error, quadrature rules exact only for straight edges):
/// - a mid-edge node more than 1e-6 of its edge's length off the edge's midpoint is moved onto
///   it, and one warning line says how many tets were curved, the largest offset and the first
///   tet (Gmsh's meshes of curved geometry come curved by default);
/// - a mid-edge node more than 0.25 of the edge length off (the quarter-point limit, past which
///   the element folds; wrongly numbered mid-edge nodes are about 0.5 off), a mid-edge node that
///   is a corner elsewhere or the mid-edge node of two different edges, and a tet whose given
///   map has det J <= 0 at a point of the degree-2 or degree-4 rule are rejected by index
///   (InputError).
///
/// A mesh built in code can be put through this check too, with a name for the messages.
///
/// @param mesh     the mesh, changed in place when tets are reoriented or straightened
/// @param file     the file name used in messages
/// @param warnings where the one-line warnings go (may be nullptr to stay quiet)
/// @return the number of tets that were reoriented
int check_tet_mesh(TetMesh& mesh, const std::string& file, std::ostream* warnings);

/// The nodes that belong to no tet (stray geometry points in a Gmsh file, say). They carry no
/// stiffness, so a solver must hold them fixed; chapters do so with a warning.
std::vector<int> nodes_without_tets(const TetMesh& mesh);

/// Signed volume of the tet spanned by the first four nodes of row `t`: det[x1-x0, x2-x0, x3-x0] / 6.
double signed_tet_volume(const TetMesh& mesh, Eigen::Index t);

} // namespace kerf
