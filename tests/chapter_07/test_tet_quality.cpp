// tet_min_dihedral_angle and tet_radius_ratio on tets whose answers we know in closed form: the
// regular tet, the corner of the cube, a sliver and a needle, and the same tets moved, turned,
// scaled and inverted.
#include "kerf/mesh/tet_quality.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

namespace {

using Corners = Eigen::Matrix<double, 4, 3>;

Corners regular_tet() {
  Corners X;
  X << 1, 1, 1, -1, 1, -1, 1, -1, -1, -1, -1, 1; // alternate corners of a cube, all edges 2 sqrt 2, listed positively
  return X;
}

Corners corner_tet() {
  Corners X;
  X << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  return X;
}

// x -> s Q x + t, row by row.
Corners moved(const Corners& X, double s) {
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  Corners Y;
  for (int a = 0; a < 4; ++a) Y.row(a) = (s * Q * X.row(a).transpose() + Eigen::Vector3d(3, -1, 2)).transpose();
  return Y;
}

} // namespace

TEST_CASE("the regular tet has dihedral angles arccos(1/3) and radius ratio 1, wherever it is and however large") {
  const double regular_angle = std::acos(1.0 / 3.0) * 180.0 / std::numbers::pi; // 70.5288 degrees
  for (const double s : {1.0, 1e-3, 50.0}) {
    CAPTURE(s);
    const Corners X = moved(regular_tet(), s);
    CHECK(kerf::tet_min_dihedral_angle(X) == kerf_test::relative(regular_angle, 1e-12));
    CHECK(kerf::tet_radius_ratio(X) == kerf_test::relative(1.0, 1e-12));
  }
}

TEST_CASE("the corner of the cube: smallest dihedral angle arccos(1/sqrt 3), radius ratio sqrt 3 - 1") {
  // Its three edges at the origin have 90 degrees; the three edges of the slanted face have the
  // angle between the normals (1,1,1)/sqrt 3 and e_i subtracted from 180, arccos(1/sqrt 3) = 54.74.
  // r = 3 V / A = 1/2 / (3/2 + sqrt(3)/2), R = sqrt(3)/2, so 3 r / R = sqrt 3 - 1 = 0.732.
  const Corners X = moved(corner_tet(), 2.0);
  CHECK(kerf::tet_min_dihedral_angle(X) == kerf_test::relative(std::acos(1.0 / std::sqrt(3.0)) * 180.0 / std::numbers::pi, 1e-12));
  CHECK(kerf::tet_radius_ratio(X) == kerf_test::relative(std::sqrt(3.0) - 1.0, 1e-12));
}

TEST_CASE("a sliver and a needle score near zero, an inverted tet keeps its angles but has radius ratio 0") {
  // The sliver: the four corners of a unit square, two opposite ones lifted by eps. Its edges are
  // all about 1, yet it is flat: dihedral angles near 0 (and 180), radius ratio O(eps).
  const double eps = 1e-3;
  Corners sliver;
  sliver << 0, 0, 0, 1, 1, 0, 1, 0, eps, 0, 1, eps;
  if ((sliver.row(1) - sliver.row(0)).dot((sliver.row(2) - sliver.row(0)).cross(sliver.row(3) - sliver.row(0))) < 0.0)
    sliver.row(1).swap(sliver.row(2));
  CHECK(kerf::tet_min_dihedral_angle(sliver) < 0.2);
  CHECK(kerf::tet_radius_ratio(sliver) < 0.01);
  // The needle: a unit triangle with its apex 1000 away.
  Corners needle = corner_tet();
  needle(3, 2) = 1000.0;
  CHECK(kerf::tet_radius_ratio(needle) < 0.01);
  // Swapping two corners inverts the tet: the shape (and so its angles) stays, the radius ratio
  // says 0 so that an inverted tet can never pass for a good one.
  Corners inverted = moved(regular_tet(), 1.0);
  inverted.row(1).swap(inverted.row(2));
  CHECK(kerf::tet_min_dihedral_angle(inverted) == kerf_test::relative(std::acos(1.0 / 3.0) * 180.0 / std::numbers::pi));
  CHECK(kerf::tet_radius_ratio(inverted) == 0.0);
}

TEST_CASE("tet_quality_summary counts what it is asked to and refuses an empty mesh") {
  kerf::TetMesh mesh;
  mesh.nodes.resize(8, 3);
  mesh.nodes.topRows(4) = regular_tet();
  Corners sliver;
  sliver << 0, 0, 0, 1, 1, 0, 1, 0, 1e-3, 0, 1, 1e-3;
  mesh.nodes.bottomRows(4) = sliver;
  mesh.tets.resize(2, 4);
  mesh.tets << 0, 1, 2, 3, 4, 6, 5, 7; // the sliver listed positively (corners 1 and 2 swapped)
  const kerf::TetQualitySummary s = kerf::tet_quality_summary(mesh, 10.0, 0.1);
  CHECK(s.min_dihedral_angle < 0.2);
  CHECK(s.min_radius_ratio < 0.01);
  CHECK(s.mean_radius_ratio == kerf_test::relative(0.5 * (1.0 + kerf::tet_radius_ratio(kerf::tet_corners(mesh, 1)))));
  CHECK(s.below_dihedral_threshold == 1);
  CHECK(s.below_radius_ratio_threshold == 1);
  CHECK_THROWS_AS(kerf::tet_quality_summary(kerf::TetMesh{}), std::invalid_argument);
}
