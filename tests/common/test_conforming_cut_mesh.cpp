// Chapter 4's conforming reference for curved cuts: the height-field surface z = z_c + h(x, y)
// as a triangle mesh, and the beam's box mesh whose node layer is moved onto it and opened along
// it (split_box_along_height_field). The surface passes the check and lies on the graph; every
// mapped tet changes its volume by exactly the factor derived in the header; the mesh still
// fills the box; the two parts share no node; each part reproduces its own rigid motion and
// its own linear field exactly.
#include "kerf/cut/clip_tet.hpp"
#include "kerf/cut/height_field_surface.hpp"
#include "kerf/cut/split_box_along_height_field.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/solve_linear_static.hpp"
#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/mesh/check_tet_mesh.hpp"
#include "kerf/mesh/check_triangle_surface.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

// Chapter 3's beam, cut at z_c = 0.1 m, 0.1 m from either end.
const Eigen::Vector3d beam_min(0, 0, 0), beam_max(0.03, 0.06, 0.2);
constexpr double z_c = 0.1;
constexpr double box_volume = 0.03 * 0.06 * 0.2; // m^3
constexpr double amplitude = 0.004;               // m, 4 % of the distance to either end

struct NamedHeight {
  std::string name;
  kerf::HeightField h;
};

// The three blades of chapter 4: a dome (zero on the beam's sides), a sine sheet across y (zero
// mean over a period) and a ridge with a kink along x = 0.015 (a grid line for even nx).
std::vector<NamedHeight> heights() {
  return {{"dome",
           [](double x, double y) {
             const double s = (x - 0.015) / 0.015, t = (y - 0.03) / 0.03;
             return amplitude * (1 - s * s) * (1 - t * t);
           }},
          {"sine", [](double, double y) { return amplitude * std::sin(2 * std::numbers::pi * y / 0.06); }},
          {"ridge", [](double x, double) { return amplitude * (1 - std::abs(2 * x / 0.03 - 1)); }}};
}

const kerf::HeightField flat = [](double, double) { return 0.0; };

Eigen::Vector3d triangle_normal(const kerf::TriangleSurface& s, Eigen::Index f) {
  const Eigen::Vector3d x0 = s.vertices.row(s.triangles(f, 0)).transpose(), x1 = s.vertices.row(s.triangles(f, 1)).transpose(),
                        x2 = s.vertices.row(s.triangles(f, 2)).transpose();
  return (x1 - x0).cross(x2 - x0);
}

// Which tets of the box lie below the layer: their centroid in the unmapped box (h = 0).
std::vector<char> tets_below(const kerf::TetMesh& unmapped) {
  std::vector<char> below(static_cast<std::size_t>(unmapped.num_tets()));
  for (Eigen::Index t = 0; t < unmapped.num_tets(); ++t)
    below[static_cast<std::size_t>(t)] = kerf::tet_corners(unmapped, t).col(2).mean() < z_c;
  return below;
}

// The part of every node: 0 if a tet below uses it, 1 if a tet above does, 2 if both (never,
// once the mesh is split), -1 if none.
std::vector<int> node_parts(const kerf::TetMesh& mesh, const std::vector<char>& below) {
  std::vector<int> part(static_cast<std::size_t>(mesh.num_nodes()), -1);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    for (int a = 0; a < mesh.nodes_per_tet(); ++a) {
      int& p = part[static_cast<std::size_t>(mesh.tets(t, a))];
      const int side = below[static_cast<std::size_t>(t)] ? 0 : 1;
      p = p < 0 || p == side ? side : 2;
    }
  return part;
}

} // namespace

TEST_CASE("height_field_surface: the graph of h on a grid, exactly on it, oriented to +z, passing the check unchanged") {
  const Eigen::Vector2i cells(4, 6);
  for (const NamedHeight& height : heights()) {
    CAPTURE(height.name);
    const kerf::TriangleSurface s = kerf::height_field_surface(height.h, z_c, {0, 0}, {0.03, 0.06}, cells);
    REQUIRE(s.num_vertices() == 5 * 7);
    REQUIRE(s.num_triangles() == 2 * 4 * 6);
    for (int j = 0; j <= cells[1]; ++j)
      for (int i = 0; i <= cells[0]; ++i) {
        const Eigen::RowVector3d x = s.vertices.row(i + 5 * j);
        CHECK(x[0] == kerf_test::relative(0.03 * i / cells[0], 1e-15));
        CHECK(x[1] == kerf_test::relative(0.06 * j / cells[1], 1e-15));
        CHECK(x[2] == z_c + height.h(x[0], x[1])); // on the graph, to the last bit
      }
    // Every normal has +z: the projection is traversed counter-clockwise, and the projected
    // areas add up to the rectangle's (no overlap, no gap).
    double projected_area = 0.0;
    for (Eigen::Index f = 0; f < s.num_triangles(); ++f) {
      const double nz = triangle_normal(s, f)[2];
      CHECK(nz > 0.0);
      projected_area += nz / 2;
    }
    CHECK(std::abs(projected_area - 0.03 * 0.06) <= 1e-14 * 0.03 * 0.06);

    kerf::TriangleSurface checked = s;
    const kerf::SurfaceCheck report = kerf::check_triangle_surface(checked, height.name);
    CHECK(report.merged_vertices == 0);
    CHECK(report.unused_vertices == 0);
    CHECK(report.flipped_triangles == 0);
    CHECK(report.components == 1);
    CHECK(report.boundary_edges == 2 * (4 + 6));
    CHECK(checked.vertices == s.vertices);
    CHECK(checked.triangles == s.triangles);
  }
  // The ridge's kink lies on the grid line x = 0.015 (nx even): the surface is exact there.
  const kerf::TriangleSurface ridge = kerf::height_field_surface(heights()[2].h, z_c, {0, 0}, {0.03, 0.06}, cells);
  for (int j = 0; j <= cells[1]; ++j) CHECK(ridge.vertices(2 + 5 * j, 2) == z_c + amplitude);

  CHECK_THROWS_AS(kerf::height_field_surface({}, z_c, {0, 0}, {1, 1}, {1, 1}), std::invalid_argument);
  CHECK_THROWS_AS(kerf::height_field_surface(flat, z_c, {0, 0}, {1, 1}, {0, 1}), std::invalid_argument);
  CHECK_THROWS_AS(kerf::height_field_surface(flat, z_c, {0, 0}, {1, 0}, {1, 1}), std::invalid_argument);
  const kerf::HeightField broken = [](double x, double) { return x > 0.5 ? std::numeric_limits<double>::quiet_NaN() : 0.0; };
  CHECK_THROWS_AS(kerf::height_field_surface(broken, z_c, {0, 0}, {1, 1}, {2, 2}), std::invalid_argument);
}

TEST_CASE("split_box_along_height_field: the layer is the surface, every tet scales by 1 + h/(z_c - z0) or 1 - h/(z1 - z_c), "
          "the box stays full") {
  const Eigen::Vector3i cells(4, 6, 8);
  const Eigen::Index per_layer = 5 * 7;
  for (int order : {1, 2}) {
    const kerf::TetMesh unmapped = kerf::split_box_along_height_field(beam_min, beam_max, cells, z_c, flat, order).split.mesh;
    const std::vector<char> below = tets_below(unmapped);
    for (const NamedHeight& height : heights()) {
      CAPTURE(order);
      CAPTURE(height.name);
      const kerf::HeightFieldSplitMesh r = kerf::split_box_along_height_field(beam_min, beam_max, cells, z_c, height.h, order);
      const kerf::TetMesh& mesh = r.split.mesh;
      REQUIRE(r.layer == 4);
      REQUIRE(mesh.num_tets() == unmapped.num_tets());

      // The cut surface is height_field_surface's, to the last bit, and the layer's nodes are its vertices.
      const kerf::TriangleSurface expected = kerf::height_field_surface(height.h, z_c, {0, 0}, {0.03, 0.06}, {4, 6});
      CHECK(r.cut_surface.vertices == expected.vertices);
      CHECK(r.cut_surface.triangles == expected.triangles);
      for (Eigen::Index s = 0; s < per_layer; ++s)
        CHECK(Eigen::RowVector3d(mesh.nodes.row(r.layer * per_layer + s)) == Eigen::RowVector3d(expected.vertices.row(s)));

      // Per tet: the corners of the z step share (x, y); the volume ratio is the header's factor.
      double total = 0.0, volume_below = 0.0, min_ratio = 2.0, max_ratio = 0.0;
      for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
        const Eigen::Matrix<double, 4, 3> X0 = kerf::tet_corners(unmapped, t);
        const double v0 = kerf::signed_tet_volume(X0), v = kerf::signed_tet_volume(kerf::tet_corners(mesh, t));
        REQUIRE(v0 > 0.0);
        CHECK(v > 0.0);
        int pairs = 0;
        double h_a = 0.0;
        for (int a = 0; a < 4; ++a)
          for (int b = a + 1; b < 4; ++b)
            if (X0(a, 0) == X0(b, 0) && X0(a, 1) == X0(b, 1)) {
              ++pairs;
              h_a = height.h(X0(a, 0), X0(a, 1));
            }
        REQUIRE(pairs == 1);
        const bool is_below = below[static_cast<std::size_t>(t)];
        const double factor = is_below ? 1 + h_a / (z_c - beam_min[2]) : 1 - h_a / (beam_max[2] - z_c);
        CHECK(v / v0 == kerf_test::relative(factor, 1e-12));
        min_ratio = std::min(min_ratio, v / v0);
        max_ratio = std::max(max_ratio, v / v0);
        total += v;
        if (is_below) volume_below += v;
      }
      MESSAGE(height.name << ", order " << order << ": tet volume ratios in [" << min_ratio << ", " << max_ratio << "], volume below "
                          << volume_below << " m^3 (flat cut " << box_volume / 2 << ")");
      CHECK(min_ratio >= 1 - amplitude / 0.1 - 1e-12);
      CHECK(max_ratio <= 1 + amplitude / 0.1 + 1e-12);
      // The mesh fills the box whatever h is; the part below is the prism under the surface.
      CHECK(std::abs(total - box_volume) <= 1e-13 * box_volume);
      double under_surface = 0.03 * 0.06 * (z_c - beam_min[2]);
      for (Eigen::Index f = 0; f < r.cut_surface.num_triangles(); ++f) {
        double mean_h = 0.0;
        for (int c = 0; c < 3; ++c) mean_h += (r.cut_surface.vertices(r.cut_surface.triangles(f, c), 2) - z_c) / 3;
        under_surface += triangle_normal(r.cut_surface, f)[2] / 2 * mean_h;
      }
      CHECK(std::abs(volume_below - under_surface) <= 1e-12 * under_surface);
      // The sine sheet's interpolant has zero mean (a whole period, equal weights on the interior
      // grid lines): the parts keep the flat cut's volumes. The dome and the ridge move volume up.
      if (height.name == "sine") CHECK(std::abs(volume_below - box_volume / 2) <= 1e-12 * box_volume);
      else CHECK(volume_below > box_volume / 2 * (1 + 0.1 * amplitude / 0.1));

      if (order == 2) { // straight edges, positive det J at every quadrature point: nothing to repair
        kerf::TetMesh copy = mesh;
        std::ostringstream warnings;
        CHECK(kerf::check_tet_mesh(copy, height.name, &warnings) == 0);
        CHECK(warnings.str().empty());
        CHECK(copy.nodes == mesh.nodes);
      }
    }
  }
}

TEST_CASE("split_box_along_height_field: with no node layer at z_c (chapter 3's 3 x 6 x 19 cells) the nearest one is fitted onto it") {
  const Eigen::Vector3i cells(3, 6, 19); // z step 0.2 / 19: layers 9 and 10 at 0.0947 and 0.1053
  const Eigen::Index per_layer = 4 * 7;
  for (int order : {1, 2}) {
    CAPTURE(order);
    const kerf::HeightFieldSplitMesh fitted = kerf::split_box_along_height_field(beam_min, beam_max, cells, z_c, flat, order);
    REQUIRE(fitted.layer == 10); // 9.5 rounds up
    // Ten even steps up to z_c, nine above it, and the layer exactly at z_c.
    for (Eigen::Index v = 0; v < 20 * per_layer; ++v) {
      const int k = static_cast<int>(v / per_layer);
      const double expected = k <= 10 ? z_c * k / 10 : z_c + (0.2 - z_c) * (k - 10) / 9;
      CHECK(std::abs(fitted.split.mesh.nodes(v, 2) - expected) <= 1e-16);
      if (k == 10) CHECK(fitted.split.mesh.nodes(v, 2) == z_c);
    }
    const kerf::HeightField dome = heights()[0].h;
    const kerf::HeightFieldSplitMesh r = kerf::split_box_along_height_field(beam_min, beam_max, cells, z_c, dome, order);
    const kerf::TriangleSurface expected = kerf::height_field_surface(dome, z_c, {0, 0}, {0.03, 0.06}, {3, 6});
    CHECK(r.cut_surface.vertices == expected.vertices);
    CHECK(r.cut_surface.triangles == expected.triangles);
    double total = 0.0;
    for (Eigen::Index t = 0; t < r.split.mesh.num_tets(); ++t) {
      const double v = kerf::signed_tet_volume(kerf::tet_corners(r.split.mesh, t));
      CHECK(v > 0.0);
      total += v;
    }
    CHECK(std::abs(total - box_volume) <= 1e-13 * box_volume);
  }
}

TEST_CASE("split_box_along_height_field: the layer's nodes are duplicated and the two parts share none") {
  const Eigen::Vector3i cells(2, 4, 6);
  for (int order : {1, 2}) {
    const std::vector<char> below = tets_below(kerf::split_box_along_height_field(beam_min, beam_max, cells, z_c, flat, order).split.mesh);
    for (const NamedHeight& height : heights()) {
      CAPTURE(order);
      CAPTURE(height.name);
      const kerf::HeightFieldSplitMesh r = kerf::split_box_along_height_field(beam_min, beam_max, cells, z_c, height.h, order);
      const kerf::SplitMesh& split = r.split;
      // Tet4: the 3 x 5 corners of the layer; Tet10 also the midpoints of its 2 x 5 x-edges,
      // 3 x 4 y-edges and 2 x 4 face diagonals.
      CHECK(split.duplicated_nodes == (order == 1 ? 15 : 15 + 10 + 12 + 8));
      REQUIRE(split.duplicate_of.size() == static_cast<std::size_t>(split.duplicated_nodes));
      const Eigen::Index V = split.mesh.num_nodes() - split.duplicated_nodes;
      for (int k = 0; k < split.duplicated_nodes; ++k) {
        const int original = split.duplicate_of[static_cast<std::size_t>(k)];
        if (k > 0) CHECK(original > split.duplicate_of[static_cast<std::size_t>(k - 1)]);
        CHECK(split.mesh.nodes.row(V + k) == split.mesh.nodes.row(original));
        // On the cut: its z is the interpolant's (for a mid-edge node, the mean of its edge's ends).
        CHECK(std::abs(split.mesh.nodes(original, 2) - z_c) <= amplitude + 1e-15);
      }
      const std::vector<int> part = node_parts(split.mesh, below);
      int lower = 0, upper = 0;
      for (Eigen::Index v = 0; v < split.mesh.num_nodes(); ++v) {
        const int p = part[static_cast<std::size_t>(v)];
        CHECK((p == 0 || p == 1)); // used, and by one part only
        (p == 0 ? lower : upper) += 1;
        if (v >= V) CHECK(p == 0); // the duplicates belong to the part below
      }
      // The unsplit mesh has equally many nodes on either side of the layer, plus the layer itself.
      CHECK(lower == upper);
      CHECK(lower + upper == split.mesh.num_nodes());
    }
  }
}

TEST_CASE("split_box_along_height_field: each part reproduces its own rigid motion and its own linear field exactly") {
  const kerf::LinearMaterial material{300e3, 0.35, 1070};
  const Eigen::Vector3i cells(2, 4, 8);
  // Two different rigid motions c + w x x (infinitesimal: zero linear strain) and linear fields.
  const auto rigid = [](const Eigen::Vector3d& c, const Eigen::Vector3d& w) {
    return [c, w](const Eigen::Vector3d& x) -> Eigen::Vector3d { return c + w.cross(x); };
  };
  const auto affine = [](const Eigen::Vector3d& c, const Eigen::Matrix3d& A) {
    return [c, A](const Eigen::Vector3d& x) -> Eigen::Vector3d { return c + A * x; };
  };
  Eigen::Matrix3d A_lower, A_upper;
  A_lower << 0.01, -0.02, 0.005, 0.003, 0.015, -0.01, -0.007, 0.002, 0.02;
  A_upper << -0.012, 0.004, 0.01, 0.02, -0.006, 0.003, 0.001, -0.015, 0.009;
  struct Case {
    std::string name;
    std::function<Eigen::Vector3d(const Eigen::Vector3d&)> lower, upper;
    bool whole_boundary; // Dirichlet on every boundary node, or on the two end faces only
  };
  const std::vector<Case> cases = {
      {"rigid motions held at the ends", rigid({1e-3, -2e-3, 5e-4}, {0.01, -0.02, 0.03}), rigid({-2e-3, 1e-3, 3e-3}, {-0.03, 0.01, 0.02}),
       false},
      {"linear fields on the boundary", affine({1e-3, -2e-3, 3e-3}, A_lower), affine({-1e-3, 2e-3, 1e-3}, A_upper), true}};

  for (int order : {1, 2}) {
    const std::vector<char> below = tets_below(kerf::split_box_along_height_field(beam_min, beam_max, cells, z_c, flat, order).split.mesh);
    for (const NamedHeight& height : heights())
      for (const Case& c : cases) {
        CAPTURE(order);
        CAPTURE(height.name);
        CAPTURE(c.name);
        const kerf::TetMesh mesh = kerf::split_box_along_height_field(beam_min, beam_max, cells, z_c, height.h, order).split.mesh;
        const std::vector<int> part = node_parts(mesh, below);
        const auto exact = [&](Eigen::Index v) {
          const Eigen::Vector3d x = mesh.nodes.row(v).transpose();
          return part[static_cast<std::size_t>(v)] == 0 ? c.lower(x) : c.upper(x);
        };
        std::vector<char> held(static_cast<std::size_t>(mesh.num_nodes()), 0);
        if (c.whole_boundary) {
          // The cut's faces are boundary faces of the split mesh, on both banks.
          const kerf::BoundaryFaces boundary = kerf::boundary_faces(mesh);
          for (Eigen::Index f = 0; f < boundary.faces.rows(); ++f)
            for (int k = 0; k < boundary.faces.cols(); ++k) held[static_cast<std::size_t>(boundary.faces(f, k))] = 1;
        } else {
          // Only z = 0 holds the part below and only z = 0.2 the part above: the cut is free.
          for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v)
            held[static_cast<std::size_t>(v)] = mesh.nodes(v, 2) == 0.0 || mesh.nodes(v, 2) == 0.2;
        }
        std::vector<kerf::DirichletNodes> conditions;
        for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v)
          if (held[static_cast<std::size_t>(v)]) conditions.push_back({{static_cast<int>(v)}, exact(v)});
        const kerf::DofMap dofs = kerf::make_dof_map(mesh.num_nodes(), conditions);
        REQUIRE(dofs.num_free > 0);
        // No body force: both fields have constant stress, so div sigma = 0 in each part, and
        // the cut's faces carry no traction only for the rigid motions (zero stress), which is
        // why the linear fields hold the cut's faces too.
        const Eigen::VectorXd u = kerf::solve_linear_static(mesh, material, dofs, Eigen::VectorXd::Zero(3 * mesh.num_nodes()), {});
        double error = 0.0, scale = 0.0;
        for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) {
          error = std::max(error, (u.segment<3>(3 * v) - exact(v)).cwiseAbs().maxCoeff());
          scale = std::max(scale, exact(v).cwiseAbs().maxCoeff());
        }
        MESSAGE(height.name << ", order " << order << ", " << c.name << ": " << dofs.num_free << " unknowns, max error " << error
                            << " m of max |u| " << scale << " m");
        CHECK(error < 1e-12 * scale); // measured below 1e-13 of max |u|: round-off
      }
  }
}

TEST_CASE("split_box_along_height_field: refuses heights that would flip a tet, and bad arguments") {
  const Eigen::Vector3i cells(2, 2, 4);
  const kerf::HeightField too_low = [](double, double) { return -0.1; }; // = -(z_c - z0): flat tets
  const kerf::HeightField too_high = [](double x, double) { return x > 0.02 ? 0.1 : 0.0; };
  const kerf::HeightField nan = [](double, double) { return std::numeric_limits<double>::quiet_NaN(); };
  for (const kerf::HeightField& h : {too_low, too_high, nan}) {
    try {
      (void)kerf::split_box_along_height_field(beam_min, beam_max, cells, z_c, h, 1);
      FAIL("a height that flips tets was accepted");
    } catch (const std::invalid_argument& e) {
      const std::string message = e.what();
      MESSAGE(message);
      // A NaN is caught first by height_field_surface(), which names the point.
      CHECK((message.find("grid node") != std::string::npos || message.find("is not finite") != std::string::npos));
    }
  }
  // Just inside the bound every tet is still positive, however thin the part below gets.
  const kerf::HeightField almost = [](double, double) { return -0.099; };
  const kerf::TetMesh thin = kerf::split_box_along_height_field(beam_min, beam_max, cells, z_c, almost, 1).split.mesh;
  for (Eigen::Index t = 0; t < thin.num_tets(); ++t) CHECK(kerf::signed_tet_volume(kerf::tet_corners(thin, t)) > 0.0);

  CHECK_THROWS_AS(kerf::split_box_along_height_field(beam_min, beam_max, cells, z_c, flat, 3), std::invalid_argument);
  CHECK_THROWS_AS(kerf::split_box_along_height_field(beam_min, beam_max, {2, 2, 1}, z_c, flat, 1), std::invalid_argument);
  CHECK_THROWS_AS(kerf::split_box_along_height_field(beam_min, beam_max, cells, 0.2, flat, 1), std::invalid_argument);
  CHECK_THROWS_AS(kerf::split_box_along_height_field(beam_min, beam_max, cells, z_c, {}, 1), std::invalid_argument);
  CHECK_THROWS_AS(kerf::split_box_along_height_field(beam_max, beam_min, cells, z_c, flat, 1), std::invalid_argument);
}
