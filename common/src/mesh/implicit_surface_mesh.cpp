#include "kerf/mesh/implicit_surface_mesh.hpp"

#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/mesh/mesh_implicit_domain.hpp"

#include <vector>

namespace kerf {

ImplicitSurfaceSizing implicit_surface_sizing(double h) { return {h, h / 10.0, 30.0}; }

TriangleSurface implicit_surface_mesh(const std::function<double(const Eigen::Vector3d&)>& phi, const Eigen::Vector3d& centre,
                                      double bounding_radius, const ImplicitSurfaceSizing& sizing) {
  // Hardly a bound on the tets: the cell size is the bounding radius and the radius-edge bound 3
  // (looser than the 2 Mesh_3 needs to terminate), so that Mesh_3 refines for the surface only.
  ImplicitMeshSizing mesh_sizing;
  mesh_sizing.cell_size = bounding_radius;
  mesh_sizing.cell_radius_edge_ratio = 3.0;
  mesh_sizing.facet_size = sizing.facet_size;
  mesh_sizing.facet_distance = sizing.facet_distance;
  mesh_sizing.facet_angle = sizing.facet_angle;
  // The optimisers improve tets, which we throw away; the perturber would also move surface vertices.
  ImplicitMeshOptimisation none;
  none.perturb = false;
  none.exude = false;
  const TetMesh mesh = mesh_implicit_domain(phi, centre, bounding_radius, mesh_sizing, none);

  // The boundary of the tets is the surface, oriented outward by boundary_faces.
  const BoundaryFaces boundary = boundary_faces(mesh);
  std::vector<int> index(static_cast<std::size_t>(mesh.num_nodes()), -1);
  std::vector<int> used;
  TriangleSurface surface;
  surface.triangles.resize(boundary.faces.rows(), 3);
  for (Eigen::Index f = 0; f < boundary.faces.rows(); ++f)
    for (int a = 0; a < 3; ++a) {
      int& i = index[static_cast<std::size_t>(boundary.faces(f, a))];
      if (i < 0) {
        i = static_cast<int>(used.size());
        used.push_back(boundary.faces(f, a));
      }
      surface.triangles(f, a) = i;
    }
  surface.vertices.resize(static_cast<Eigen::Index>(used.size()), 3);
  for (std::size_t v = 0; v < used.size(); ++v) surface.vertices.row(static_cast<Eigen::Index>(v)) = mesh.nodes.row(used[v]);
  return surface;
}

} // namespace kerf
