#include "kerf/cut/split_mesh_along_cut.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

namespace kerf {

namespace {

// Throws if tet t has corners strictly on both sides of the plane and its section by the plane
// overlaps the rectangle shrunk by `tolerance` with a positive area. A section that only
// touches the rectangle's boundary (a tet beyond the front, next to the node layer that
// carries it) is allowed: there the material is not cut.
void check_conforms(const TetMesh& mesh, const RectangleCut& cut, const std::vector<double>& d, Eigen::Index t,
                    double tolerance) {
  bool above = false, below = false;
  for (int c = 0; c < 4; ++c) {
    above = above || d[static_cast<std::size_t>(mesh.tets(t, c))] > tolerance;
    below = below || d[static_cast<std::size_t>(mesh.tets(t, c))] < -tolerance;
  }
  if (!above || !below) return;

  // The section: corners on the plane, and the crossing points of edges from above to below.
  std::vector<Eigen::Vector3d> section;
  for (int c = 0; c < 4; ++c) {
    const int v = mesh.tets(t, c);
    if (std::abs(d[static_cast<std::size_t>(v)]) <= tolerance) section.push_back(mesh.nodes.row(v).transpose());
  }
  for (const auto& edge : tet_edge_corners) {
    const int i = mesh.tets(t, edge[0]), j = mesh.tets(t, edge[1]);
    const double di = d[static_cast<std::size_t>(i)], dj = d[static_cast<std::size_t>(j)];
    if ((di > tolerance && dj < -tolerance) || (di < -tolerance && dj > tolerance)) {
      const Eigen::Vector3d xi = mesh.nodes.row(i).transpose(), xj = mesh.nodes.row(j).transpose();
      section.push_back(xi + di / (di - dj) * (xj - xi));
    }
  }
  if (cut.overlap_area(section, tolerance) > 0.0)
    throw std::invalid_argument("split_mesh_along_cut: tet " + std::to_string(t) +
                                " has corners on both sides of the cut's plane and its section by the plane overlaps the "
                                "rectangle: the mesh does not conform to the cut (it needs a node layer on the cut, "
                                "Schoch et al. section 6.1)");
}

} // namespace

SplitMesh split_mesh_along_cut(const TetMesh& mesh, const RectangleCut& cut, double tolerance) {
  if (!(tolerance >= 0.0)) throw std::invalid_argument("split_mesh_along_cut: the tolerance must be >= 0");
  const int nodes_per_tet = mesh.nodes_per_tet();
  if (nodes_per_tet != 4 && nodes_per_tet != 10)
    throw std::invalid_argument("split_mesh_along_cut: the mesh must be Tet4 or Tet10, not " + std::to_string(nodes_per_tet) +
                                " nodes per tet");
  const Eigen::Index num_nodes = mesh.num_nodes();
  const auto node = [](int v) { return static_cast<std::size_t>(v); };

  std::vector<double> d(static_cast<std::size_t>(num_nodes));
  std::vector<char> on_plane(d.size());
  for (Eigen::Index v = 0; v < num_nodes; ++v) {
    d[static_cast<std::size_t>(v)] = cut.signed_distance_to_plane(mesh.nodes.row(v).transpose());
    on_plane[static_cast<std::size_t>(v)] = std::abs(d[static_cast<std::size_t>(v)]) <= tolerance;
  }
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) check_conforms(mesh, cut, d, t, tolerance);

  // The faces in the plane, keyed by sorted corners: how many tets share each, and one of them.
  struct PlaneFace {
    int count = 0;
    Eigen::Index tet = 0;
    int local_face = 0;
  };
  std::map<std::array<int, 3>, PlaneFace> plane_faces;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    for (int a = 0; a < 4; ++a) {
      std::array<int, 3> key;
      bool in_plane_face = true;
      for (int c = 0; c < 3; ++c) {
        key[static_cast<std::size_t>(c)] = mesh.tets(t, tet_outward_face_corners[a][c]);
        in_plane_face = in_plane_face && on_plane[node(key[static_cast<std::size_t>(c)])];
      }
      if (!in_plane_face) continue;
      std::sort(key.begin(), key.end());
      PlaneFace& face = plane_faces[key];
      if (face.count++ == 0) {
        face.tet = t;
        face.local_face = a;
      }
    }

  // A node is on the cut if the interior plane faces around it all lie in the rectangle; one
  // face sticking out of the rectangle puts it on the front, where the body is still whole.
  std::vector<char> touches_inside(d.size(), 0), touches_outside(d.size(), 0);
  for (const auto& [key, face] : plane_faces) {
    if (face.count < 2) continue; // a face on the body's surface separates nothing
    bool inside = true;
    for (int v : key) inside = inside && cut.contains_projection(mesh.nodes.row(v).transpose(), tolerance);
    std::vector<int> face_nodes(key.begin(), key.end());
    if (nodes_per_tet == 10)
      for (int c = 0; c < 3; ++c)
        face_nodes.push_back(mesh.tets(face.tet, tet10_edge_node(tet_outward_face_corners[face.local_face][c],
                                                                 tet_outward_face_corners[face.local_face][(c + 1) % 3])));
    for (int v : face_nodes) (inside ? touches_inside : touches_outside)[node(v)] = 1;
  }

  // A tet with corners strictly on both sides of the plane is material that the cut does not
  // separate (check_conforms allowed it only beyond the rectangle): its nodes on the plane are
  // on the front even where no plane face beyond the rectangle reaches them (a mesh whose node
  // layer follows the cut only up to its front).
  std::vector<char> in_straddling_tet(d.size(), 0);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    bool above = false, below = false;
    for (int c = 0; c < 4; ++c) {
      above = above || d[node(mesh.tets(t, c))] > tolerance;
      below = below || d[node(mesh.tets(t, c))] < -tolerance;
    }
    if (above && below)
      for (int a = 0; a < nodes_per_tet; ++a) in_straddling_tet[node(mesh.tets(t, a))] = 1;
  }

  SplitMesh result;
  std::vector<int> duplicate(d.size(), -1);
  for (Eigen::Index v = 0; v < num_nodes; ++v) {
    const std::size_t i = static_cast<std::size_t>(v);
    if (on_plane[i] && touches_inside[i] && !touches_outside[i] && !in_straddling_tet[i] &&
        cut.contains_projection(mesh.nodes.row(v).transpose(), tolerance)) {
      duplicate[i] = static_cast<int>(num_nodes) + result.duplicated_nodes++;
      result.duplicate_of.push_back(static_cast<int>(v));
    }
  }

  result.mesh.nodes.resize(num_nodes + result.duplicated_nodes, 3);
  result.mesh.nodes.topRows(num_nodes) = mesh.nodes;
  for (int k = 0; k < result.duplicated_nodes; ++k)
    result.mesh.nodes.row(num_nodes + k) = mesh.nodes.row(result.duplicate_of[static_cast<std::size_t>(k)]);
  result.mesh.tets = mesh.tets;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (int c = 0; c < 4; ++c) centroid += 0.25 * mesh.nodes.row(mesh.tets(t, c)).transpose();
    if (!(cut.signed_distance_to_plane(centroid) < 0.0)) continue;
    for (int a = 0; a < nodes_per_tet; ++a) {
      const int copy = duplicate[node(mesh.tets(t, a))];
      if (copy >= 0) result.mesh.tets(t, a) = copy;
    }
  }
  return result;
}

} // namespace kerf
