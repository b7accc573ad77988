#include "kerf/scene/cut_xfem_loads.hpp"

#include "kerf/app/input_error.hpp"
#include "kerf/fem/assemble_loads.hpp"
#include "kerf/scene/scene_mesh.hpp"

#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace kerf {

namespace {

// The rule over a convex polygon: fan triangles, each with the three-point rule at its edge
// midpoints (weights area / 3, exact to degree 2: a Tet10's shape functions on a face).
template <typename AtPoint>
void for_each_polygon_point(const std::vector<Eigen::Vector3d>& polygon, AtPoint at_point) {
  for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {
    const Eigen::Vector3d& a = polygon[0];
    const Eigen::Vector3d& b = polygon[k];
    const Eigen::Vector3d& c = polygon[k + 1];
    const double area = 0.5 * (b - a).cross(c - a).norm();
    for (const Eigen::Vector3d& x : {Eigen::Vector3d(0.5 * (a + b)), Eigen::Vector3d(0.5 * (b + c)), Eigen::Vector3d(0.5 * (c + a))})
      at_point(x, area / 3.0);
  }
}

} // namespace

Eigen::VectorXd cut_xfem_scene_loads(const Scene& scene, const CutXfemModel& model, const BoundaryFaces& boundary) {
  const TetMesh& mesh = model.mesh();
  const Eigen::Index N = mesh.num_nodes();
  const MeshPieces& pieces = model.pieces();
  // The u rows: chapter 1's loads, with its gravity replaced by the pieces' (the same for an
  // exact rule). The a rows of gravity come with the model's.
  const Eigen::VectorXd gravity = model.gravity_load(scene.material.density, scene.gravity);
  Eigen::VectorXd f = gravity;
  f.head(3 * N) += scene_external_loads(scene, mesh, boundary) - assemble_gravity(mesh, scene.material.density, scene.gravity);

  // The a rows of each traction: over the part of each loaded face that each piece holds.
  for (std::size_t i = 0; i < scene.traction.size(); ++i) {
    const std::string field = "traction[" + std::to_string(i) + "].region";
    std::vector<char> in_region(static_cast<std::size_t>(N), 0);
    for (const int v : scene_region_nodes(scene, mesh, scene.traction[i].region, field)) in_region[static_cast<std::size_t>(v)] = 1;
    const RegionFaces region = faces_in_region(mesh, boundary, in_region);
    if (region.area == 0.0) throw InputError(scene.source.string(), field, "no boundary face has all its nodes in the region");
    const Eigen::Vector3d traction = scene.traction[i].total_force / region.area;
    for (const Eigen::Index face : region.faces) {
      const Eigen::Index t = boundary.tet[static_cast<std::size_t>(face)];
      const int local_face = boundary.local_face[static_cast<std::size_t>(face)];
      const int num_pieces = model.num_integrated_pieces(t);
      const int e = pieces.entry[static_cast<std::size_t>(t)];
      for (int p = 0; p < num_pieces; ++p) {
        std::vector<std::vector<Eigen::Vector3d>> polygons;
        if (num_pieces == 1) {
          std::vector<Eigen::Vector3d> triangle;
          for (int k = 0; k < 4; ++k)
            if (k != local_face) triangle.push_back(mesh.nodes.row(mesh.tets(t, k)).transpose());
          polygons.push_back(triangle);
        } else {
          const TetPieces& tp = pieces.tets[static_cast<std::size_t>(e)];
          for (const PieceBoundaryPolygon& b : tp.pieces[static_cast<std::size_t>(p)].boundary)
            if (b.origin.kind == FaceOrigin::Kind::tet_face && b.origin.index == local_face) polygons.push_back(b.polygon);
        }
        // int N_a t dA on the enrichment rows, and the branch functions' int N_a (F_l - F_l(x_a)) t dA
        // (Paulus eq. 7; the edge-midpoint rule is not exact for them: they are no polynomials).
        for (const std::vector<Eigen::Vector3d>& polygon : polygons)
          for_each_polygon_point(polygon, [&](const Eigen::Vector3d& x, double weight) {
            const Eigen::VectorXd N_x = model.shape_values(t, x);
            for (int a = 0; a < mesh.nodes_per_tet(); ++a) {
              const int node = model.phantom_node(t, p, a);
              if (node >= N) f.segment<3>(3 * node) += weight * N_x[a] * traction;
            }
            for (const auto& [node, value] : model.branch_values_at(t, p, x)) f.segment<3>(3 * node) += weight * value * traction;
          });
      }
    }
  }
  if (!f.allFinite()) throw InputError(scene.source.string(), "traction", "the nodal forces are too large to represent (not finite)");
  return f;
}

} // namespace kerf
