#include "kerf/mesh/box_mesh.hpp"

#include <stdexcept>

namespace kerf {

TetMesh make_box_mesh(const Eigen::Vector3d& min, const Eigen::Vector3d& max, const Eigen::Vector3i& cells) {
  if ((cells.array() < 1).any()) throw std::invalid_argument("make_box_mesh: every cell count must be at least 1");
  if ((max - min).minCoeff() <= 0.0) throw std::invalid_argument("make_box_mesh: max must exceed min in x, y and z");
  const int nx = cells[0], ny = cells[1], nz = cells[2];
  const auto node_index = [&](int i, int j, int k) { return i + (nx + 1) * (j + (ny + 1) * k); };

  TetMesh mesh;
  mesh.nodes.resize(static_cast<Eigen::Index>(nx + 1) * (ny + 1) * (nz + 1), 3);
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        const Eigen::Vector3d t(double(i) / nx, double(j) / ny, double(k) / nz);
        mesh.nodes.row(node_index(i, j, k)) = (min.array() + t.array() * (max - min).array()).transpose();
      }

  // The six tets of the unit cube around the diagonal 0 -> 7, where corner c has the
  // offsets (c & 1, (c >> 1) & 1, (c >> 2) & 1). Each tet walks 0 -> one axis -> two axes -> 7;
  // the three even permutations of the axes give positive orientation directly and the three
  // odd ones are listed with their middle corners swapped so that every det is positive.
  constexpr int kuhn_tets[6][4] = {{0, 1, 3, 7}, {0, 3, 2, 7}, {0, 2, 6, 7},
                                   {0, 6, 4, 7}, {0, 4, 5, 7}, {0, 5, 1, 7}};
  mesh.tets.resize(6 * static_cast<Eigen::Index>(nx) * ny * nz, 4);
  Eigen::Index t = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (const auto& tet : kuhn_tets) {
          for (int a = 0; a < 4; ++a) {
            const int c = tet[a];
            mesh.tets(t, a) = node_index(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1));
          }
          ++t;
        }
  return mesh;
}

} // namespace kerf
