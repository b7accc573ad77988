// Chapter 7 stores the blade's cut in the reference configuration: a world point is pulled back
// to the material point the deformation carried there (xfem/pull_back.hpp). Checked against
// fields whose inverse is known in closed form: a large rotation with a stretch (where the
// fixed point X <- x - u(X) would diverge), and a body cut in two whose upper part has moved
// up, opening a gap that has no material point at all.
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/point_locator.hpp"
#include "kerf/xfem/pull_back.hpp"

#include "support/cut_body.hpp"

#include <doctest/doctest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>

TEST_CASE("pull-back of an affine field with a 1.2 rad rotation: exact in one Newton step, where the fixed point diverges") {
  const support::CutBody body(kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {4, 4, 4}), {}, kerf::LinearMaterial{});
  // x = Q X + t with Q = R S, R a 1.2 rad turn about (1, 2, 3), S a stretch: u(X) = (Q - I) X + t,
  // affine, so the Tet4 field is exactly it. |Q - I| > 1: X <- x - u(X) would diverge.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(1.2, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Matrix3d Q = R * Eigen::Vector3d(1.1, 0.9, 1.05).asDiagonal();
  const Eigen::Vector3d t(0.2, -0.1, 0.3);
  CHECK((Q - Eigen::Matrix3d::Identity()).operatorNorm() > 1.0);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * body.model.num_dof_nodes());
  for (Eigen::Index v = 0; v < body.mesh.num_nodes(); ++v) {
    const Eigen::Vector3d X = body.mesh.nodes.row(v).transpose();
    u.segment<3>(3 * v) = (Q - Eigen::Matrix3d::Identity()) * X + t;
  }
  const kerf::PointLocator locator(body.mesh);
  int most_iterations = 0;
  double worst = 0.0;
  for (int k = 0; k < 50; ++k) {
    const Eigen::Vector3d X(0.05 + 0.9 * std::fmod(0.37 * k, 1.0), 0.05 + 0.9 * std::fmod(0.61 * k + 0.2, 1.0), 0.05 + 0.9 * std::fmod(0.13 * k + 0.5, 1.0));
    const Eigen::Vector3d x = Q * X + t;
    // The guess: the body's centre, far from X (a blade's first point has no better one).
    const kerf::PullBack p = kerf::pull_back_to_reference(body.model, locator, u, x, Eigen::Vector3d(0.5, 0.5, 0.5), 1e-12);
    REQUIRE(p.converged);
    worst = std::max(worst, (p.reference - X).norm());
    most_iterations = std::max(most_iterations, p.iterations);
  }
  MESSAGE("affine field: largest |X - X_exact| " << worst << " m, at most " << most_iterations << " Newton steps");
  // Round-off of a 1 m body (measured 1e-16 m); affine: one step from any guess inside the mesh.
  CHECK(worst < 1e-12);
  CHECK(most_iterations == 1);
}

TEST_CASE("pull-back across an opened cut: each piece's points come back to their own side, a point in the gap has no material point") {
  // The box cut through at z = 0.45 (4 cells: nodes at 0.25 k, so the cut misses every node);
  // the part above is lifted by 0.1 m, the part below stays: the gap 0.45 < z < 0.55 is empty.
  const kerf::TriangleSurface cut = kerf::rectangle_surface(kerf::RectangleCut({-1, -1, 0.45}, {3, 0, 0}, {0, 3, 0}));
  const support::CutBody body(kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {4, 4, 4}), {cut}, kerf::LinearMaterial{});
  const Eigen::Vector3d lift(0.0, 0.0, 0.1);
  const auto field = [&](bool above) { return above ? lift : Eigen::Vector3d::Zero(); };
  Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * body.model.num_dof_nodes());
  const auto N = body.mesh.num_nodes();
  for (Eigen::Index v = 0; v < N; ++v) {
    const bool above = body.mesh.nodes(v, 2) > 0.45;
    u.segment<3>(3 * v) = field(above);
    // One enrichment per node whose support the cut splits: the far side's field minus the home side's.
    for (int k = body.enrichment.first_enrichment[static_cast<std::size_t>(v)]; k < body.enrichment.first_enrichment[static_cast<std::size_t>(v) + 1]; ++k)
      u.segment<3>(3 * (N + k)) = field(!above) - field(above);
  }
  const kerf::PointLocator locator(body.mesh);
  double worst = 0.0;
  for (const Eigen::Vector3d& X : {Eigen::Vector3d(0.3, 0.6, 0.2), Eigen::Vector3d(0.7, 0.2, 0.44), Eigen::Vector3d(0.3, 0.6, 0.46), Eigen::Vector3d(0.8, 0.9, 0.9)}) {
    const bool above = X[2] > 0.45;
    const Eigen::Vector3d x = X + field(above);
    // The guess is the world point itself: for the lifted part it lies 0.1 m off, across the cut
    // for the points just above it.
    const kerf::PullBack p = kerf::pull_back_to_reference(body.model, locator, u, x, x, 1e-12);
    CAPTURE(X.transpose());
    REQUIRE(p.converged);
    worst = std::max(worst, (p.reference - X).norm());
  }
  MESSAGE("opened cut: largest |X - X_exact| " << worst << " m");
  CHECK(worst < 1e-12);
  // In the gap: z = 0.5 in the world is above the lower part (top at 0.45) and below the upper
  // part (bottom at 0.55). No X maps there; the iteration must say so, not return a point.
  const kerf::PullBack gap = kerf::pull_back_to_reference(body.model, locator, u, {0.5, 0.5, 0.5}, {0.5, 0.5, 0.5}, 1e-12);
  MESSAGE("gap: converged " << gap.converged << ", residual " << gap.residual << " m after " << gap.iterations << " steps");
  CHECK_FALSE(gap.converged);
  CHECK(gap.residual > 0.01);
  // Outside the deformed body.
  CHECK_FALSE(kerf::pull_back_to_reference(body.model, locator, u, {0.5, 0.5, 1.5}, {0.5, 0.5, 0.5}, 1e-12).converged);
}
