#include "kerf/fem/rigid_motion_check.hpp"

#include "kerf/mesh/check_tet_mesh.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace kerf {

namespace {

/// Union-find over the nodes: the representative of v's piece, halving the path on the way.
int find_root(std::vector<int>& parent, int v) {
  while (parent[static_cast<std::size_t>(v)] != v) {
    int& up = parent[static_cast<std::size_t>(v)];
    up = parent[static_cast<std::size_t>(up)];
    v = up;
  }
  return v;
}

/// Whether node v belongs to some tet.
std::vector<char> nodes_in_tets(const TetMesh& mesh) {
  std::vector<char> used(static_cast<std::size_t>(mesh.num_nodes()), 0);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    for (int a = 0; a < mesh.nodes_per_tet(); ++a) used[static_cast<std::size_t>(mesh.tets(t, a))] = 1;
  return used;
}

/// How many of the six rigid motions of the piece with these nodes its prescribed DOFs leave free.
int free_motions_of_piece(const TetMesh& mesh, const DofMap& dofs, const std::vector<int>& piece) {
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
      row[p] = 1.0;                                                                   // translation along p
      for (int k = 0; k < 3; ++k) row[3 + k] = Eigen::Vector3d::Unit(k).cross(r)[p]; // rotation about axis k
      rows.push_back(row);
    }
  }
  if (rows.empty()) return 6;
  Eigen::MatrixXd modes(static_cast<Eigen::Index>(rows.size()), 6);
  for (std::size_t i = 0; i < rows.size(); ++i) modes.row(static_cast<Eigen::Index>(i)) = rows[i];
  // Scale the rotation columns by the piece's size so that both kinds of columns count alike.
  double size = 0.0;
  for (int v : piece) size = std::max(size, (mesh.nodes.row(v).transpose() - centroid).norm());
  if (size > 0.0) modes.rightCols<3>() /= size;
  const Eigen::VectorXd sigma = Eigen::JacobiSVD<Eigen::MatrixXd>(modes).singularValues();
  int rank = 0;
  for (Eigen::Index i = 0; i < sigma.size(); ++i) rank += sigma[i] > 1e-10 * sigma[0];
  return 6 - rank;
}

} // namespace

std::vector<UnheldPiece> unheld_pieces(const TetMesh& mesh, const DofMap& dofs, const std::vector<double>& tet_volume,
                                       const std::vector<Eigen::Vector3d>& tet_point) {
  // Connected pieces by union-find over the nodes of each tet.
  std::vector<int> parent(static_cast<std::size_t>(mesh.num_nodes()));
  std::iota(parent.begin(), parent.end(), 0);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    for (int a = 1; a < mesh.nodes_per_tet(); ++a)
      parent[static_cast<std::size_t>(find_root(parent, mesh.tets(t, a)))] = find_root(parent, mesh.tets(t, 0));

  const std::vector<char> used = nodes_in_tets(mesh);
  std::vector<std::vector<int>> nodes_of_piece(static_cast<std::size_t>(mesh.num_nodes()));
  for (int v = 0; v < static_cast<int>(mesh.num_nodes()); ++v)
    if (used[static_cast<std::size_t>(v)]) nodes_of_piece[static_cast<std::size_t>(find_root(parent, v))].push_back(v);

  // Each piece's volume and the centroid of its largest tet, for the report.
  std::vector<UnheldPiece> report(static_cast<std::size_t>(mesh.num_nodes()));
  std::vector<double> largest(static_cast<std::size_t>(mesh.num_nodes()), -1.0);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const auto k = static_cast<std::size_t>(t);
    const auto root = static_cast<std::size_t>(find_root(parent, mesh.tets(t, 0)));
    const double volume = tet_volume.empty() ? std::abs(signed_tet_volume(mesh, t)) : tet_volume[k];
    report[root].volume += volume;
    if (volume > largest[root]) {
      largest[root] = volume;
      report[root].point = tet_point.empty() ? Eigen::Vector3d(tet_corners(mesh, t).colwise().mean().transpose()) : tet_point[k];
    }
  }

  std::vector<UnheldPiece> unheld;
  for (std::size_t root = 0; root < nodes_of_piece.size(); ++root) {
    if (nodes_of_piece[root].empty()) continue;
    report[root].free_motions = free_motions_of_piece(mesh, dofs, nodes_of_piece[root]);
    if (report[root].free_motions > 0) unheld.push_back(report[root]);
  }
  return unheld;
}

int count_free_rigid_motions(const TetMesh& mesh, const DofMap& dofs) {
  int free_motions = 0;
  // A node in no tet has no stiffness at all: each of its free DOFs is a free motion.
  const std::vector<char> used = nodes_in_tets(mesh);
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v)
    if (!used[static_cast<std::size_t>(v)])
      for (int p = 0; p < 3; ++p) free_motions += dofs.free_index[static_cast<std::size_t>(3 * v + p)] >= 0;
  for (const UnheldPiece& piece : unheld_pieces(mesh, dofs)) free_motions += piece.free_motions;
  return free_motions;
}

} // namespace kerf
