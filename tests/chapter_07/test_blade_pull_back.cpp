// The blade's edge pulled back into the reference configuration (xfem/blade_pull_back.hpp),
// checked on a body moved rigidly, x = R X + c, whose inverse is known: R^T (x - c). The Tet4
// field of u = (R - I) X + c is that motion exactly, so the samples inside pull back to it, and
// the extension past the body's surface by the local linear map is exact too: an edge poking
// out at both ends comes back with its ends at exactly R^T (x - c).
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/point_locator.hpp"
#include "kerf/xfem/blade_pull_back.hpp"

#include "support/cut_body.hpp"

#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace {

// The unit box in 4 x 4 x 4 cells, turned 0.9 rad about (1, 2, 3) and moved by c.
struct RigidBody {
  support::CutBody body{kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {4, 4, 4}), {}, kerf::LinearMaterial{}};
  kerf::PointLocator locator{body.mesh};
  Eigen::Matrix3d R = Eigen::AngleAxisd(0.9, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  Eigen::Vector3d c{0.2, -0.1, 0.3};
  Eigen::VectorXd u;
  RigidBody() : u(Eigen::VectorXd::Zero(3 * body.model.num_dof_nodes())) {
    for (Eigen::Index v = 0; v < body.mesh.num_nodes(); ++v)
      u.segment<3>(3 * v) = (R - Eigen::Matrix3d::Identity()) * body.mesh.nodes.row(v).transpose() + c;
  }
  Eigen::Vector3d world(const Eigen::Vector3d& X) const { return R * X + c; }
  Eigen::Vector3d reference(const Eigen::Vector3d& x) const { return R.transpose() * (x - c); }
  // Whether the reference point X lies in the box, and how far it is from the box's surface.
  static bool in_box(const Eigen::Vector3d& X) { return (X.array() > 0.0).all() && (X.array() < 1.0).all(); }
  static double distance_to_surface(const Eigen::Vector3d& X) { return std::min(X.minCoeff(), 1.0 - X.maxCoeff()); }
};

} // namespace

TEST_CASE("blade pull-back: an edge poking out of a rigidly moved body at both ends comes back exactly, ends included") {
  const RigidBody rigid;
  // In the reference configuration the edge runs from x = -0.47 to x = 1.33 through the box:
  // both ends outside, the middle inside. In the world it is that segment moved rigidly.
  const Eigen::Vector3d A(-0.47, 0.31, 0.62), B(1.33, 0.58, 0.47);
  const kerf::BladeEdge world{rigid.world(A), rigid.world(B)};
  const int samples = 25;
  const kerf::ReferenceBlade blade = kerf::pull_back_blade_edge(rigid.body.model, rigid.locator, rigid.u, world, samples, nullptr, 1e-12);
  REQUIRE(blade.in_tissue());
  REQUIRE(static_cast<int>(blade.samples.size()) == samples);
  REQUIRE(static_cast<int>(blade.inside.size()) == samples);

  // The samples inside are those whose reference point is in the box; none of them lies within
  // 0.01 m of the box's surface, so the count does not hang on round-off.
  int expected_inside = 0;
  double worst = 0.0;
  for (int s = 0; s < samples; ++s) {
    const double lambda = static_cast<double>(s) / (samples - 1);
    const Eigen::Vector3d X = (1.0 - lambda) * A + lambda * B;
    REQUIRE(std::abs(RigidBody::distance_to_surface(X)) > 0.01);
    const bool inside = RigidBody::in_box(X);
    CAPTURE(s);
    CHECK(static_cast<bool>(blade.inside[static_cast<std::size_t>(s)]) == inside);
    expected_inside += inside ? 1 : 0;
    // Pulled back or extended, every sample is R^T (x - c).
    worst = std::max(worst, (blade.samples[static_cast<std::size_t>(s)] - X).norm());
  }
  CHECK(expected_inside > 2);
  CHECK(expected_inside < samples - 2); // both ends outside: something to extend on each side
  CHECK(blade.samples_inside == expected_inside);
  const double end_error = std::max((blade.edge.start - A).norm(), (blade.edge.end - B).norm());
  MESSAGE("rigid motion: " << blade.samples_inside << " of " << samples << " samples inside; largest |X_s - R^T (x_s - c)| " << worst
                           << " m, at the ends " << end_error << " m");
  // Newton is exact in one step for an affine field and the extension is the same affine map:
  // round-off of a 1 m body and extensions of 0.47 and 0.33 m (measured 4e-16 m, 2e-16 m at the ends).
  CHECK(worst < 1e-12);
  CHECK(end_error < 1e-12);

  // The anchor maps any world point back as the motion does: its reference point is its world
  // point's, its inverse gradient R^T.
  CHECK((blade.anchor.reference - rigid.reference(blade.anchor.world)).norm() < 1e-12);
  CHECK((blade.anchor.inverse_gradient - rigid.R.transpose()).norm() < 1e-12);
  for (const Eigen::Vector3d& x : {world.start, world.end, Eigen::Vector3d(3.0, -2.0, 5.0)})
    CHECK((blade.anchor.map(x) - rigid.reference(x)).norm() < 1e-11); // |x - x_s| up to 6 m: 6 times the round-off above

  // The next frame, the blade moved 0.02 m, warm-started from this one: the same exactness.
  const Eigen::Vector3d shift(0.0, 0.0, 0.02);
  const kerf::BladeEdge next_world{rigid.world(A + shift), rigid.world(B + shift)};
  const kerf::ReferenceBlade next = kerf::pull_back_blade_edge(rigid.body.model, rigid.locator, rigid.u, next_world, samples, &blade, 1e-12);
  CHECK(next.samples_inside == expected_inside);
  CHECK((next.edge.start - (A + shift)).norm() < 1e-12);
  CHECK((next.edge.end - (B + shift)).norm() < 1e-12);
}

TEST_CASE("blade pull-back: an edge with one end inside keeps that end's own pull-back, and extends the other") {
  const RigidBody rigid;
  // A inside, B 0.48 m above the box. The body has moved 0.3 m up and turned: the world points of
  // samples 4 and 5 (reference z = 0.83 and 0.94) lie above the reference box, so Newton cannot
  // start from them; they pull back from their neighbour's reference point (before that retry
  // they were taken for outside: 4 samples inside instead of 6).
  const Eigen::Vector3d A(0.52, 0.47, 0.39), B(0.61, 0.55, 1.48);
  const kerf::BladeEdge world{rigid.world(A), rigid.world(B)};
  const kerf::ReferenceBlade blade = kerf::pull_back_blade_edge(rigid.body.model, rigid.locator, rigid.u, world, 11, nullptr, 1e-12);
  CHECK(blade.inside.front() == 1);
  CHECK(blade.inside.back() == 0);
  // Samples at z = 0.39 + 0.109 s: s = 0 .. 5 inside (z < 1), 6 .. 10 outside.
  CHECK(blade.samples_inside == 6);
  CHECK((blade.edge.start - A).norm() < 1e-12);
  CHECK((blade.edge.end - B).norm() < 1e-12);
}

TEST_CASE("blade pull-back: an edge entirely outside the body is not in the tissue, and its samples are its world points") {
  const RigidBody rigid;
  // 0.5 m beyond the box's face x = 1, in the reference configuration: outside the moved body.
  const Eigen::Vector3d A(1.5, 0.2, 0.3), B(1.6, 0.8, 0.7);
  const kerf::BladeEdge world{rigid.world(A), rigid.world(B)};
  const kerf::ReferenceBlade blade = kerf::pull_back_blade_edge(rigid.body.model, rigid.locator, rigid.u, world, 9, nullptr, 1e-12);
  CHECK_FALSE(blade.in_tissue());
  CHECK(blade.samples_inside == 0);
  CHECK(std::none_of(blade.inside.begin(), blade.inside.end(), [](char c) { return c != 0; }));
  CHECK((blade.samples.front() - world.start).norm() == 0.0);
  CHECK((blade.samples.back() - world.end).norm() == 0.0);
  CHECK_THROWS_AS(kerf::pull_back_blade_edge(rigid.body.model, rigid.locator, rigid.u, world, 1, nullptr, 1e-12), std::invalid_argument);
}
