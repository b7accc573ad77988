// The clamps that move in time (scene_prescribed_motion.hpp): the smooth ramp and the motion of
// translated and rotated clamps, their v and a against finite differences of u and v.
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/scene/scene.hpp"
#include "kerf/scene/scene_prescribed_motion.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <string>

namespace {

// A 1 x 1 x 1 box of 2^3 cells; the clamp at z = 0 is translated and turned about z through
// (0.5, 0.5, 0) by 30 degrees, both along a ramp of 0.4 s; a second entry holds the node x = y = z = 1.
const std::string moving_scene = R"({
  "mesh": {"box": {"min": [0, 0, 0], "max": [1, 1, 1], "cells": [2, 2, 2]}},
  "dirichlet": [{"region": {"box": {"min": [0, 0, 0], "max": [1, 1, 0]}}, "displacement": [0.1, -0.2, 0.05],
                 "rotation": {"axis": [0, 0, 1], "degrees": 30, "center": [0.5, 0.5, 0]}, "ramp_time": 0.4},
                {"region": {"box": {"min": [1, 1, 1], "max": [1, 1, 1]}}}],
  "time": {"integrator": "newmark", "dt": 0.01, "steps": 10}
})";

} // namespace

TEST_CASE("the smooth ramp rises from 0 to 1 with its derivatives, which finite differences confirm") {
  CHECK(kerf::smooth_ramp(-0.5).s == 0.0);
  CHECK(kerf::smooth_ramp(1.5).s == 1.0);
  CHECK(kerf::smooth_ramp(0.5).s == kerf_test::relative(0.5, 1e-15)); // symmetric about the middle
  // Central differences of step h have an error h^2 |s'''| / 6 <= 1e-8 * 60 / 6 = 1e-7 (|s'''| <= 60),
  // and h^2 |s''''| / 12 <= 3e-8 for s'' (|s''''| <= 360): 1e-6 leaves room for round-off eps / h ~ 2e-12.
  const double h = 1e-4;
  for (const double tau : {0.1, 0.3, 0.5, 0.77, 0.95}) {
    CAPTURE(tau);
    const kerf::SmoothRamp r = kerf::smooth_ramp(tau);
    CHECK(std::abs(r.ds - (kerf::smooth_ramp(tau + h).s - kerf::smooth_ramp(tau - h).s) / (2 * h)) < 1e-6);
    CHECK(std::abs(r.dds - (kerf::smooth_ramp(tau + h).ds - kerf::smooth_ramp(tau - h).ds) / (2 * h)) < 1e-6);
  }
  // s' and s'' vanish at both ends (so the clamp starts and stops smoothly) and s' is continuous there.
  for (const double tau : {0.0, 1.0}) {
    CHECK(kerf::smooth_ramp(tau).ds == 0.0);
    CHECK(kerf::smooth_ramp(tau).dds == 0.0);
  }
  CHECK(kerf::smooth_ramp(1e-6).ds < 1e-10);
}

TEST_CASE("a ramped clamp's velocity and acceleration are the derivatives of its displacement") {
  const kerf::Scene scene = kerf::parse_scene(moving_scene, "moving.json", ".");
  REQUIRE(scene.dirichlet[0].ramp_time == 0.4);
  CHECK(kerf::scene_dirichlet_moves(scene));
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {2, 2, 2});
  const Eigen::Index dof_nodes = mesh.num_nodes() + 3; // three enriched DOF nodes, which the motion leaves at 0
  // At the start everything is at rest and undeformed.
  const kerf::PrescribedMotion start = kerf::scene_prescribed_motion(scene, mesh, dof_nodes, 0.0);
  CHECK(start.u.norm() == 0.0);
  CHECK(start.v.norm() == 0.0);
  CHECK(start.a.norm() == 0.0);
  // After the ramp: the quasi-static path's end (the rotation and translation of chapter 2's scenes), at rest.
  const kerf::PrescribedMotion end = kerf::scene_prescribed_motion(scene, mesh, dof_nodes, 0.5);
  const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
  const Eigen::Vector3d X(0, 0, 0); // node 0, a corner of the clamp
  const Eigen::Vector3d r = X - Eigen::Vector3d(0.5, 0.5, 0);
  const Eigen::Vector3d expected = Eigen::Vector3d(c * r.x() - s * r.y(), s * r.x() + c * r.y(), 0) - r + Eigen::Vector3d(0.1, -0.2, 0.05);
  CHECK((end.u.segment<3>(0) - expected).norm() <= 1e-15);
  CHECK(end.v.norm() == 0.0);
  CHECK(end.a.norm() == 0.0);
  // Inside the ramp, central differences in time (step h = 1e-5 s; u varies on the ramp's 0.4 s,
  // so the truncation h^2 u''' / 6 is about 1e-10 * |u| / 0.4^3 < 1e-8 relative): v = du/dt, a = dv/dt.
  const double h = 1e-5;
  for (const double t : {0.05, 0.17, 0.2, 0.33}) {
    CAPTURE(t);
    const kerf::PrescribedMotion now = kerf::scene_prescribed_motion(scene, mesh, dof_nodes, t);
    const kerf::PrescribedMotion before = kerf::scene_prescribed_motion(scene, mesh, dof_nodes, t - h);
    const kerf::PrescribedMotion after = kerf::scene_prescribed_motion(scene, mesh, dof_nodes, t + h);
    const Eigen::VectorXd v_fd = (after.u - before.u) / (2 * h), a_fd = (after.v - before.v) / (2 * h);
    CHECK((now.v - v_fd).norm() <= 1e-7 * now.v.norm());
    CHECK((now.a - a_fd).norm() <= 1e-6 * now.a.norm());
    CHECK(now.v.norm() > 0.1); // the clamp does move
    CHECK(now.u.tail(9).norm() == 0.0); // the enriched DOFs stay at 0
  }
}
