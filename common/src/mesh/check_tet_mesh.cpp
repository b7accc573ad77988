#include "kerf/mesh/check_tet_mesh.hpp"

#include "kerf/app/input_error.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <utility>

namespace kerf {

double signed_tet_volume(const TetMesh& mesh, Eigen::Index t) {
  const Eigen::Vector3d x0 = mesh.nodes.row(mesh.tets(t, 0)).transpose();
  Eigen::Matrix3d edges;
  for (int c = 0; c < 3; ++c)
    edges.col(c) = mesh.nodes.row(mesh.tets(t, c + 1)).transpose() - x0;
  return edges.determinant() / 6.0;
}

std::vector<int> nodes_without_tets(const TetMesh& mesh) {
  std::vector<char> used(static_cast<std::size_t>(mesh.num_nodes()), 0);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    for (int a = 0; a < mesh.nodes_per_tet(); ++a) used[static_cast<std::size_t>(mesh.tets(t, a))] = 1;
  std::vector<int> unused;
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v)
    if (!used[static_cast<std::size_t>(v)]) unused.push_back(static_cast<int>(v));
  return unused;
}

int check_tet_mesh(TetMesh& mesh, const std::string& file, std::ostream* warnings) {
  if (mesh.num_nodes() == 0) throw InputError(file, "nodes", "the mesh has no nodes");
  if (mesh.num_tets() == 0) throw InputError(file, "elements", "the mesh has no tetrahedra");
  if (mesh.nodes_per_tet() != 4 && mesh.nodes_per_tet() != 10)
    throw InputError(file, "elements", "expected 4 or 10 nodes per tetrahedron");
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v)
    if (!mesh.nodes.row(v).allFinite())
      throw InputError(file, "node " + std::to_string(v), "coordinate is not a finite number");
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    for (int a = 0; a < mesh.nodes_per_tet(); ++a)
      if (mesh.tets(t, a) < 0 || mesh.tets(t, a) >= mesh.num_nodes())
        throw InputError(file, "element " + std::to_string(t),
                         "node index " + std::to_string(mesh.tets(t, a)) + " is outside [0, " +
                             std::to_string(mesh.num_nodes()) + ")");

  // The flatness threshold is relative to the element's own size, so that a mesh in
  // millimetres and the same mesh in metres are judged alike.
  int reoriented = 0;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    double mean_edge = 0.0;
    for (const auto& e : tet_edge_corners)
      mean_edge += (mesh.nodes.row(mesh.tets(t, e[0])) - mesh.nodes.row(mesh.tets(t, e[1]))).norm();
    mean_edge /= 6.0;
    const double volume = signed_tet_volume(mesh, t);
    if (!(std::abs(volume) > 1e-12 * mean_edge * mean_edge * mean_edge))
      throw InputError(file, "element " + std::to_string(t),
                       "tetrahedron has zero volume (its corners are coplanar)");
    if (volume < 0.0) {
      // Swapping corners 1 and 2 flips the orientation; for Tet10 the mid-edge nodes follow:
      // edge (0,1) <-> (0,2) is node 4 <-> 6 and edge (1,3) <-> (2,3) is node 8 <-> 9.
      std::swap(mesh.tets(t, 1), mesh.tets(t, 2));
      if (mesh.nodes_per_tet() == 10) {
        std::swap(mesh.tets(t, 4), mesh.tets(t, 6));
        std::swap(mesh.tets(t, 8), mesh.tets(t, 9));
      }
      ++reoriented;
    }
  }
  if (reoriented > 0 && warnings)
    *warnings << "warning: " << file << ": " << reoriented
              << " inverted tetrahedra were reoriented (corners 1 and 2 swapped)\n";
  return reoriented;
}

} // namespace kerf
