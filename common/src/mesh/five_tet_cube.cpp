#include "kerf/mesh/five_tet_cube.hpp"

#include <stdexcept>

namespace kerf {

TetMesh make_five_tet_cube(const Eigen::Vector3d& min, const Eigen::Vector3d& max) {
  if ((max - min).minCoeff() <= 0.0) throw std::invalid_argument("make_five_tet_cube: max must exceed min in x, y and z");
  TetMesh mesh;
  mesh.nodes.resize(8, 3);
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d offset(c & 1, (c >> 1) & 1, (c >> 2) & 1);
    mesh.nodes.row(c) = (min.array() + offset.array() * (max - min).array()).transpose();
  }
  // The central tet of the even corners, then the corner tets of 1, 2, 4 and 7, each ordered so
  // that det[x1 - x0, x2 - x0, x3 - x0] > 0 (worked out on the unit cube: +2, +1, +1, +1, +1).
  mesh.tets.resize(5, 4);
  mesh.tets << 0, 5, 3, 6, //
      1, 3, 0, 5,          //
      2, 0, 3, 6,          //
      4, 5, 0, 6,          //
      7, 3, 5, 6;
  return mesh;
}

} // namespace kerf
