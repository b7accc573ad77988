#include "kerf/fem/rigid_motion_check.hpp"

#include <Eigen/Dense>
#include <numeric>
#include <vector>

namespace kerf {

namespace {

int find_root(std::vector<int>& parent, int v) {
  while (parent[static_cast<std::size_t>(v)] != v) v = parent[static_cast<std::size_t>(v)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(v)])];
  return v;
}

} // namespace

int count_free_rigid_motions(const TetMesh& mesh, const DofMap& dofs) {
  // Connected pieces by union-find over the nodes of each tet.
  std::vector<int> parent(static_cast<std::size_t>(mesh.num_nodes()));
  std::iota(parent.begin(), parent.end(), 0);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    for (int a = 1; a < mesh.nodes_per_tet(); ++a)
      parent[static_cast<std::size_t>(find_root(parent, mesh.tets(t, a)))] = find_root(parent, mesh.tets(t, 0));

  std::vector<char> used(static_cast<std::size_t>(mesh.num_nodes()), 0);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    for (int a = 0; a < mesh.nodes_per_tet(); ++a) used[static_cast<std::size_t>(mesh.tets(t, a))] = 1;

  // A node in no tet has no stiffness at all: each of its free DOFs is a free motion.
  int free_motions = 0;
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v)
    if (!used[static_cast<std::size_t>(v)])
      for (int p = 0; p < 3; ++p) free_motions += dofs.free_index[static_cast<std::size_t>(3 * v + p)] >= 0;

  std::vector<std::vector<int>> pieces(static_cast<std::size_t>(mesh.num_nodes()));
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v)
    if (used[static_cast<std::size_t>(v)]) pieces[static_cast<std::size_t>(find_root(parent, static_cast<int>(v)))].push_back(static_cast<int>(v));

  for (const auto& piece : pieces) {
    if (piece.empty()) continue;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (int v : piece) centroid += mesh.nodes.row(v).transpose();
    centroid /= static_cast<double>(piece.size());
    // Rows: prescribed DOFs of the piece; columns: the six rigid modes evaluated there.
    std::vector<Eigen::Matrix<double, 1, 6>> rows;
    for (int v : piece) {
      const Eigen::Vector3d r = mesh.nodes.row(v).transpose() - centroid;
      for (int p = 0; p < 3; ++p) {
        if (dofs.free_index[static_cast<std::size_t>(3 * v + p)] >= 0) continue;
        Eigen::Matrix<double, 1, 6> row = Eigen::Matrix<double, 1, 6>::Zero();
        row[p] = 1.0;                                               // translation along p
        const Eigen::Vector3d unit = Eigen::Vector3d::Unit(p);
        for (int k = 0; k < 3; ++k) row[3 + k] = Eigen::Vector3d::Unit(k).cross(r).dot(unit); // rotation about k
        rows.push_back(row);
      }
    }
    if (rows.empty()) {
      free_motions += 6;
      continue;
    }
    Eigen::MatrixXd modes(static_cast<Eigen::Index>(rows.size()), 6);
    for (std::size_t i = 0; i < rows.size(); ++i) modes.row(static_cast<Eigen::Index>(i)) = rows[i];
    // Scale the rotation columns by the piece's size so that both kinds of columns count alike.
    double size = 0.0;
    for (int v : piece) size = std::max(size, (mesh.nodes.row(v).transpose() - centroid).norm());
    if (size > 0.0) modes.rightCols<3>() /= size;
    const Eigen::VectorXd sigma = Eigen::JacobiSVD<Eigen::MatrixXd>(modes).singularValues();
    int rank = 0;
    for (Eigen::Index i = 0; i < sigma.size(); ++i) rank += sigma[i] > 1e-10 * sigma[0];
    free_motions += 6 - rank;
  }
  return free_motions;
}

} // namespace kerf
