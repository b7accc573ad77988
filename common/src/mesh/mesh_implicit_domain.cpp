#include "kerf/mesh/mesh_implicit_domain.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Labeled_mesh_domain_3.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Random.h>
#include <CGAL/Spatial_sort_traits_adapter_3.h>
#include <CGAL/hilbert_sort.h>
#include <CGAL/make_mesh_3.h>

#include <Eigen/Geometry>
#include <array>
#include <map>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace kerf {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Domain = CGAL::Labeled_mesh_domain_3<Kernel>;
using Triangulation = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using Complex = CGAL::Mesh_complex_3_in_triangulation_3<Triangulation>;
using Criteria = CGAL::Mesh_criteria_3<Triangulation>;

/// The checks that keep Mesh_3 from running without end: it shoots rays from the centre until
/// enough of them cross the surface, so the centre must be inside and the sphere outside.
void require_enclosed(const std::function<double(const Eigen::Vector3d&)>& phi, const Eigen::Vector3d& centre,
                      double bounding_radius) {
  if (!(phi(centre) < 0.0)) throw std::invalid_argument("mesh_implicit_domain: phi(centre) must be negative (the centre inside)");
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j)
      for (int k = -1; k <= 1; ++k) {
        if (i == 0 && j == 0 && k == 0) continue;
        const Eigen::Vector3d x = centre + bounding_radius * Eigen::Vector3d(i, j, k).normalized();
        if (!(phi(x) > 0.0)) {
          std::ostringstream message;
          message << "mesh_implicit_domain: phi must be positive on the bounding sphere, but phi(" << x.transpose()
                  << ") = " << phi(x) << " (the radius " << bounding_radius << " m is too small)";
          throw std::invalid_argument(message.str());
        }
      }
}

void require_sizes(const ImplicitMeshSizing& s) {
  if (!(s.cell_size > 0.0 && s.facet_size > 0.0 && s.facet_distance > 0.0 && s.cell_radius_edge_ratio > 0.0 &&
        s.facet_angle > 0.0 && s.facet_angle <= 30.0 && s.max_vertices > 0))
    throw std::invalid_argument("mesh_implicit_domain: every size must be positive and the facet angle in (0, 30] degrees");
}

} // namespace

TetMesh mesh_implicit_domain(const std::function<double(const Eigen::Vector3d&)>& phi, const Eigen::Vector3d& centre,
                             double bounding_radius, const ImplicitMeshSizing& sizing,
                             const ImplicitMeshOptimisation& optimisation) {
  require_sizes(sizing);
  if (!(bounding_radius > 0.0)) throw std::invalid_argument("mesh_implicit_domain: the bounding radius must be positive");
  require_enclosed(phi, centre, bounding_radius);

  namespace p = CGAL::parameters;
  const auto function = [&phi](const Point& x) { return phi(Eigen::Vector3d(x.x(), x.y(), x.z())); };
  // The domain's own generator shoots the rays that find the first surface points; the default
  // generator is seeded too, as make_mesh_3 itself does when asked for reproducible runs.
  CGAL::Random domain_random(0);
  CGAL::get_default_random() = CGAL::Random(0);
  // The surface points are found by bisection to 1e-6 of the bounding box: far below any facet
  // distance we ask for, at some 20 bisection steps per point.
  const Domain domain = Domain::create_implicit_mesh_domain(
      function, Kernel::Sphere_3(Point(centre.x(), centre.y(), centre.z()), bounding_radius * bounding_radius),
      p::relative_error_bound = 1e-6, p::p_rng = &domain_random);
  const Criteria criteria(p::facet_angle = sizing.facet_angle, p::facet_size = sizing.facet_size,
                          p::facet_distance = sizing.facet_distance, p::cell_radius_edge_ratio = sizing.cell_radius_edge_ratio,
                          p::cell_size = sizing.cell_size);

  CGAL::Mesh_error_code error = CGAL::CGAL_MESH_3_NO_ERROR;
  const auto odt = optimisation.odt_iterations > 0 ? p::odt(p::max_iteration_number = optimisation.odt_iterations) : p::no_odt();
  const auto lloyd =
      optimisation.lloyd_iterations > 0 ? p::lloyd(p::max_iteration_number = optimisation.lloyd_iterations) : p::no_lloyd();
  const auto perturb = optimisation.perturb ? p::perturb(p::time_limit = 0, p::sliver_bound = optimisation.sliver_bound) : p::no_perturb();
  const auto exude = optimisation.exude ? p::exude(p::time_limit = 0, p::sliver_bound = optimisation.sliver_bound) : p::no_exude();
  const Complex c3t3 = CGAL::make_mesh_3<Complex>(
      domain, criteria, odt, lloyd, perturb, exude,
      p::mesh_3_options(p::maximal_number_of_vertices = sizing.max_vertices, p::pointer_to_error_code = &error));
  if (error != CGAL::CGAL_MESH_3_NO_ERROR) {
    std::ostringstream message;
    message << "mesh_implicit_domain: Mesh_3 stopped: " << CGAL::mesh_error_string(error) << " (" << sizing.max_vertices
            << "); the cell size " << sizing.cell_size << " m is too small for the shape";
    throw std::runtime_error(message.str());
  }
  if (c3t3.number_of_cells_in_complex() == 0)
    throw std::runtime_error("mesh_implicit_domain: Mesh_3 made no tets (the sizes are too large for the shape, or phi < 0 nowhere it looked)");

  // The tets in the order of a Hilbert curve through their centroids, and the vertices numbered
  // in the order those tets first use them (so only used ones are kept). Mesh_3's own cell order
  // follows its memory, scattered over the organ; along the curve, neighbouring tets and nodes
  // get nearby numbers, so that an assembly or a matrix-vector product walks memory in order
  // (the design page, "Assembly into a fixed pattern", measures it). The order is deterministic,
  // as Mesh_3's is.
  std::vector<Triangulation::Cell_handle> cells;
  std::vector<Point> centroids;
  for (auto cell = c3t3.cells_in_complex_begin(); cell != c3t3.cells_in_complex_end(); ++cell) {
    cells.push_back(cell);
    std::array<Point, 4> corners;
    for (int a = 0; a < 4; ++a) corners[static_cast<std::size_t>(a)] = cell->vertex(a)->point().point();
    centroids.push_back(CGAL::centroid(corners[0], corners[1], corners[2], corners[3]));
  }
  std::vector<std::size_t> order(cells.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  using SortTraits = CGAL::Spatial_sort_traits_adapter_3<Kernel, CGAL::Pointer_property_map<Point>::type>;
  CGAL::hilbert_sort(order.begin(), order.end(), SortTraits(CGAL::make_property_map(centroids)));

  std::map<Triangulation::Vertex_handle, int> index;
  TetMesh mesh;
  mesh.tets.resize(static_cast<Eigen::Index>(cells.size()), 4);
  std::vector<Eigen::Vector3d> positions;
  for (std::size_t k = 0; k < order.size(); ++k) {
    const auto& cell = cells[order[k]];
    for (int a = 0; a < 4; ++a) {
      const auto vertex = cell->vertex(a);
      const auto [it, is_new] = index.emplace(vertex, static_cast<int>(positions.size()));
      if (is_new) {
        const auto& x = vertex->point().point(); // a weighted point: its bare point
        positions.emplace_back(CGAL::to_double(x.x()), CGAL::to_double(x.y()), CGAL::to_double(x.z()));
      }
      mesh.tets(static_cast<Eigen::Index>(k), a) = it->second;
    }
  }
  mesh.nodes.resize(static_cast<Eigen::Index>(positions.size()), 3);
  for (std::size_t v = 0; v < positions.size(); ++v) mesh.nodes.row(static_cast<Eigen::Index>(v)) = positions[v].transpose();

  // CGAL's cells are positively oriented already; we check each one anyway and swap corners 1
  // and 2 of any that is not, so that the promise holds whatever the triangulation's convention.
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const Eigen::Vector3d x0 = mesh.nodes.row(mesh.tets(t, 0)), x1 = mesh.nodes.row(mesh.tets(t, 1));
    const Eigen::Vector3d x2 = mesh.nodes.row(mesh.tets(t, 2)), x3 = mesh.nodes.row(mesh.tets(t, 3));
    if ((x1 - x0).dot((x2 - x0).cross(x3 - x0)) < 0.0) std::swap(mesh.tets(t, 1), mesh.tets(t, 2));
  }
  return mesh;
}

} // namespace kerf
