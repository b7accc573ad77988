#include "kerf/mesh/check_tet_mesh.hpp"

#include "kerf/app/input_error.hpp"
#include "kerf/fem/tet_quadrature.hpp"
#include "kerf/fem/tet_shape_functions.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>
#include <vector>

namespace kerf {

namespace {

/// A mid-edge node closer than this to its edge's midpoint, relative to the edge length, counts
/// as on it. Seven printed digits (single precision) round a coordinate by up to 5e-8 of its
/// size, so such files pass for elements larger than about a tenth of their distance from the
/// origin, while any curvature a mesher puts on purpose (percents of the edge) is caught. Below
/// that size the round-off is straightened too: harmless, and the warning says how little moved.
constexpr double straight_edge_tolerance = 1e-6;

/// A mid-edge node farther than this from its edge's midpoint, relative to the edge length, is
/// refused rather than straightened. A quarter is the quarter-point limit: a node moved along
/// its edge to a quarter of the length makes det J vanish at the corner, and beyond it negative.
/// A node numbered for another edge of the tet sits about half an edge length away or more.
constexpr double misplaced_node_offset = 0.25;

/// The distance of mid-edge node 4+e of tet t from the midpoint of its edge, over the edge's length.
double mid_edge_offset(const TetMesh& mesh, Eigen::Index t, int e) {
  const Eigen::RowVector3d xi = mesh.nodes.row(mesh.tets(t, tet_edge_corners[e][0]));
  const Eigen::RowVector3d xj = mesh.nodes.row(mesh.tets(t, tet_edge_corners[e][1]));
  return (mesh.nodes.row(mesh.tets(t, 4 + e)) - 0.5 * (xi + xj)).norm() / (xj - xi).norm();
}

/// "mid-edge node 12 (local node 5, on the edge between corners 1 and 2)", for messages.
std::string describe_mid_edge_node(const TetMesh& mesh, Eigen::Index t, int e) {
  return "mid-edge node " + std::to_string(mesh.tets(t, 4 + e)) + " (local node " + std::to_string(4 + e) +
         ", on the edge between corners " + std::to_string(tet_edge_corners[e][0]) + " and " +
         std::to_string(tet_edge_corners[e][1]) + ")";
}

/// The reference shape gradients of the Tet10 at every point of a quadrature rule.
std::vector<Eigen::Matrix<double, 10, 3>> tet10_gradients_at(const TetQuadratureRule& rule) {
  std::vector<Eigen::Matrix<double, 10, 3>> gradients;
  for (const Eigen::Vector3d& xi : rule.points) gradients.push_back(tet10_shape_gradients(xi));
  return gradients;
}

/// Refuses a node that is a corner of one tet and a mid-edge node of another: a Tet10 mesh's
/// corners and mid-edge nodes are different nodes, so the numbering is wrong.
void refuse_corners_in_mid_edge_slots(const TetMesh& mesh, const std::string& file) {
  std::vector<Eigen::Index> tet_with_corner(static_cast<std::size_t>(mesh.num_nodes()), -1);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    for (int a = 0; a < 4; ++a) tet_with_corner[static_cast<std::size_t>(mesh.tets(t, a))] = t;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    for (int e = 0; e < 6; ++e)
      if (const Eigen::Index other = tet_with_corner[static_cast<std::size_t>(mesh.tets(t, 4 + e))]; other >= 0)
        throw InputError(file, "element " + std::to_string(t),
                         describe_mid_edge_node(mesh, t, e) + " is a corner of element " + std::to_string(other) +
                             ": the nodes are numbered wrongly");
}

/// Refuses a mid-edge node more than misplaced_node_offset from its edge's midpoint.
void refuse_misplaced_mid_edge_nodes(const TetMesh& mesh, const std::string& file) {
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    for (int e = 0; e < 6; ++e)
      if (const double offset = mid_edge_offset(mesh, t, e); !(offset <= misplaced_node_offset)) {
        std::ostringstream problem;
        problem << describe_mid_edge_node(mesh, t, e) << " is " << offset
                << " of the edge length away from the edge's midpoint (at most " << misplaced_node_offset
                << " is taken for a curved edge): the mid-edge nodes are in the wrong order, or the edge is bent too far";
        throw InputError(file, "element " + std::to_string(t), problem.str());
      }
}

/// Refuses a tet whose own (possibly curved) map has det J <= 0 at a point of the rules the
/// library integrates with: degree 2 (stiffness) and degree 4 (mass). Such a tet folds over
/// itself; straightening it would hide a broken mesh rather than undo a small curvature.
void refuse_folded_tets(const TetMesh& mesh, const std::string& file) {
  for (const int degree : {2, 4}) {
    const TetQuadratureRule rule = tet_quadrature_rule(degree);
    const std::vector<Eigen::Matrix<double, 10, 3>> gradients = tet10_gradients_at(rule);
    for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
      Eigen::Matrix<double, 10, 3> X;
      for (int a = 0; a < 10; ++a) X.row(a) = mesh.nodes.row(mesh.tets(t, a));
      for (std::size_t q = 0; q < gradients.size(); ++q)
        if (const double det_J = (X.transpose() * gradients[q]).determinant(); !(det_J > 0.0)) {
          std::ostringstream problem;
          problem << "det J = " << det_J << " <= 0 at point " << q << " of the degree-" << degree
                  << " quadrature rule: the curved tetrahedron folds over itself";
          throw InputError(file, "element " + std::to_string(t), problem.str());
        }
    }
  }
}

/// Moves every mid-edge node more than straight_edge_tolerance off its edge's midpoint onto it,
/// with one warning line. A node still off afterwards was moved onto two different midpoints:
/// it is the mid-edge node of different edges in different tets, and is refused.
void straighten_mid_edge_nodes(TetMesh& mesh, const std::string& file, std::ostream* warnings) {
  int straightened = 0;
  Eigen::Index first_straightened = -1;
  double largest_offset = 0.0;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    bool curved = false;
    for (int e = 0; e < 6; ++e) {
      const double offset = mid_edge_offset(mesh, t, e);
      if (offset <= straight_edge_tolerance) continue;
      curved = true;
      largest_offset = std::max(largest_offset, offset);
      mesh.nodes.row(mesh.tets(t, 4 + e)) = 0.5 * (mesh.nodes.row(mesh.tets(t, tet_edge_corners[e][0])) +
                                                   mesh.nodes.row(mesh.tets(t, tet_edge_corners[e][1])));
    }
    if (!curved) continue;
    if (first_straightened < 0) first_straightened = t;
    ++straightened;
  }
  if (straightened == 0) return;

  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    for (int e = 0; e < 6; ++e)
      if (!(mid_edge_offset(mesh, t, e) <= straight_edge_tolerance))
        throw InputError(file, "element " + std::to_string(t),
                         describe_mid_edge_node(mesh, t, e) +
                             " is the mid-edge node of another edge in another tetrahedron: the mid-edge nodes are numbered wrongly");
  if (warnings)
    *warnings << "warning: " << file << ": " << straightened << " Tet10 elements had curved edges (the first is element "
              << first_straightened << ", mid-edge nodes up to " << largest_offset
              << " of the edge length off the midpoint); their mid-edge nodes were moved onto the midpoints, "
                 "since Kerf's Tet10 are straight-edged\n";
}

/// The Tet10 checks, on a mesh whose corners are already positively oriented.
///
/// Kerf's Tet10 are straight-edged everywhere outside the stiffness: gravity from the corner
/// volume, face areas from the corners, the affine map of the point locator and of the L2
/// error, and the 4-point rule is exact only for straight edges. So a curved Tet10 (Gmsh puts
/// the mid-edge nodes of curved geometry on the surface by default) is straightened, with a
/// warning, and what cannot be a curved edge is refused first. Once straight, det J = 6 V > 0
/// everywhere, the corner volumes having been checked already.
void check_tet10_mid_edge_nodes(TetMesh& mesh, const std::string& file, std::ostream* warnings) {
  refuse_corners_in_mid_edge_slots(mesh, file);
  refuse_misplaced_mid_edge_nodes(mesh, file);
  refuse_folded_tets(mesh, file);
  straighten_mid_edge_nodes(mesh, file, warnings);
}

} // namespace

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
  if (mesh.nodes_per_tet() == 10) check_tet10_mid_edge_nodes(mesh, file, warnings);
  return reoriented;
}

} // namespace kerf
