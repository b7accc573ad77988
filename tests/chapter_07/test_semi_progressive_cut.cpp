// The semi-progressive cut (cut/semi_progressive_cut.hpp) and what drives it: the blade path
// (cut/blade_path.hpp) and the quad its edge sweeps (cut/swept_quad.hpp).
//
// The reference for "crossed" is chapter 4's exact clipping: a tet the sheet crosses is one
// cut_mesh_into_pieces splits into two pieces for the same sheet given as one surface. We check
// it for a full pass, a pass stopped mid-mesh (where the difference between "the blade is in the
// tet" and "the blade went through it" is the whole point), a trembling blade, and sheets through
// nodes and faces, where exact predicates decide what a touch means.
#include "kerf/cut/blade_path.hpp"
#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/cut/semi_progressive_cut.hpp"
#include "kerf/cut/swept_quad.hpp"
#include "kerf/mesh/box_mesh.hpp"

#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

// The unit cube in 6 x 6 x 6 cells, 1296 tets: every kind of tet of Kuhn's split, many times over,
// and chapter 4 clips it in a fraction of a second.
kerf::TetMesh unit_box() { return kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {6, 6, 6}); }

// A straight blade: its edge runs from `origin + s motion` to `origin + edge + s motion`.
struct StraightBlade {
  Eigen::Vector3d origin, edge, motion;
  kerf::BladeEdge at(double s) const { return {origin + s * motion, origin + edge + s * motion}; }
};

// Sweeps the blade from s0 to s1 in `steps` equal steps, one add_swept_triangles per step, and
// returns every tet that became crossed.
std::set<int> sweep(kerf::SemiProgressiveCut& cut, const StraightBlade& blade, double s0, double s1, int steps) {
  std::set<int> crossed;
  for (int k = 0; k < steps; ++k) {
    const double a = s0 + (s1 - s0) * k / steps, b = s0 + (s1 - s0) * (k + 1) / steps;
    for (const int t : cut.add_swept_triangles(kerf::swept_quad(blade.at(a), blade.at(b)))) CHECK(crossed.insert(t).second);
  }
  return crossed;
}

// Chapter 4's answer for one surface: the tets it splits into two or more pieces.
std::set<int> split_by_chapter_4(const kerf::TetMesh& mesh, const kerf::TriangleSurface& surface) {
  const kerf::MeshPieces pieces = kerf::cut_mesh_into_pieces(mesh, kerf::CutSurfaces({surface}));
  std::set<int> split;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    if (pieces.num_pieces(t) >= 2) split.insert(static_cast<int>(t));
  return split;
}

std::set<int> partially_cut_by_chapter_4(const kerf::TetMesh& mesh, const kerf::TriangleSurface& surface) {
  const kerf::MeshPieces pieces = kerf::cut_mesh_into_pieces(mesh, kerf::CutSurfaces({surface}));
  std::set<int> partial;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    if (pieces.state(t) == kerf::SurfaceCutState::partially_cut) partial.insert(static_cast<int>(t));
  return partial;
}

std::set<int> as_set(const std::vector<int>& v) { return {v.begin(), v.end()}; }

// A generic tilted plane through the cube, n = (1, 0.37, 0.21) normalised, a little off the
// centre; the blade's edge (along u) spans the cube and moves along v, both in the plane.
struct TiltedPlane {
  Eigen::Vector3d centre{0.513, 0.5, 0.5};
  Eigen::Vector3d normal = Eigen::Vector3d(1.0, 0.37, 0.21).normalized();
  Eigen::Vector3d u = normal.cross(Eigen::Vector3d::UnitZ()).normalized();
  Eigen::Vector3d v = normal.cross(u);
  // Half-widths of 1 > the cube's half-diagonal 0.87: the full sheet covers the whole section.
  StraightBlade blade() const { return {centre - u - v, 2.0 * u, 2.0 * v}; }
  // The sheet swept from s = 0 to s, as chapter 4's rectangle.
  kerf::TriangleSurface swept_rectangle(double s) const {
    const StraightBlade b = blade();
    return kerf::rectangle_surface(kerf::RectangleCut(b.origin, b.edge, s * b.motion));
  }
  double height(const Eigen::Vector3d& x) const { return normal.dot(x - centre); }
};

// The number of edges of tet t whose corners lie strictly on opposite sides of the plane.
int edges_across(const kerf::TetMesh& mesh, const TiltedPlane& plane, int t) {
  int n = 0;
  for (const auto& edge : kerf::tet_edge_corners)
    if (plane.height(mesh.nodes.row(mesh.tets(t, edge[0])).transpose()) * plane.height(mesh.nodes.row(mesh.tets(t, edge[1])).transpose()) < 0) ++n;
  return n;
}

double smallest_node_height(const kerf::TetMesh& mesh, const TiltedPlane& plane) {
  double smallest = std::numeric_limits<double>::infinity();
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) smallest = std::min(smallest, std::abs(plane.height(mesh.nodes.row(v).transpose())));
  return smallest;
}

} // namespace

TEST_CASE("a full planar pass crosses exactly the tets chapter 4's clipping splits in two") {
  const kerf::TetMesh mesh = unit_box();
  const TiltedPlane plane;
  // The plane is generic: no node within 1e-3 of it (the nearest is 3.4e-3 away), so no touch decides anything here.
  REQUIRE(smallest_node_height(mesh, plane) > 1e-3);
  kerf::SemiProgressiveCut cut(mesh);
  const std::set<int> crossed = sweep(cut, plane.blade(), 0.0, 1.0, 40);

  const std::set<int> split = split_by_chapter_4(mesh, plane.swept_rectangle(1.0));
  CHECK(split.size() > 100);
  CHECK(crossed == split);
  CHECK(as_set(cut.crossed_tets()) == crossed);
  CHECK(cut.num_nodes_on_sheet() == 0);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const int ti = static_cast<int>(t);
    // Every tet the plane passes through has all its cut edges crossed, 3 (a corner cut off) or 4 (2:2).
    CHECK(cut.num_crossed_edges(ti) == edges_across(mesh, plane, ti));
    CHECK(cut.tet_crossed(ti) == (edges_across(mesh, plane, ti) > 0));
    if (!cut.tet_crossed(ti)) continue;
    const std::vector<Eigen::Vector3d> points = cut.cut_points(ti);
    CHECK((points.size() == 3 || points.size() == 4));
    // The crossing points lie on the plane to round-off of unit coordinates (measured 3.2e-16).
    for (const Eigen::Vector3d& p : points) CHECK(std::abs(plane.height(p)) < 1e-14);
  }
}

TEST_CASE("a pass stopped mid-mesh crosses the tets wholly behind the blade's edge, not those the edge is in") {
  const kerf::TetMesh mesh = unit_box();
  const TiltedPlane plane;
  // The blade stops at s = 0.5137 of its travel: its edge then lies inside a row of tets.
  const double stop = 0.5137;
  kerf::SemiProgressiveCut cut(mesh);
  const std::set<int> crossed = sweep(cut, plane.blade(), 0.0, stop, 21);

  const kerf::TriangleSurface behind = plane.swept_rectangle(stop);
  CHECK(crossed == split_by_chapter_4(mesh, behind));
  // The tets the edge is inside (chapter 4: the cut covers area in them but leaves them whole)
  // have some, never all, of the edges the plane would cross, and are not crossed.
  const std::set<int> partial = partially_cut_by_chapter_4(mesh, behind);
  CHECK(partial.size() > 10);
  std::map<int, int> by_crossed_edges;
  for (const int t : partial) {
    CHECK_FALSE(cut.tet_crossed(t));
    CHECK(cut.num_crossed_edges(t) >= 1);
    CHECK(cut.num_crossed_edges(t) < edges_across(mesh, plane, t));
    ++by_crossed_edges[cut.num_crossed_edges(t)];
  }
  // Measured: 24 such tets, 7 with 1 crossed edge, 15 with 2, 2 with 3; 177 tets crossed.
  // Among them are tets of G's list L3 (3 crossed edges of a 2:2 split still missing its 4th):
  // Gutierrez's "cut at the third edge" would have split them with the blade still inside.
  CHECK(by_crossed_edges[3] > 0);
  // And a tet with crossed edges is either crossed or one the edge is in: nothing else.
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    if (cut.num_crossed_edges(static_cast<int>(t)) > 0 && !cut.tet_crossed(static_cast<int>(t))) CHECK(partial.count(static_cast<int>(t)) == 1);

  // Going on to the far side crosses the rest, and the union is the full pass's set.
  const std::set<int> rest = sweep(cut, plane.blade(), stop, 1.0, 19);
  std::set<int> all = crossed;
  all.insert(rest.begin(), rest.end());
  CHECK(all == split_by_chapter_4(mesh, plane.swept_rectangle(1.0)));
}

TEST_CASE("one tet split 2:2 is crossed at its fourth crossed edge, not its third") {
  kerf::TetMesh tet;
  tet.nodes.resize(4, 3);
  tet.nodes << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  tet.tets.resize(1, 4);
  tet.tets << 0, 1, 2, 3;
  // The plane x + y = 0.5 splits {0, 3} from {1, 2}; its section is a rectangle. The blade's edge
  // is tilted in the plane (0.3 u + z) and moves along u = (1, -1, 0)/sqrt 2, so it meets the four
  // crossing points one at a time: edge 2-3, 0-2, 1-3, then 0-1 (at u-offsets -0.50, -0.35, 0.20, 0.35).
  const Eigen::Vector3d u = Eigen::Vector3d(1, -1, 0).normalized();
  const Eigen::Vector3d edge = (0.3 * u + Eigen::Vector3d::UnitZ()).normalized() * 3.0;
  const Eigen::Vector3d start = Eigen::Vector3d(0.25, 0.25, 0.0) - 0.5 * edge;
  const StraightBlade blade{start - u, edge, u};
  kerf::SemiProgressiveCut cut(tet);
  // To u-offset 0.28 of the section's centre: between the third and the fourth point.
  CHECK(sweep(cut, blade, 0.0, 1.28, 8).empty());
  CHECK(cut.num_crossed_edges(0) == 3);
  CHECK_FALSE(cut.tet_crossed(0));
  CHECK(sweep(cut, blade, 1.28, 2.0, 4) == std::set<int>{0});
  CHECK(cut.num_crossed_edges(0) == 4);
  // The four points: the corners of the rectangle x + y = 0.5, z in [0, 0.5] (measured 2.2e-16 off).
  const std::vector<Eigen::Vector3d> points = cut.cut_points(0);
  REQUIRE(points.size() == 4);
  for (const Eigen::Vector3d& p : points) {
    CHECK(std::abs(p.x() + p.y() - 0.5) < 1e-15);
    CHECK((std::abs(p.z()) < 1e-15 || std::abs(p.z() - 0.5) < 1e-15));
  }
}

TEST_CASE("a blade stopped exactly on a tet's last crossing point has crossed it: swept triangles are closed") {
  kerf::TetMesh tet;
  tet.nodes.resize(4, 3);
  tet.nodes << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  tet.tets.resize(1, 4);
  tet.tets << 0, 1, 2, 3;
  // The plane z = 1/4 isolates corner 3; it crosses edges 0-3, 2-3 and 1-3 at x = 0, 0 and 3/4.
  // The edge runs along y and moves along x (all coordinates dyadic, so every test is exact).
  const StraightBlade blade{{-1, -1, 0.25}, {0, 3, 0}, {1, 0, 0}};
  kerf::SemiProgressiveCut cut(tet);
  CHECK(cut.add_swept_triangles(kerf::swept_quad(blade.at(0.0), blade.at(1.5))).empty()); // edge at x = 1/2
  CHECK(cut.num_crossed_edges(0) == 2);
  CHECK(cut.add_swept_triangles(kerf::swept_quad(blade.at(1.5), blade.at(1.75))) == std::vector<int>{0}); // at x = 3/4: on the point
  CHECK(cut.num_crossed_edges(0) == 3);
  CHECK(cut.edge_crossing(cut.tet_edges(0)[4]).point == Eigen::Vector3d(0.75, 0, 0.25)); // edge (1, 3), exact
}

TEST_CASE("the edge test alone: an edge against one triangle, through it, on its boundary, beside it, ending in it, in its plane") {
  // The triangle z = 1/4 over (0, 0), (2, 0), (0, 2); dyadic coordinates, so every answer is exact.
  const kerf::SweptTriangle triangle{Eigen::Vector3d(0, 0, 0.25), Eigen::Vector3d(2, 0, 0.25), Eigen::Vector3d(0, 2, 0.25)};
  const auto contact = [&](Eigen::Vector3d a, Eigen::Vector3d b) { return kerf::edge_triangle_contact(triangle, a, b); };
  // Through the inside: crossed a quarter of the way up.
  const kerf::EdgeTriangleContact inside = contact({0.5, 0.5, 0}, {0.5, 0.5, 1});
  CHECK(inside.crossed);
  CHECK(inside.parameter == 0.25);
  CHECK_FALSE(inside.end_on_sheet[0]);
  CHECK_FALSE(inside.end_on_sheet[1]);
  // Through the triangle's edge x + y = 2, and through its corner (2, 0): closed, so crossed.
  CHECK(contact({1, 1, 1}, {1, 1, 0}).crossed);
  CHECK(contact({1, 1, 1}, {1, 1, 0}).parameter == 0.75);
  CHECK(contact({2, 0, 0}, {2, 0, 0.5}).crossed);
  // Beside it, and not reaching its plane.
  CHECK_FALSE(contact({1.5, 1.5, 0}, {1.5, 1.5, 1}).crossed);
  CHECK_FALSE(contact({0.5, 0.5, 0}, {0.5, 0.5, 0.125}).crossed);
  CHECK(contact({1.5, 1.5, 0}, {1.5, 1.5, 1}).parameter == 0.0);
  // An end in the triangle is on the sheet, and the edge is not crossed there.
  const kerf::EdgeTriangleContact end_in = contact({0.5, 0.5, 1}, {0.5, 0.5, 0.25});
  CHECK_FALSE(end_in.crossed);
  CHECK_FALSE(end_in.end_on_sheet[0]);
  CHECK(end_in.end_on_sheet[1]);
  // An end in the plane but outside the triangle is not.
  CHECK_FALSE(contact({3, 3, 0.25}, {3, 3, 1}).end_on_sheet[0]);
  // An edge in the triangle (in its plane): both ends on the sheet, not crossed.
  const kerf::EdgeTriangleContact in_plane = contact({0.25, 0.25, 0.25}, {1, 0.5, 0.25});
  CHECK_FALSE(in_plane.crossed);
  CHECK(in_plane.end_on_sheet[0]);
  CHECK(in_plane.end_on_sheet[1]);
}

TEST_CASE("the tet test alone: a tet's corners separated by its crossed edges and its corners on the sheet, or not") {
  // Edges in the order of tet_edge_corners: (0,1) (1,2) (0,2) (0,3) (1,3) (2,3).
  const std::array<bool, 4> none_on{false, false, false, false};
  CHECK_FALSE(kerf::tet_corners_separated({false, false, false, false, false, false}, none_on));
  // Corner 3 cut off by its three edges; corners {0, 3} from {1, 2} by the four edges between them.
  CHECK(kerf::tet_corners_separated({false, false, false, true, true, true}, none_on));
  CHECK(kerf::tet_corners_separated({true, false, true, false, true, true}, none_on));
  // Three of those four (G's third edge; 0-3 and 1-2 still joined through 2-3): not yet.
  CHECK_FALSE(kerf::tet_corners_separated({true, false, true, false, true, false}, none_on));
  // A sheet through corner 0 crossing the opposite face's edges 1-2 and 1-3 cuts corner 1 off 2 and 3.
  CHECK(kerf::tet_corners_separated({false, true, false, false, true, false}, {true, false, false, false}));
  // A sheet that only grazes corner 0 does not; one through the edge 0-1 and crossing 2-3 does.
  CHECK_FALSE(kerf::tet_corners_separated({false, false, false, false, false, false}, {true, false, false, false}));
  CHECK(kerf::tet_corners_separated({false, false, false, false, false, true}, {true, true, false, false}));
  // Three corners on the sheet leave one group: a sheet in a face crosses nothing.
  CHECK_FALSE(kerf::tet_corners_separated({false, false, false, false, false, false}, {true, true, true, false}));
}

TEST_CASE("a trembling blade crosses no edge twice: forward, back and forward again change nothing") {
  const kerf::TetMesh mesh = unit_box();
  const TiltedPlane plane;
  const StraightBlade blade = plane.blade();
  kerf::SemiProgressiveCut cut(mesh);
  const std::set<int> first = sweep(cut, blade, 0.0, 0.6, 12);
  REQUIRE(!first.empty());
  std::map<int, Eigen::Vector3d> points;
  for (int e = 0; e < cut.num_edges(); ++e)
    if (cut.edge_crossed(e)) points[e] = cut.edge_crossing(e).point;
  const auto crossed_before = cut.crossed_tets();

  // The same quads back and forward again.
  CHECK(sweep(cut, blade, 0.6, 0.0, 12).empty());
  CHECK(sweep(cut, blade, 0.0, 0.6, 12).empty());
  // Back once more with the hand shaken off the plane by a quarter of the nearest node's
  // distance: the sheet crosses the same edges at other points, and the first points stay. It
  // stops short of the front (s = 0.5, not 0.6): an edge across the plane has its ends at least
  // 4 shakes apart in height, so its crossing point moves at most a quarter of its length (0.07)
  // along the plane, less than the 0.2 to the front, and no edge beyond the front comes in reach.
  const double shake = 0.25 * smallest_node_height(mesh, plane);
  StraightBlade shaken = blade;
  shaken.origin += shake * plane.normal;
  CHECK(sweep(cut, shaken, 0.5, 0.0, 7).empty());

  CHECK(cut.crossed_tets() == crossed_before);
  CHECK(cut.num_crossed_edges_total() == static_cast<int>(points.size()));
  for (const auto& [e, p] : points) CHECK(cut.edge_crossing(e).point == p); // bitwise: recorded once
}

TEST_CASE("degenerate sheets: through a row of nodes, in a plane of faces, grazing one node") {
  const kerf::TetMesh mesh = unit_box();
  // Blades with dyadic coordinates, so that the sheets pass through nodes exactly (no rounding).

  SUBCASE("through a row of nodes: the row is on the sheet, and the crossed tets are chapter 4's split ones") {
    // The plane through the row y = z = 0.5 (7 nodes along x) with in-plane motion m = (0, -3/8, 1):
    // no other node lies on it (j + 3k/8 = 0 has no solution with |j|, |k| <= 3 but 0).
    const Eigen::Vector3d m(0, -0.375, 1);
    const StraightBlade blade{Eigen::Vector3d(-0.5, 0.5, 0.5) - m, {2, 0, 0}, m};
    kerf::SemiProgressiveCut cut(mesh);
    const std::set<int> crossed = sweep(cut, blade, 0.0, 2.0, 16);
    CHECK(cut.num_nodes_on_sheet() == 7);
    CHECK(crossed == split_by_chapter_4(mesh, kerf::rectangle_surface(kerf::RectangleCut(blade.origin, blade.edge, 2.0 * m))));
    // Some crossed tets have a corner on the sheet (cut through the corner: 2 crossed edges and the corner).
    int through_corner = 0;
    for (const int t : crossed)
      for (int a = 0; a < 4; ++a) through_corner += cut.node_on_sheet(mesh.tets(t, a)) ? 1 : 0;
    CHECK(through_corner > 0);
    // A crossed tet's cut points: 3 (a corner cut off) or 4 (2:2) crossing points, or, with corners
    // on the sheet, 2 crossings and the corner, or 1 crossing and the two corners of an edge on the row.
    for (const int t : crossed) {
      int on_sheet = 0;
      for (int a = 0; a < 4; ++a) on_sheet += cut.node_on_sheet(mesh.tets(t, a)) ? 1 : 0;
      const std::size_t points = cut.cut_points(t).size();
      CHECK((on_sheet == 0 ? points == 3 || points == 4 : points == 3));
      CHECK(cut.num_crossed_edges(t) + on_sheet == static_cast<int>(points));
    }
    // No edge along the row is crossed: it lies in the sheet.
    for (int e = 0; e < cut.num_edges(); ++e) {
      const auto [a, b] = cut.edge_nodes(e);
      if (cut.node_on_sheet(a) && cut.node_on_sheet(b)) CHECK_FALSE(cut.edge_crossed(e));
    }
  }

  SUBCASE("in a plane of faces: its 49 nodes are on the sheet, no edge and no tet is crossed") {
    // z = 0.5 is the grid plane k = 3; Kuhn's tets have no edge across a grid plane.
    const StraightBlade blade{{-0.5, -0.5, 0.5}, {2, 0, 0}, {0, 1, 0}};
    kerf::SemiProgressiveCut cut(mesh);
    CHECK(sweep(cut, blade, 0.0, 2.0, 16).empty());
    CHECK(cut.num_nodes_on_sheet() == 49);
    CHECK(cut.num_crossed_edges_total() == 0);
    CHECK(cut.crossed_tets().empty());
    // Chapter 4 agrees that no tet is split: such a cut separates tets only across the faces it
    // lies in (MeshPieces' glue), which an edge-based test does not see: documented in the header.
    const kerf::MeshPieces pieces =
        kerf::cut_mesh_into_pieces(mesh, kerf::CutSurfaces({kerf::rectangle_surface(kerf::RectangleCut(blade.origin, blade.edge, 2.0 * blade.motion))}));
    CHECK(pieces.count(kerf::SurfaceCutState::completely_cut) == 0);
    CHECK(pieces.count(kerf::SurfaceCutState::touched) > 0);
  }

  SUBCASE("grazing one node: the box's corner is on the sheet, nothing is crossed") {
    // The plane x + y + z = 0 touches the cube at the node (0, 0, 0) only; the triangle's centroid is that node.
    kerf::SemiProgressiveCut cut(mesh);
    CHECK(cut.add_swept_triangles({{Eigen::Vector3d(0.25, 0.25, -0.5), Eigen::Vector3d(-0.5, 0.25, 0.25), Eigen::Vector3d(0.25, -0.5, 0.25)}}).empty());
    CHECK(cut.num_nodes_on_sheet() == 1);
    CHECK(cut.node_on_sheet(0));
    CHECK(cut.num_crossed_edges_total() == 0);
  }

  SUBCASE("through one interior node: crossed tets around it are chapter 4's split ones") {
    // The plane through the centre node with normal (1, 5/16, 9/128), spanned by two dyadic directions.
    const Eigen::Vector3d c(0.5, 0.5, 0.5), u(0.3125, -1, 0), w(0.0703125, 0, -1);
    kerf::TriangleSurface sheet;
    sheet.vertices.resize(3, 3);
    sheet.vertices << (c + 4 * u).transpose(), (c + 4 * w).transpose(), (c - 4 * u - 4 * w).transpose();
    sheet.triangles.resize(1, 3);
    sheet.triangles << 0, 1, 2;
    kerf::SemiProgressiveCut cut(mesh);
    const std::set<int> crossed = as_set(
        cut.add_swept_triangles({{sheet.vertices.row(0).transpose(), sheet.vertices.row(1).transpose(), sheet.vertices.row(2).transpose()}}));
    CHECK(cut.num_nodes_on_sheet() == 1);
    CHECK(crossed == split_by_chapter_4(mesh, sheet));
    int around_centre = 0;
    for (const int t : crossed)
      for (int a = 0; a < 4; ++a) around_centre += mesh.tets(t, a) == 171 ? 1 : 0; // node (3, 3, 3) = 3 + 7 * 3 + 49 * 3
    CHECK(around_centre > 0);
  }
}

TEST_CASE("BladePath refuses bad keyframes in one line each, and interpolates the edge") {
  const auto key = [](double t, Eigen::Vector3d a, Eigen::Vector3d b) { return kerf::BladeKeyframe{t, {a, b}}; };
  const Eigen::Vector3d o(0, 0, 0), z(0, 0, 1);
  const auto message = [](const std::vector<kerf::BladeKeyframe>& keys) {
    try {
      kerf::BladePath path(keys);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(message({}) == "BladePath: 0 keyframes given, at least 2 are needed");
  CHECK(message({key(0, o, z)}) == "BladePath: 1 keyframe given, at least 2 are needed");
  CHECK(message({key(0, o, z), key(1, o, {0, std::nan(""), 1})}) == "BladePath: keyframe 1 has a non-finite time or position");
  CHECK(message({key(0, o, z), key(std::numeric_limits<double>::infinity(), o, z)}) == "BladePath: keyframe 1 has a non-finite time or position");
  CHECK(message({key(0, o, z), key(0.5, o, z), key(0.5, o, z)}) == "BladePath: keyframe 2's time 0.5 s is not after keyframe 1's (0.5 s)");
  CHECK(message({key(0, o, z), key(1, o, z), key(0.25, o, z)}) == "BladePath: keyframe 2's time 0.25 s is not after keyframe 1's (1 s)");
  CHECK(message({key(0, z, z), key(1, o, z)}) == "BladePath: keyframe 0's edge has zero length");

  const kerf::BladePath path({key(0, o, z), key(2, {1, 0, 0}, {1, 0, 1}), key(3, {1, 1, 0}, {1, 1, 2})});
  CHECK(path.duration() == 3.0);
  CHECK(path.start_time() == 0.0);
  CHECK(path.end_time() == 3.0);
  // Halfway through the first step, a quarter of the way... and clamped outside; exact in binary.
  CHECK(path.edge_at(1.0).start == Eigen::Vector3d(0.5, 0, 0));
  CHECK(path.edge_at(1.0).end == Eigen::Vector3d(0.5, 0, 1));
  CHECK(path.edge_at(2.5).start == Eigen::Vector3d(1, 0.5, 0));
  CHECK(path.edge_at(2.5).end == Eigen::Vector3d(1, 0.5, 1.5));
  CHECK(path.edge_at(2.0).end == Eigen::Vector3d(1, 0, 1));
  CHECK(path.edge_at(-1.0).end == z);
  CHECK(path.edge_at(7.0).end == Eigen::Vector3d(1, 1, 2));
}

TEST_CASE("the swept quad: empty for a blade at rest or sliding along itself, two triangles of normal edge x motion for a translation") {
  const kerf::BladeEdge edge{{0, 0, 0}, {0, 0, 1}};
  CHECK(kerf::swept_quad(edge, edge).empty());
  CHECK(kerf::swept_quad(edge, {{0, 0, 0.25}, {0, 0, 1.25}}).empty());

  const Eigen::Vector3d d(0.5, 0, 0);
  const std::vector<kerf::SweptTriangle> quad = kerf::swept_quad(edge, {edge.start + d, edge.end + d});
  REQUIRE(quad.size() == 2);
  const Eigen::Vector3d expected = (edge.end - edge.start).cross(d); // (0, 0.5, 0): twice the area of each half
  for (const kerf::SweptTriangle& t : quad) CHECK(((t[1] - t[0]).cross(t[2] - t[0]) - expected).norm() == 0.0);

  // A blade pivoting about its start sweeps one triangle.
  const std::vector<kerf::SweptTriangle> fan = kerf::swept_quad(edge, {{0, 0, 0}, {1, 0, 0}});
  REQUIRE(fan.size() == 1);
  CHECK(((fan[0][1] - fan[0][0]).cross(fan[0][2] - fan[0][0]) - Eigen::Vector3d(0, 1, 0)).norm() == 0.0);
}
