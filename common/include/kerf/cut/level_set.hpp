/// @file level_set.hpp
/// @brief Nodal level set values Lambda_i of a plane cut (Schoch et al. eq. 72), snapped to zero near the plane.
#pragma once

#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/mesh/tet_mesh.hpp"

#include <Eigen/Core>

namespace kerf {

/// The level set of a cut sampled at the nodes, Lambda_i = Lambda(x_i) (Schoch et al., eq. 72),
/// with the sign of each node.
///
/// Values with |Lambda_i| <= snap_tolerance are stored as exactly 0. A node that lies on the
/// cut plane up to round-off (the plane z = 0.1 through a layer of nodes of a box mesh, say)
/// would otherwise get a sign from the last bits of a subtraction, and the tets around it would
/// be classified as cut or uncut at random. After snapping, "the cut passes through this node"
/// is a fact that the classification (tet_cut_classification.hpp) handles as its own case.
///
/// The default tolerance is far below Schoch et al.'s "minimum distance between an element node
/// and a cut, until which we define the element not to be cut" (section 5.2): it only removes
/// round-off. Ill-conditioning from tiny pieces is handled by the volume-fraction rule in
/// clip_tet.hpp; pass a larger tolerance to reproduce the paper's minimum-distance rule.
struct LevelSet {
  Eigen::VectorXd lambda;   ///< #V signed distances to the cut plane (m), snapped values exactly 0
  Eigen::VectorXi sign;     ///< #V signs: +1 above, -1 below, 0 on the plane
  double snap_tolerance = 0.0; ///< the tolerance that was used (m)
};

/// 1e-9 times the diagonal of the mesh's bounding box: the same relative tolerance the scene
/// uses for node regions, and far above the round-off of coordinates of order the diagonal.
double default_snap_tolerance(const TetMesh& mesh);

/// The level set of the plane of `cut` at every node of `mesh` (all #V nodes, also the
/// mid-edge nodes of a Tet10 mesh), snapped with default_snap_tolerance(mesh).
LevelSet make_level_set(const TetMesh& mesh, const RectangleCut& cut);

/// As above with an explicit snap tolerance.
/// @param mesh           the mesh, #V nodes
/// @param cut            the cut; its plane defines Lambda (see RectangleCut for why the plane)
/// @param snap_tolerance values with |Lambda_i| <= this (m) become exactly 0; must be >= 0
/// @return #V values and signs
LevelSet make_level_set(const TetMesh& mesh, const RectangleCut& cut, double snap_tolerance);

/// +1, -1 or 0: the sign of an already snapped level set value.
inline int level_set_sign(double lambda) { return (lambda > 0.0) - (lambda < 0.0); }

} // namespace kerf
