#include "kerf/mesh/boundary_faces.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <map>

namespace kerf {

BoundaryFaces boundary_faces(const TetMesh& mesh) {
  // A face seen twice is interior. std::map on the sorted corner triple keeps this simple and
  // deterministic; it runs once per mesh.
  std::map<std::array<int, 3>, std::pair<int, int>> seen; // key -> (tet, local face), tet = -1 once shared
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    for (int a = 0; a < 4; ++a) {
      std::array<int, 3> key;
      for (int c = 0; c < 3; ++c) key[c] = mesh.tets(t, tet_outward_face_corners[a][c]);
      std::sort(key.begin(), key.end());
      auto [it, inserted] = seen.try_emplace(key, static_cast<int>(t), a);
      if (!inserted) it->second.first = -1;
    }

  BoundaryFaces boundary;
  const int nodes_per_face = mesh.order() == 2 ? 6 : 3;
  std::vector<std::array<int, 6>> rows;
  for (const auto& [key, owner] : seen) {
    const auto [t, a] = owner;
    if (t < 0) continue;
    std::array<int, 6> row{};
    for (int c = 0; c < 3; ++c) row[c] = mesh.tets(t, tet_outward_face_corners[a][c]);
    if (nodes_per_face == 6)
      for (int c = 0; c < 3; ++c)
        row[3 + c] = mesh.tets(t, tet10_edge_node(tet_outward_face_corners[a][c], tet_outward_face_corners[a][(c + 1) % 3]));
    rows.push_back(row);
    boundary.tet.push_back(t);
    boundary.local_face.push_back(a);
  }
  boundary.faces.resize(static_cast<Eigen::Index>(rows.size()), nodes_per_face);
  for (std::size_t f = 0; f < rows.size(); ++f)
    for (int c = 0; c < nodes_per_face; ++c) boundary.faces(static_cast<Eigen::Index>(f), c) = rows[f][c];
  return boundary;
}

double face_area(const TetMesh& mesh, const BoundaryFaces& boundary, Eigen::Index f) {
  const Eigen::Vector3d x0 = mesh.nodes.row(boundary.faces(f, 0)).transpose();
  const Eigen::Vector3d x1 = mesh.nodes.row(boundary.faces(f, 1)).transpose();
  const Eigen::Vector3d x2 = mesh.nodes.row(boundary.faces(f, 2)).transpose();
  return 0.5 * (x1 - x0).cross(x2 - x0).norm();
}

TriangleSurface boundary_surface(const TetMesh& mesh) {
  const BoundaryFaces boundary = boundary_faces(mesh);
  std::vector<int> index(static_cast<std::size_t>(mesh.num_nodes()), -1);
  std::vector<int> used;
  TriangleSurface s;
  s.triangles.resize(boundary.faces.rows(), 3);
  for (Eigen::Index f = 0; f < boundary.faces.rows(); ++f)
    for (int a = 0; a < 3; ++a) {
      int& i = index[static_cast<std::size_t>(boundary.faces(f, a))];
      if (i < 0) i = static_cast<int>(used.size()), used.push_back(boundary.faces(f, a));
      s.triangles(f, a) = i;
    }
  s.vertices.resize(static_cast<Eigen::Index>(used.size()), 3);
  for (std::size_t v = 0; v < used.size(); ++v) s.vertices.row(static_cast<Eigen::Index>(v)) = mesh.nodes.row(used[v]);
  return s;
}

} // namespace kerf
