// The sheet a blade leaves (cut/cut_sheet.hpp): which of the edges offered to it are kept (the
// quad_length rule, `force`), the refusal of quads that fold back over the cut (a trembling
// blade), and the sheet as a cut surface: vertex 2 k is edge k's start, two triangles per kept
// quad, a strip that passes check_triangle_surface unchanged with all normals to one side.
#include "kerf/cut/cut_sheet.hpp"
#include "kerf/mesh/check_triangle_surface.hpp"

#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace {

// A straight blade: its edge runs from `origin + s motion` to `origin + edge + s motion`.
struct StraightBlade {
  Eigen::Vector3d origin, edge, motion;
  kerf::BladeEdge at(double s) const { return {origin + s * motion, origin + edge + s * motion}; }
};

// The blade of these tests: a 1.3 m edge, tilted, moving along a unit direction
// perpendicular to it, so that s is the distance it has moved (m).
StraightBlade tilted_blade() {
  const Eigen::Vector3d edge = Eigen::Vector3d(0.2, 0.3, 1.0).normalized() * 1.3;
  const Eigen::Vector3d motion = edge.cross(Eigen::Vector3d(0.1, 1.0, 0.0)).normalized();
  return {Eigen::Vector3d(-0.3, 0.4, -0.2), edge, motion};
}

// The unit normal (x1 - x0) x (x2 - x0) / |...| of triangle f.
Eigen::Vector3d unit_normal(const kerf::TriangleSurface& s, Eigen::Index f) {
  const Eigen::Vector3d x0 = s.vertices.row(s.triangles(f, 0)), x1 = s.vertices.row(s.triangles(f, 1)),
                        x2 = s.vertices.row(s.triangles(f, 2));
  return (x1 - x0).cross(x2 - x0).normalized();
}

} // namespace

TEST_CASE("cut sheet: a quad_length that is not a positive length is refused") {
  CHECK_THROWS_AS(kerf::CutSheet(0.0), std::invalid_argument);
  CHECK_THROWS_AS(kerf::CutSheet(-0.1), std::invalid_argument);
  CHECK_THROWS_AS(kerf::CutSheet(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
  CHECK_THROWS_AS(kerf::CutSheet(std::numeric_limits<double>::infinity()), std::invalid_argument);
}

TEST_CASE("cut sheet: an edge is kept once an end has moved quad_length from the last kept one, or when forced") {
  const StraightBlade blade = tilted_blade();
  kerf::CutSheet sheet(0.1);
  CHECK(sheet.empty());
  // The first edge starts the sheet and sweeps nothing.
  CHECK(sheet.offer(blade.at(0.0)).empty());
  CHECK_FALSE(sheet.empty());
  CHECK(sheet.num_edges() == 1);
  // Moves shorter than 0.1 m from the kept edge are not kept (each is measured from edge 0,
  // not from the last offer: 0.09 m is 0.03 m past the offer before it, and still not kept).
  for (const double s : {0.03, 0.06, 0.09}) {
    CHECK(sheet.offer(blade.at(s)).empty());
    CHECK(sheet.num_edges() == 1);
  }
  // 0.12 m: kept, with swept_quad's two triangles.
  CHECK(sheet.offer(blade.at(0.12)).size() == 2);
  CHECK(sheet.num_edges() == 2);
  CHECK(sheet.num_triangles() == 2);
  CHECK((sheet.last_edge().start - blade.at(0.12).start).norm() == 0.0);
  // A move of 0.05 m is kept only when forced (the blade leaves the body, the path ends).
  CHECK(sheet.offer(blade.at(0.17)).empty());
  CHECK(sheet.num_edges() == 2);
  CHECK(sheet.offer(blade.at(0.17), true).size() == 2);
  CHECK(sheet.num_edges() == 3);
  // Forced, but not moved at all: nothing to sweep, nothing kept.
  CHECK(sheet.offer(blade.at(0.17), true).empty());
  CHECK(sheet.num_edges() == 3);
  // One end far enough suffices: the blade pivots about its start, its end moving 0.15 m.
  const kerf::BladeEdge last = sheet.last_edge();
  const kerf::BladeEdge pivoted{last.start, last.end + 0.15 * blade.motion};
  CHECK_FALSE(sheet.offer(pivoted).empty());
  CHECK(sheet.num_edges() == 4);
  CHECK(sheet.num_refused() == 0);
}

TEST_CASE("cut sheet: a trembling blade adds nothing until it moves forward past its last edge") {
  const StraightBlade blade = tilted_blade();
  kerf::CutSheet sheet(0.1);
  for (const double s : {0.0, 0.15, 0.3}) sheet.offer(blade.at(s));
  REQUIRE(sheet.num_edges() == 3);
  REQUIRE(sheet.num_triangles() == 4);
  // Back over the cut: 0.15 m back is far enough to be a quad, but it folds back: refused.
  CHECK(sheet.offer(blade.at(0.15)).empty());
  CHECK(sheet.num_refused() == 1);
  // 0.05 m back: too short to be a quad at all, so not counted as refused.
  CHECK(sheet.offer(blade.at(0.25)).empty());
  CHECK(sheet.num_refused() == 1);
  // Further back, and back again with force: refused both times.
  CHECK(sheet.offer(blade.at(0.0)).empty());
  CHECK(sheet.offer(blade.at(0.18), true).empty());
  CHECK(sheet.num_refused() == 3);
  // Forward again, but not yet quad_length past the last kept edge (s = 0.3): nothing.
  CHECK(sheet.offer(blade.at(0.37)).empty());
  CHECK(sheet.num_edges() == 3);
  CHECK(sheet.num_triangles() == 4);
  // Past it by more than 0.1 m: the sheet grows again, from its last edge.
  CHECK(sheet.offer(blade.at(0.42)).size() == 2);
  CHECK(sheet.num_edges() == 4);
  CHECK(sheet.num_triangles() == 6);
  CHECK(sheet.num_refused() == 3);
  // The trembling left no trace: the sheet is the one a blade moving straight to 0.42 leaves.
  kerf::CutSheet straight(0.1);
  for (const double s : {0.0, 0.15, 0.3, 0.42}) straight.offer(blade.at(s));
  const kerf::TriangleSurface a = sheet.surface(), b = straight.surface();
  CHECK(a.vertices == b.vertices);
  CHECK(a.triangles == b.triangles);
}

TEST_CASE("cut sheet: the surface of a translating blade is a strip of 2 triangles per quad, checked, all normals to one side") {
  const StraightBlade blade = tilted_blade();
  kerf::CutSheet sheet(0.1);
  std::vector<kerf::BladeEdge> kept;
  // 40 frames of 0.0173 m: every sixth (0.1038 m) is kept; the last is forced.
  for (int frame = 0; frame <= 40; ++frame) {
    const kerf::BladeEdge edge = blade.at(0.0173 * frame);
    const int before = sheet.num_edges();
    sheet.offer(edge, frame == 40);
    if (sheet.num_edges() > before) kept.push_back(edge);
  }
  const int quads = sheet.num_edges() - 1;
  CHECK(sheet.num_edges() == static_cast<int>(kept.size()));
  CHECK(quads == 7); // frames 0, 6, ..., 36, and 40 forced
  CHECK(sheet.num_triangles() == 2 * quads);
  CHECK(sheet.num_refused() == 0);

  kerf::TriangleSurface surface = sheet.surface();
  REQUIRE(surface.num_vertices() == 2 * sheet.num_edges());
  REQUIRE(surface.num_triangles() == 2 * quads);
  // Vertex 2 k is edge k's start, 2 k + 1 its end: the very positions offered.
  for (int k = 0; k < sheet.num_edges(); ++k) {
    CHECK((surface.vertices.row(2 * k).transpose() - kept[static_cast<std::size_t>(k)].start).norm() == 0.0);
    CHECK((surface.vertices.row(2 * k + 1).transpose() - kept[static_cast<std::size_t>(k)].end).norm() == 0.0);
  }
  // Each quad's triangles use the corners of its own two edges only.
  for (Eigen::Index f = 0; f < surface.num_triangles(); ++f) {
    const int k = static_cast<int>(f / 2);
    for (int c = 0; c < 3; ++c) {
      CHECK(surface.triangles(f, c) >= 2 * k);
      CHECK(surface.triangles(f, c) <= 2 * k + 3);
    }
  }
  // For a translating blade every normal is the edge's direction crossed with the motion. The
  // triangles are flat and their corners exact positions, so the normals agree to round-off
  // (measured 1e-16).
  const Eigen::Vector3d expected = blade.edge.cross(blade.motion).normalized();
  double worst = 0.0;
  for (Eigen::Index f = 0; f < surface.num_triangles(); ++f) worst = std::max(worst, (unit_normal(surface, f) - expected).norm());
  MESSAGE("translating blade: largest |n_f - (e x d) / |e x d|| " << worst);
  CHECK(worst < 1e-12);

  // A cut surface as chapter 4 wants it: nothing to weld, drop or flip; one strip whose boundary
  // is the first and last edges and the two ends' paths, 2 per quad.
  const kerf::TriangleSurface unchanged = surface;
  const kerf::SurfaceCheck check = kerf::check_triangle_surface(surface, "sheet");
  CHECK(check.merged_vertices == 0);
  CHECK(check.unused_vertices == 0);
  CHECK(check.flipped_triangles == 0);
  CHECK(check.components == 1);
  CHECK(check.boundary_edges == 2 * quads + 2);
  CHECK(surface.vertices == unchanged.vertices);
  CHECK(surface.triangles == unchanged.triangles);
}

TEST_CASE("cut sheet: a blade pivoting about its start gains one triangle per kept edge, and its fixed end is welded by the check") {
  // swept_quad drops the second triangle of a quad whose start does not move (a0 = a1). The
  // numbering "vertex 2 k is edge k's start" then gives the fixed end one vertex per edge: the
  // strip is right once check_triangle_surface has welded them, which chapter 7 does not do
  // before handing the sheet to chapter 4 (the clipping is geometric and does not care; a
  // crack front found from the unwelded surface would have the fan's inner edges on it).
  const StraightBlade blade = tilted_blade();
  kerf::CutSheet sheet(0.1);
  const kerf::BladeEdge first = blade.at(0.0);
  for (int k = 0; k <= 4; ++k) {
    const Eigen::Matrix3d R = Eigen::AngleAxisd(0.1 * k, blade.edge.cross(blade.motion).normalized()).toRotationMatrix();
    const std::vector<kerf::SweptTriangle> gained = sheet.offer({first.start, first.start + R * (first.end - first.start)});
    CHECK(gained.size() == (k == 0 ? 0u : 1u));
  }
  CHECK(sheet.num_edges() == 5);
  CHECK(sheet.num_triangles() == 4);
  CHECK(sheet.num_refused() == 0);
  kerf::TriangleSurface surface = sheet.surface();
  const kerf::SurfaceCheck check = kerf::check_triangle_surface(surface, "pivoting sheet");
  CHECK(check.merged_vertices == 4); // edges 1 .. 4's starts onto edge 0's
  CHECK(check.flipped_triangles == 0);
  CHECK(check.components == 1);
  CHECK(check.boundary_edges == 6); // a fan of 4 triangles: 2 sides and 4 outer edges
}

TEST_CASE("cut sheet: a blade that turns while it moves still leaves one consistently oriented strip") {
  // The edge turns 0.05 rad per kept quad about an axis along the motion, through a point
  // beyond its end (the tip goes round a wider arc than the start): the quads are not planar.
  const StraightBlade blade = tilted_blade();
  kerf::CutSheet sheet(0.1);
  const Eigen::Vector3d pivot = blade.origin + 1.5 * blade.edge;
  for (int k = 0; k <= 8; ++k) {
    const Eigen::Matrix3d R = Eigen::AngleAxisd(0.05 * k, blade.motion).toRotationMatrix();
    const Eigen::Vector3d shift = 0.12 * k * blade.motion;
    sheet.offer({pivot + R * (blade.origin - pivot) + shift, pivot + R * (blade.origin + blade.edge - pivot) + shift});
  }
  CHECK(sheet.num_edges() == 9);
  CHECK(sheet.num_triangles() == 16);
  CHECK(sheet.num_refused() == 0);
  kerf::TriangleSurface surface = sheet.surface();
  const kerf::SurfaceCheck check = kerf::check_triangle_surface(surface, "turning sheet");
  CHECK(check.merged_vertices == 0);
  CHECK(check.flipped_triangles == 0);
  CHECK(check.components == 1);
  // The normals turn with the blade (0.4 rad in all; a triangle of a non-planar quad tilts a
  // little more: the smallest cosine to the first quad's is 0.85, measured) and stay on one
  // side: no triangle folds back against its neighbour or against the first.
  const Eigen::Vector3d first = unit_normal(surface, 0);
  double smallest = 1.0;
  for (Eigen::Index f = 0; f < surface.num_triangles(); ++f) {
    smallest = std::min(smallest, unit_normal(surface, f).dot(first));
    if (f > 0) CHECK(unit_normal(surface, f).dot(unit_normal(surface, f - 1)) > 0.9);
  }
  MESSAGE("turning blade: smallest cosine of a normal to the first quad's " << smallest);
  CHECK(smallest > 0.0);
}
