#include "kerf/cut/level_set.hpp"

#include <cmath>
#include <stdexcept>

namespace kerf {

double default_snap_tolerance(const TetMesh& mesh) {
  if (mesh.num_nodes() == 0) return 0.0;
  const Eigen::Vector3d diagonal = (mesh.nodes.colwise().maxCoeff() - mesh.nodes.colwise().minCoeff()).transpose();
  return 1e-9 * diagonal.norm();
}

LevelSet make_level_set(const TetMesh& mesh, const RectangleCut& cut) {
  return make_level_set(mesh, cut, default_snap_tolerance(mesh));
}

LevelSet make_level_set(const TetMesh& mesh, const RectangleCut& cut, double snap_tolerance) {
  if (!(snap_tolerance >= 0.0)) throw std::invalid_argument("make_level_set: snap_tolerance must be >= 0");
  LevelSet level_set;
  level_set.snap_tolerance = snap_tolerance;
  level_set.lambda.resize(mesh.num_nodes());
  level_set.sign.resize(mesh.num_nodes());
  for (Eigen::Index i = 0; i < mesh.num_nodes(); ++i) {
    double lambda = cut.signed_distance_to_plane(mesh.nodes.row(i).transpose());
    if (std::abs(lambda) <= snap_tolerance) lambda = 0.0; // also turns -0.0 into +0.0
    level_set.lambda[i] = lambda;
    level_set.sign[i] = level_set_sign(lambda);
  }
  return level_set;
}

} // namespace kerf
