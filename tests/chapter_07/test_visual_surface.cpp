// The visual surface (mesh/implicit_surface_mesh.hpp, xfem/visual_surface.hpp): the fine surface of
// the liver is closed, outward, on phi = 0 and several times finer than the tets' boundary; its
// embedding rebuilds every vertex from its tet's corners; it moves exactly with a rigid motion and
// with a tet's linear field (extrapolated outside); across an opened XFEM cut each vertex takes
// its own side's displacement, and the triangles that would stretch across the gap are dropped.
#include "support/cut_body.hpp"
#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/implicit_surface_mesh.hpp"
#include "kerf/mesh/liver_mesh.hpp"
#include "kerf/mesh/liver_shape.hpp"
#include "kerf/mesh/point_locator.hpp"
#include "kerf/xfem/visual_surface.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

namespace {

// The liver at 3000 tets (test_liver_mesh.cpp's size) and a visual surface of 5 mm triangles.
constexpr double visual_size = 0.005;

const kerf::TetMesh& liver() {
  static const kerf::TetMesh mesh = kerf::make_liver_mesh(3000);
  return mesh;
}

const kerf::TriangleSurface& liver_visual() {
  static const kerf::TriangleSurface surface = kerf::implicit_surface_mesh(
      kerf::liver_phi, kerf::liver_centre(), kerf::liver_bounding_radius(), kerf::implicit_surface_sizing(visual_size));
  return surface;
}

Eigen::Vector3d row(const Eigen::MatrixX3d& m, Eigen::Index i) { return m.row(i).transpose(); }

// The volume enclosed by outward triangles: sum of x0 . (x1 x x2) / 6 (divergence theorem).
double enclosed_volume(const kerf::TriangleSurface& s) {
  double volume = 0.0;
  for (Eigen::Index f = 0; f < s.num_triangles(); ++f)
    volume += row(s.vertices, s.triangles(f, 0)).dot(row(s.vertices, s.triangles(f, 1)).cross(row(s.vertices, s.triangles(f, 2)))) / 6.0;
  return volume;
}

double mesh_volume(const kerf::TetMesh& mesh) {
  double volume = 0.0;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const Eigen::Matrix<double, 4, 3> X = kerf::tet_corners(mesh, t);
    volume += (X.row(1) - X.row(0)).dot((X.row(2) - X.row(0)).cross(X.row(3) - X.row(0))) / 6.0;
  }
  return volume;
}

// A unit box cut clean through by the plane z = 0.43, and the field that lifts the pieces above
// it (H = +1) by u_plus and sinks those below by u_minus: at every node, u_i is its home side's
// value and a_k the other side's minus it (tests/chapter_04's piecewise_field).
kerf::TriangleSurface level_cut() {
  kerf::TriangleSurface cut;
  cut.vertices = Eigen::MatrixX3d{{-1, -1, 0.43}, {2, -1, 0.43}, {2, 2, 0.43}, {-1, 2, 0.43}};
  cut.triangles = Eigen::MatrixX3i{{0, 1, 2}, {0, 2, 3}};
  return cut;
}
const Eigen::Vector3d u_plus(0.02, 0.0, 0.1), u_minus(0.0, -0.01, -0.05);
Eigen::Vector3d side_value(const Eigen::Vector3d& x) { return x.z() > 0.43 ? u_plus : u_minus; }
Eigen::VectorXd two_sided_field(const support::CutBody& body) {
  const Eigen::Index N = body.mesh.num_nodes();
  Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * body.model.num_dof_nodes());
  for (Eigen::Index i = 0; i < N; ++i) u.segment<3>(3 * i) = side_value(row(body.mesh.nodes, i));
  for (Eigen::Index i = 0; i < N; ++i)
    for (int k = body.enrichment.first_enrichment[static_cast<std::size_t>(i)]; k < body.enrichment.first_enrichment[static_cast<std::size_t>(i) + 1]; ++k)
      u.segment<3>(3 * (N + k)) = (row(body.mesh.nodes, i).z() > 0.43 ? u_minus : u_plus) - u.segment<3>(3 * i);
  return u;
}

} // namespace

TEST_CASE("the liver's visual surface is closed, outward, on phi = 0 and several times finer than the tets' boundary") {
  const kerf::TriangleSurface& s = liver_visual();
  // Every directed edge is matched by its reverse, once: closed, a manifold, consistently oriented.
  std::map<std::pair<int, int>, int> directed;
  for (Eigen::Index f = 0; f < s.num_triangles(); ++f)
    for (int a = 0; a < 3; ++a) ++directed[{s.triangles(f, a), s.triangles(f, (a + 1) % 3)}];
  int unmatched = 0;
  for (const auto& [edge, count] : directed) unmatched += (count == 1 && directed.count({edge.second, edge.first}) == 1 && directed.at({edge.second, edge.first}) == 1) ? 0 : 1;
  CHECK(unmatched == 0);
  // Euler characteristic V - E + F = 2: one closed surface of a sphere's topology.
  CHECK(s.num_vertices() - static_cast<Eigen::Index>(directed.size()) / 2 + s.num_triangles() == 2);

  // Outward: the enclosed volume is positive, and close to the tets' volume. MESSAGE prints what we measured.
  const double volume = enclosed_volume(s), tets = mesh_volume(liver());
  MESSAGE("visual triangles ", s.num_triangles(), ", vertices ", s.num_vertices(), ", volume ", volume, " vs tets ", tets);
  // The tets' chords cut a little off the convex parts: measured 1.8 % more than the tets.
  CHECK(volume > 0.0);
  CHECK(std::abs(volume / tets - 1.0) < 0.03);

  const kerf::BoundaryFaces boundary = kerf::boundary_faces(liver());
  MESSAGE("tet boundary triangles ", boundary.faces.rows());
  // Measured 5.7 times (3796 of 668) with 5 mm triangles.
  CHECK(s.num_triangles() > 4 * boundary.faces.rows());

  double worst_phi = 0.0;
  for (Eigen::Index v = 0; v < s.num_vertices(); ++v) worst_phi = std::max(worst_phi, std::abs(kerf::liver_phi(row(s.vertices, v))));
  MESSAGE("largest |phi| at a vertex ", worst_phi);
  // Mesh_3 bisects to 1e-6 of the bounding sphere's diameter (0.3 um here); phi grows like a
  // distance near the surface. Measured 0.14 um.
  CHECK(worst_phi < 1e-6 * 2.0 * kerf::liver_bounding_radius());
}

TEST_CASE("the embedding rebuilds every vertex from its tet's corners; outside vertices lie close to their tet") {
  const kerf::VisualSurface visual(liver(), liver_visual());
  double worst_inside = 0.0;
  for (Eigen::Index v = 0; v < liver_visual().num_vertices(); ++v) {
    const kerf::VisualVertexEmbedding& e = visual.embedding()[static_cast<std::size_t>(v)];
    const double error = (visual.embedded_position(v) - row(liver_visual().vertices, v)).norm();
    worst_inside = std::max(worst_inside, error);
    CHECK(e.barycentric.sum() == kerf_test::relative(1.0, 1e-12));
    if (e.distance == 0.0) CHECK(e.barycentric.minCoeff() >= -1e-10);
  }
  MESSAGE("outside ", visual.num_outside(), " of ", liver_visual().num_vertices(), ", largest distance ", visual.largest_distance(),
          ", worst rebuild ", worst_inside);
  CHECK(worst_inside < 1e-12);
  // The tets' boundary triangles are chords of phi = 0, so on the convex parts (most of the
  // liver) the fine surface lies outside them, at most about the sag Mesh_3's facet distance
  // bounds (at circumcentres): 1.13 times it at 3000 tets (1.86 mm of 1.65 mm).
  CHECK(visual.num_outside() > liver_visual().num_vertices() / 2);
  CHECK(visual.largest_distance() < 1.5 * kerf::liver_mesh_sizing(3000).facet_distance);
}

TEST_CASE("a rigid motion moves every vertex by it, a tet's linear field matches the field, outside vertices included") {
  const kerf::VisualSurface visual(liver(), liver_visual());
  const Eigen::Vector3d t(0.01, -0.02, 0.03), w(0.3, -0.1, 0.2);
  const kerf::TriangleSurface moved = visual.deform([&](int, const Eigen::Vector3d& x) -> Eigen::Vector3d { return t + w.cross(x); });
  double worst = 0.0;
  for (Eigen::Index v = 0; v < moved.num_vertices(); ++v) {
    const Eigen::Vector3d x = row(liver_visual().vertices, v);
    worst = std::max(worst, (row(moved.vertices, v) - (x + t + w.cross(x))).norm());
  }
  CHECK(worst < 1e-15);

  // The FE field of tet t of nodal values of a linear field: sum_a lambda_a(x) u(X_a), lambda
  // from the tet's corners, extrapolated outside it. It is the linear field itself.
  const Eigen::Matrix3d A{{0.1, -0.2, 0.05}, {0.3, 0.0, -0.1}, {-0.05, 0.2, 0.15}};
  const auto linear = [&](const Eigen::Vector3d& x) -> Eigen::Vector3d { return t + A * x; };
  const kerf::TriangleSurface stretched = visual.deform([&](int tet, const Eigen::Vector3d& x) -> Eigen::Vector3d {
    const Eigen::Matrix<double, 4, 3> X = kerf::tet_corners(liver(), tet);
    Eigen::Matrix3d J;
    for (int a = 0; a < 3; ++a) J.col(a) = (X.row(a + 1) - X.row(0)).transpose();
    const Eigen::Vector3d xi = J.inverse() * (x - X.row(0).transpose());
    const Eigen::Vector4d lambda(1.0 - xi.sum(), xi(0), xi(1), xi(2));
    Eigen::Vector3d u = Eigen::Vector3d::Zero();
    for (int a = 0; a < 4; ++a) u += lambda(a) * linear(X.row(a).transpose());
    return u;
  });
  worst = 0.0;
  for (Eigen::Index v = 0; v < stretched.num_vertices(); ++v) {
    const Eigen::Vector3d x = row(liver_visual().vertices, v);
    worst = std::max(worst, (row(stretched.vertices, v) - (x + linear(x))).norm());
  }
  // Round-off of the 3x3 solve on tets 1 cm across, on displacements of a few mm.
  CHECK(worst < 1e-14);
}

TEST_CASE("across an opened XFEM cut each vertex takes its side's displacement; the triangles across the gap are dropped") {
  // A unit box cut clean through by the plane z = 0.43 (level_cut), a visual sphere inside it,
  // and the field that moves each side by its own constant (two_sided_field).
  const kerf::TriangleSurface cut = level_cut();
  const kerf::LinearMaterial material{1000.0, 0.3, 1.0};
  const support::CutBody body(kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {3, 3, 4}), {cut}, material);
  const Eigen::Vector3d centre(0.5, 0.5, 0.5);
  const kerf::TriangleSurface sphere = kerf::implicit_surface_mesh(
      [&](const Eigen::Vector3d& x) { return (x - centre).norm() - 0.4; }, centre, 0.49, kerf::implicit_surface_sizing(0.05));
  const Eigen::VectorXd u = two_sided_field(body);

  const kerf::VisualSurface visual(body.mesh, sphere);
  CHECK(visual.num_outside() == 0);
  const kerf::TriangleSurface moved = visual.deform(kerf::xfem_visual_displacement(body.model, u));
  double worst = 0.0;
  for (Eigen::Index v = 0; v < sphere.num_vertices(); ++v) {
    const Eigen::Vector3d x = row(sphere.vertices, v);
    worst = std::max(worst, (row(moved.vertices, v) - x - side_value(x)).norm());
  }
  CHECK(worst < 1e-14);

  // Kept: triangles with all corners on one side; dropped: those with corners on both.
  const std::vector<int> keep = kerf::untorn_triangles(sphere, kerf::CutSurfaces({cut}));
  std::vector<bool> kept(static_cast<std::size_t>(sphere.num_triangles()), false);
  for (const int f : keep) kept[static_cast<std::size_t>(f)] = true;
  int wrong = 0, dropped = 0;
  for (Eigen::Index f = 0; f < sphere.num_triangles(); ++f) {
    int above = 0;
    for (int a = 0; a < 3; ++a) above += sphere.vertices(sphere.triangles(f, a), 2) > 0.43 ? 1 : 0;
    const bool straddles = above == 1 || above == 2;
    wrong += straddles == kept[static_cast<std::size_t>(f)] ? 1 : 0;
    dropped += kept[static_cast<std::size_t>(f)] ? 0 : 1;
  }
  MESSAGE("sphere triangles ", sphere.num_triangles(), ", dropped ", dropped);
  CHECK(wrong == 0);
  CHECK(dropped > 0);
  CHECK(kerf::keep_triangles(moved, keep).num_triangles() == static_cast<Eigen::Index>(keep.size()));

  // A sphere of radius 0.52 pokes out of the box's faces by up to 2 cm, also out of cut tets:
  // xfem_visual_displacement takes the field at the tet's clamped point, on that point's piece.
  // The clamped point moves a few cm at most, so away from the cut by 5 cm every vertex still
  // gets its own side's (constant, so exactly extrapolated) displacement.
  const kerf::TriangleSurface bulging = kerf::implicit_surface_mesh(
      [&](const Eigen::Vector3d& x) { return (x - centre).norm() - 0.52; }, centre, 0.6, kerf::implicit_surface_sizing(0.05));
  const kerf::VisualSurface outside(body.mesh, bulging);
  CHECK(outside.num_outside() > 0);
  const kerf::TriangleSurface moved_out = outside.deform(kerf::xfem_visual_displacement(body.model, u));
  double worst_outside = 0.0;
  for (Eigen::Index v = 0; v < bulging.num_vertices(); ++v) {
    const Eigen::Vector3d x = row(bulging.vertices, v);
    CHECK_FALSE(row(moved_out.vertices, v).hasNaN());
    if (std::abs(x.z() - 0.43) > 0.05) worst_outside = std::max(worst_outside, (row(moved_out.vertices, v) - x - side_value(x)).norm());
  }
  MESSAGE("bulging sphere: outside ", outside.num_outside(), " of ", bulging.num_vertices(), ", largest distance ", outside.largest_distance());
  CHECK(worst_outside < 1e-14);
}

TEST_CASE("chapter 8's skin: the torn triangles split along the cut, each part moved with its side, and no area lost") {
  // The box, cut and two-sided field of the case above, and its bulging sphere, whose vertices
  // lie up to 2 cm out of the box, also out of cut tets: there the clamped point of a cut tet
  // may lie across the cut (the case above measures only 5 cm away from it). CutSkin splits each
  // torn triangle along the cut and moves every corner of a split triangle, and every point
  // where the cut crosses an edge, with the field at a point of its own side inside the body.
  const kerf::TriangleSurface cut = level_cut();
  const support::CutBody body(kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {3, 3, 4}), {cut}, {1000.0, 0.3, 1.0});
  const Eigen::Vector3d centre(0.5, 0.5, 0.5);
  const Eigen::VectorXd u = two_sided_field(body);
  const kerf::TriangleSurface bulging = kerf::implicit_surface_mesh(
      [&](const Eigen::Vector3d& x) { return (x - centre).norm() - 0.52; }, centre, 0.6, kerf::implicit_surface_sizing(0.05));
  const kerf::VisualSurface visual(body.mesh, bulging);
  const kerf::PointLocator locator(body.mesh);
  const kerf::CutSkin skin(visual, kerf::CutSurfaces({cut}), locator);
  MESSAGE("torn triangles split ", skin.num_split(), ", dropped ", skin.num_dropped(), " of ", bulging.num_triangles());
  CHECK(skin.num_split() > 0);
  CHECK(skin.num_dropped() == 0); // a plane crosses a triangle through two edges or none

  // Unmoved, the skin covers the visual surface exactly: the area of the split parts is the torn
  // triangles' (which untorn_triangles drops).
  const auto area = [](const kerf::TriangleSurface& s) {
    double sum = 0.0;
    for (Eigen::Index f = 0; f < s.num_triangles(); ++f)
      sum += 0.5 * (row(s.vertices, s.triangles(f, 1)) - row(s.vertices, s.triangles(f, 0)))
                       .cross(row(s.vertices, s.triangles(f, 2)) - row(s.vertices, s.triangles(f, 0)))
                       .norm();
    return sum;
  };
  const kerf::TriangleSurface at_rest = skin.deform([](int, const Eigen::Vector3d&) { return Eigen::Vector3d::Zero(); });
  CHECK(area(at_rest) == kerf_test::relative(area(bulging), 1e-12));
  CHECK(area(kerf::keep_triangles(bulging, kerf::untorn_triangles(bulging, kerf::CutSurfaces({cut})))) < 0.99 * area(bulging));

  // Each side's skin is closed along the rim: the two triangles of a crossed edge share its point
  // for each side, so every edge is shared by two triangles but the rim's own, which join two
  // of those points (one triangle each: the cut's walls are drawn apart).
  std::map<std::pair<int, int>, int> edge_uses;
  for (Eigen::Index f = 0; f < at_rest.num_triangles(); ++f)
    for (int a = 0; a < 3; ++a) {
      const int i = at_rest.triangles(f, a), j = at_rest.triangles(f, (a + 1) % 3);
      ++edge_uses[{std::min(i, j), std::max(i, j)}];
    }
  int rim_edges = 0, open_edges = 0;
  for (const auto& [edge, uses] : edge_uses) {
    const bool on_rim = edge.first >= bulging.num_vertices() && edge.second >= bulging.num_vertices();
    rim_edges += on_rim ? 1 : 0;
    open_edges += !on_rim && uses != 2 ? 1 : 0;
    if (on_rim) CHECK(uses == 1);
  }
  CHECK(rim_edges > 0);
  CHECK(open_edges == 0);

  // Opened: every corner of every triangle of the skin moves with the side of that triangle.
  const kerf::TriangleSurface moved = skin.deform(kerf::xfem_visual_displacement(body.model, u));
  REQUIRE(moved.num_vertices() == at_rest.num_vertices());
  double worst = 0.0;
  for (Eigen::Index f = 0; f < moved.num_triangles(); ++f) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (int a = 0; a < 3; ++a) centroid += row(at_rest.vertices, at_rest.triangles(f, a)) / 3.0;
    for (int a = 0; a < 3; ++a) {
      const Eigen::Index v = moved.triangles(f, a);
      worst = std::max(worst, (row(moved.vertices, v) - row(at_rest.vertices, v) - side_value(centroid)).norm());
    }
  }
  CHECK(worst < 1e-14);
}
