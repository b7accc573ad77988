// The liver of our own (mesh/liver_shape.hpp, mesh/liver_mesh.hpp): the implicit shape has the
// size and smoothness we asked for, and Mesh_3's Tet4 mesh of it has the shape's volume and
// extent, about the number of tets asked for, positive tets, a closed connected surface of a
// sphere's topology and no slivers, the same on every call; sizes it cannot make are refused
// in one line.
#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/mesh/check_tet_mesh.hpp"
#include "kerf/mesh/liver_mesh.hpp"
#include "kerf/mesh/liver_shape.hpp"
#include "kerf/mesh/mesh_implicit_domain.hpp"
#include "kerf/mesh/tet_quality.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <functional>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace {

// The tests mesh with 3000 tets: large enough that both lobes are several tets thick, small
// enough that Mesh_3 takes well under a second.
constexpr int test_tets = 3000;

const kerf::TetMesh& liver_mesh() {
  static const kerf::TetMesh mesh = kerf::make_liver_mesh(test_tets);
  return mesh;
}

// What a fine grid says of the shape, without any mesh: the midpoints of 1 mm cubes with phi < 0.
struct GridShape {
  double cell = 0.001;
  double volume = 0.0;
  Eigen::AlignedBox3d extent; // the box of the inside midpoints, grown by half a cell
  bool all_inside_bounding_box = true;
};

// The midpoint count's error is a sum of +- (part of a cube) over the ~10^5 cubes the surface
// crosses, which cancel: of order sqrt(10^5) cubes, 3e-7 m^3, 0.02 % of the volume. The extent
// is exact to half a cell, 0.5 mm.
const GridShape& grid_shape() {
  static const GridShape grid = [] {
    GridShape g;
    // A box larger than liver_bounding_box() by 5 mm, so that the test would see a shape
    // sticking out of it.
    const Eigen::AlignedBox3d search(kerf::liver_bounding_box().min() - Eigen::Vector3d::Constant(0.005),
                                     kerf::liver_bounding_box().max() + Eigen::Vector3d::Constant(0.005));
    const Eigen::Vector3i cells = (search.sizes() / g.cell).array().ceil().cast<int>();
    long inside = 0;
    for (int k = 0; k < cells.z(); ++k)
      for (int j = 0; j < cells.y(); ++j)
        for (int i = 0; i < cells.x(); ++i) {
          const Eigen::Vector3d x = search.min() + g.cell * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5);
          if (kerf::liver_phi(x) >= 0.0) continue;
          ++inside;
          g.extent.extend(x);
          if (!kerf::liver_bounding_box().contains(x)) g.all_inside_bounding_box = false;
        }
    g.volume = static_cast<double>(inside) * std::pow(g.cell, 3);
    g.extent.min().array() -= 0.5 * g.cell;
    g.extent.max().array() += 0.5 * g.cell;
    return g;
  }();
  return grid;
}

double mesh_volume(const kerf::TetMesh& mesh) {
  double volume = 0.0;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) volume += kerf::signed_tet_volume(mesh, t);
  return volume;
}

// The second difference (phi(x + h d) - 2 phi(x) + phi(x - h d)) / h^2: bounded as h -> 0 where
// phi is smooth, growing like 1/h across a kink (a min or max of two functions).
double second_difference(const Eigen::Vector3d& x, const Eigen::Vector3d& d, double h) {
  return (kerf::liver_phi(x + h * d) - 2.0 * kerf::liver_phi(x) + kerf::liver_phi(x - h * d)) / (h * h);
}

} // namespace

TEST_CASE("the liver shape is about 0.20 x 0.15 x 0.10 m, inside its bounding box and sphere, and its volume is liver_volume()") {
  const GridShape& g = grid_shape();
  // Measured: x -0.1001..0.0999, y -0.0752..0.0759, z -0.0398..0.0603 (0.200 x 0.151 x 0.100 m).
  const Eigen::Vector3d size = g.extent.sizes();
  CHECK(size.x() == kerf_test::relative(0.20, 0.05));
  CHECK(size.y() == kerf_test::relative(0.15, 0.05));
  CHECK(size.z() == kerf_test::relative(0.10, 0.05));
  CHECK(g.extent.center().norm() < 0.015); // centred near the origin (measured 10 mm, z up from the floor)
  // liver_bounding_box() contains the shape (by its construction, and here every inside grid point)
  // and is within 13 mm of it on every side (measured 11.7 mm at the left lobe's tip, 8 mm on top):
  // loose by the most the lobes' blend could add, which it adds only where the lobes meet.
  CHECK(g.all_inside_bounding_box);
  CHECK((g.extent.min() - kerf::liver_bounding_box().min()).maxCoeff() < 0.013);
  CHECK((kerf::liver_bounding_box().max() - g.extent.max()).maxCoeff() < 0.013);
  CHECK((kerf::liver_bounding_box().min() - g.extent.min()).maxCoeff() < 0.5 * g.cell);
  CHECK((g.extent.max() - kerf::liver_bounding_box().max()).maxCoeff() < 0.5 * g.cell);
  // The mesher starts inside and needs phi > 0 on the sphere: every box corner is on it or inside it.
  CHECK(kerf::liver_phi(kerf::liver_centre()) < 0.0);
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d x = g.extent.corner(static_cast<Eigen::AlignedBox3d::CornerType>(corner));
    CHECK((x - kerf::liver_centre()).norm() < kerf::liver_bounding_radius());
  }
  // The library's 2 mm count against this 1 mm one: measured 0.09 % apart; its doc promises 0.5 %.
  CHECK(kerf::liver_volume() == kerf_test::relative(g.volume, 0.005));
}

TEST_CASE("the liver's phi is smooth where the lobes blend and where the floor meets the dome") {
  // Where the two arguments of a blend are equal, a plain min or max would put a kink, and there
  // the second difference grows like 1/h (tenfold when h shrinks tenfold). We find those places on
  // two lines by bisection and ask that the second difference converges instead. Measured: the
  // two step sizes agree to 1e-5 relative (second differences of 6 to 31 per metre); with
  // std::min for the lobes' blend this test fails (checked once by hand).
  const auto right = [](const Eigen::Vector3d& x) { return kerf::liver_lobe_phi(kerf::liver_right_lobe, x); };
  const auto left = [](const Eigen::Vector3d& x) { return kerf::liver_lobe_phi(kerf::liver_left_lobe, x); };
  const auto lobes = [&](const Eigen::Vector3d& x) { return kerf::smooth_minimum(right(x), left(x), kerf::liver_lobe_blend); };
  struct Crest {
    Eigen::Vector3d start, direction;
    double s_end;
    std::function<double(const Eigen::Vector3d&)> g; // the two arguments' difference: zero on the crest
  };
  const std::array<Crest, 2> crests{{
      // from the left lobe's centre towards the right one's: phi_right = phi_left between them
      {{-0.05, 0.01, 0.0}, {1, 0, 0}, 0.075, [&](const Eigen::Vector3d& x) { return right(x) - left(x); }},
      // outwards 5 mm above the floor: the lobes' phi meets the floor's z_floor - z near the rim
      {{0.03, 0.0, -0.035}, {1, 0, 0}, 0.09,
       [&](const Eigen::Vector3d& x) { return lobes(x) - (kerf::liver_floor_height - x.z()); }},
  }};
  for (const Crest& c : crests) {
    CAPTURE(c.start.transpose());
    double a = 0.0, b = c.s_end;
    REQUIRE(c.g(c.start) * c.g(c.start + b * c.direction) < 0.0);
    for (int step = 0; step < 60; ++step) {
      const double m = 0.5 * (a + b);
      (c.g(c.start + a * c.direction) * c.g(c.start + m * c.direction) <= 0.0 ? b : a) = m;
    }
    const Eigen::Vector3d crest = c.start + a * c.direction;
    for (const Eigen::Vector3d& d : {Eigen::Vector3d(c.direction), Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0, 1, 0)}) {
      CAPTURE(d.transpose());
      const double coarse = second_difference(crest, d, 1e-4), fine = second_difference(crest, d, 1e-5);
      CHECK(std::abs(fine - coarse) <= 1e-3 * (1.0 + std::abs(coarse)));
    }
  }
}

TEST_CASE("make_liver_mesh: about the tets asked for, all positive, only used nodes") {
  const kerf::TetMesh& mesh = liver_mesh();
  REQUIRE(mesh.nodes_per_tet() == 4);
  // The promise is +-30 % from 2k to 100k; measured 3028 tets (672 nodes) for 3000.
  CHECK(mesh.num_tets() > 0.7 * test_tets);
  CHECK(mesh.num_tets() < 1.3 * test_tets);
  Eigen::Index non_positive = 0;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    if (!(kerf::signed_tet_volume(mesh, t) > 0.0)) ++non_positive;
  CHECK(non_positive == 0);
  CHECK(kerf::nodes_without_tets(mesh).empty());
  CHECK(mesh.tets.minCoeff() == 0);
  CHECK(mesh.tets.maxCoeff() == mesh.num_nodes() - 1);
}

TEST_CASE("the liver mesh has the shape's volume and extent, to its surface's approximation") {
  const kerf::TetMesh& mesh = liver_mesh();
  const GridShape& g = grid_shape();
  const kerf::BoundaryFaces boundary = kerf::boundary_faces(mesh);
  double area = 0.0;
  for (Eigen::Index f = 0; f < boundary.faces.rows(); ++f) area += kerf::face_area(mesh, boundary, f);
  const double facet_distance = kerf::liver_mesh_sizing(test_tets).facet_distance;
  // The surface vertices lie on phi = 0 and the triangles are chords of a mostly convex surface,
  // so the mesh is smaller than the shape. A chord triangle is at most facet_distance from the
  // surface (at its circumcentre, Mesh_3's bound) and, like a chord of a cap, half that on average:
  // the deficit is at most area x facet_distance / 2 (3.6 % here). Measured: 2.15 % short.
  const double volume = mesh_volume(mesh);
  CHECK(volume < g.volume);
  CHECK(g.volume - volume < 0.5 * area * facet_distance);
  // Every node lies inside the grid's extent and the extremes are reached to within a chord's
  // depth, facet_distance (1.7 mm), plus the grid's half cell. Measured: at most 0.74 mm apart.
  const Eigen::Vector3d low = mesh.nodes.colwise().minCoeff().transpose();
  const Eigen::Vector3d high = mesh.nodes.colwise().maxCoeff().transpose();
  for (int axis = 0; axis < 3; ++axis) {
    CAPTURE(axis);
    CHECK(std::abs(low[axis] - g.extent.min()[axis]) < facet_distance + 0.5 * g.cell);
    CHECK(std::abs(high[axis] - g.extent.max()[axis]) < facet_distance + 0.5 * g.cell);
  }
}

TEST_CASE("the liver mesh's surface is closed, consistently oriented, connected, and a sphere's") {
  const kerf::TetMesh& mesh = liver_mesh();
  const kerf::TetMatrix& faces = kerf::boundary_faces(mesh).faces;
  // Closed and oriented: every directed edge (a, b) of an outward triangle is met once, and its
  // reverse (b, a) once too, by the triangle on the other side. So each undirected edge is in
  // exactly two boundary triangles, which turn it opposite ways.
  std::map<std::pair<int, int>, int> directed;
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int e = 0; e < 3; ++e) ++directed[{faces(f, e), faces(f, (e + 1) % 3)}];
  int unmatched = 0;
  for (const auto& [edge, count] : directed) {
    const auto reverse = directed.find({edge.second, edge.first});
    if (count != 1 || reverse == directed.end() || reverse->second != 1) ++unmatched;
  }
  CHECK(unmatched == 0);
  // One piece: join the triangles that share an edge (union-find) and count the roots.
  std::vector<int> parent(static_cast<std::size_t>(faces.rows()));
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&parent](int f) {
    while (parent[f] != f) f = parent[f] = parent[parent[f]];
    return f;
  };
  std::map<std::pair<int, int>, int> first_face;
  for (int f = 0; f < faces.rows(); ++f)
    for (int e = 0; e < 3; ++e) {
      const int a = faces(f, e), b = faces(f, (e + 1) % 3);
      const auto [it, is_new] = first_face.emplace(std::minmax(a, b), f);
      if (!is_new) parent[root(f)] = root(it->second);
    }
  int components = 0;
  for (int f = 0; f < faces.rows(); ++f)
    if (root(f) == f) ++components;
  CHECK(components == 1);
  // A sphere's topology, no handle and no cavity: V - E + F = 2 on the surface.
  std::vector<int> surface_nodes(faces.data(), faces.data() + faces.size());
  std::sort(surface_nodes.begin(), surface_nodes.end());
  const auto V = std::unique(surface_nodes.begin(), surface_nodes.end()) - surface_nodes.begin();
  const auto E = static_cast<Eigen::Index>(first_face.size());
  CHECK(V - E + faces.rows() == 2);
}

TEST_CASE("the liver mesh has no slivers") {
  const kerf::TetQualitySummary q = kerf::tet_quality_summary(liver_mesh(), 10.0, 0.1);
  // The perturber and exuder aim for 15 degrees (ImplicitMeshOptimisation::sliver_bound) and
  // reached it at every size we measured, 2k to 100k. Measured here: smallest dihedral angle
  // 15.10 degrees, smallest radius ratio 0.258, mean radius ratio 0.795.
  CHECK(q.min_dihedral_angle > 14.0);
  CHECK(q.min_radius_ratio > 0.2);
  CHECK(q.mean_radius_ratio > 0.75);
  CHECK(q.below_dihedral_threshold == 0);
  CHECK(q.below_radius_ratio_threshold == 0);
}

TEST_CASE("make_liver_mesh gives the same mesh on every call") {
  const kerf::TetMesh again = kerf::make_liver_mesh(test_tets);
  REQUIRE(again.num_nodes() == liver_mesh().num_nodes());
  REQUIRE(again.num_tets() == liver_mesh().num_tets());
  CHECK(again.nodes == liver_mesh().nodes); // bit for bit
  CHECK(again.tets == liver_mesh().tets);
}

TEST_CASE("sizes the liver cannot be meshed with are refused in one line naming the size and the range") {
  for (const int target : {-5, 0, 999, 1'000'001}) {
    CAPTURE(target);
    try {
      (void)kerf::make_liver_mesh(target);
      FAIL("no exception");
    } catch (const std::invalid_argument& error) {
      const std::string message = error.what();
      CHECK(message == "make_liver_mesh: " + std::to_string(target) + " tets is outside the range [1000, 1000000]");
    }
  }
}

TEST_CASE("mesh_implicit_domain refuses a domain it would search without end, and stops a mesh too fine") {
  const auto ball = [](const Eigen::Vector3d& x) { return x.norm() - 0.05; };
  kerf::ImplicitMeshSizing sizing;
  const auto one_line = [](const std::exception& error) { return std::string(error.what()).find('\n') == std::string::npos; };
  // Mesh_3 shoots rays from the centre until they cross the surface: from outside the ball, or
  // with a sphere that cuts it, it could shoot forever.
  CHECK_THROWS_WITH_AS(kerf::mesh_implicit_domain(ball, {0.1, 0, 0}, 0.2, sizing),
                       "mesh_implicit_domain: phi(centre) must be negative (the centre inside)", std::invalid_argument);
  CHECK_THROWS_AS(kerf::mesh_implicit_domain(ball, {0, 0, 0}, 0.03, sizing), std::invalid_argument);
  sizing.cell_size = 0.0;
  CHECK_THROWS_AS(kerf::mesh_implicit_domain(ball, {0, 0, 0}, 0.1, sizing), std::invalid_argument);
  // A cell size of 0.1 mm would need some 10^8 vertices; Mesh_3 stops at max_vertices and we say so.
  sizing.cell_size = sizing.facet_size = 1e-4;
  sizing.max_vertices = 2000;
  try {
    (void)kerf::mesh_implicit_domain(ball, {0, 0, 0}, 0.1, sizing);
    FAIL("no exception");
  } catch (const std::runtime_error& error) {
    CHECK(one_line(error));
    CHECK(std::string(error.what()).find("maximal number of vertices") != std::string::npos);
  }
}
