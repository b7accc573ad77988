// The walls of an opened cut (xfem/cut_faces.hpp): a tilted plane through the unit box, each
// side moved away from it by d along its normal (the field examples/07_visual_surface_study.cpp
// prescribes for its picture, chapter 4's u_i and a_k). Each side's wall then lies on the plane
// shifted by +-d, faces into the gap, and the two walls together have twice the area of the cut
// inside the body; not moved, both walls lie on the cut plane.
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/xfem/cut_faces.hpp"

#include "chapter_07/tilted_plane_cut.hpp"
#include "support/cut_body.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace {

using namespace tilted_cut;

// What the walls are: per side (+1 the wall at height +d, -1 at -d) the area, the largest
// distance of a corner from its plane, and the largest |n_f - expected| of a unit normal.
struct Walls {
  double area_above = 0.0, area_below = 0.0, off_plane = 0.0, normal_error = 0.0;
  int triangles = 0, unassigned = 0;
};

Walls measure_walls(const kerf::TriangleSurface& s, double d) {
  Walls walls;
  walls.triangles = static_cast<int>(s.num_triangles());
  const Eigen::Vector3d n = plane_normal();
  for (Eigen::Index f = 0; f < s.num_triangles(); ++f) {
    const Eigen::Vector3d x0 = s.vertices.row(s.triangles(f, 0)), x1 = s.vertices.row(s.triangles(f, 1)),
                          x2 = s.vertices.row(s.triangles(f, 2));
    const Eigen::Vector3d area_vector = 0.5 * (x1 - x0).cross(x2 - x0);
    const double centre = height((x0 + x1 + x2) / 3.0);
    // The upper side moved up: its wall is at +d and faces down into the gap, -n.
    const int side = d == 0.0 ? (area_vector.dot(n) < 0.0 ? 1 : -1) : (centre > 0.0 ? 1 : -1);
    if (d != 0.0 && std::abs(std::abs(centre) - d) > 0.5 * d) ++walls.unassigned;
    for (const Eigen::Vector3d& x : {x0, x1, x2}) walls.off_plane = std::max(walls.off_plane, std::abs(height(x) - side * d));
    if (area_vector.norm() > 0.0) walls.normal_error = std::max(walls.normal_error, (area_vector.normalized() + side * n).norm());
    (side > 0 ? walls.area_above : walls.area_below) += area_vector.norm();
  }
  return walls;
}

} // namespace

TEST_CASE("cut faces: an opened plane cut has one wall per side on the plane shifted by +-d, facing the gap, each of the cut's area") {
  const support::CutBody body(kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {4, 4, 4}), {tilted_plane()}, kerf::LinearMaterial{});
  REQUIRE(body.enrichment.num_enrichments() > 0);
  const double d = 0.015;
  const kerf::TriangleSurface faces = kerf::cut_face_surface(body.model, separated_sides(body, d));
  REQUIRE(faces.num_triangles() > 0);
  const Walls walls = measure_walls(faces, d);
  MESSAGE("opened by 2 x " << d << " m: " << walls.triangles << " triangles, areas " << walls.area_above << " and " << walls.area_below
                           << " m^2 (cut " << area_in_box() << " m^2, relative errors " << walls.area_above / area_in_box() - 1.0 << " and "
                           << walls.area_below / area_in_box() - 1.0 << "), largest distance from the shifted plane " << walls.off_plane
                           << " m, largest normal error " << walls.normal_error);
  CHECK(walls.unassigned == 0);
  // The pieces' polygons are the clipped plane, moved by an affine field that is a translation
  // on each side: round-off of coordinates of order 1 (measured 7e-17 m).
  CHECK(walls.off_plane < 1e-13);
  CHECK(walls.normal_error < 1e-10); // measured 8e-16
  // Each wall covers the cut inside the body once: the polygons of one side tile it, without
  // gap or overlap (sum over 256 triangles: round-off).
  CHECK(walls.area_above == kerf_test::relative(area_in_box(), 1e-12));
  CHECK(walls.area_below == kerf_test::relative(area_in_box(), 1e-12));
  CHECK(walls.area_above + walls.area_below == kerf_test::relative(2.0 * area_in_box(), 1e-12));
}

TEST_CASE("cut faces: with no displacement both walls lie on the cut plane, back to back") {
  const support::CutBody body(kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {4, 4, 4}), {tilted_plane()}, kerf::LinearMaterial{});
  const kerf::TriangleSurface faces = kerf::cut_face_surface(body.model, Eigen::VectorXd::Zero(3 * body.model.num_dof_nodes()));
  const Walls walls = measure_walls(faces, 0.0);
  MESSAGE("closed: largest distance from the plane " << walls.off_plane << " m");
  CHECK(walls.off_plane < 1e-13); // the clipped polygons' corners, on the plane to round-off (measured 3e-17 m)
  CHECK(walls.normal_error < 1e-10);
  CHECK(walls.area_above == kerf_test::relative(area_in_box(), 1e-12));
  CHECK(walls.area_below == kerf_test::relative(area_in_box(), 1e-12));
}

TEST_CASE("cut faces: a body with no cut, or a cut that ends inside every tet it meets, has no walls") {
  const support::CutBody uncut(kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {2, 2, 2}), {}, kerf::LinearMaterial{});
  CHECK(kerf::cut_face_surface(uncut.model, Eigen::VectorXd::Zero(3 * uncut.model.num_dof_nodes())).num_triangles() == 0);
  // A small square inside one tet column's cell, 0.1 m wide: it meets tets but separates no
  // node's support, so no tet is split and nothing opens.
  const kerf::TriangleSurface small = kerf::rectangle_surface(kerf::RectangleCut({0.2, 0.2, 0.23}, {0.1, 0, 0}, {0, 0.1, 0}));
  const support::CutBody inside(kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {2, 2, 2}), {small}, kerf::LinearMaterial{});
  REQUIRE(inside.enrichment.num_enrichments() == 0);
  CHECK(kerf::cut_face_surface(inside.model, Eigen::VectorXd::Zero(3 * inside.model.num_dof_nodes())).num_triangles() == 0);
}
