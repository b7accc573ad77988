// Koschier Figs. 5 and 10 (notes 6.5): a slice of a hinged cube at rest. Gravity's moment
// about the hinge vanishes at rest (the hinge's reactions have none), so the model's centre of
// mass hangs straight under the hinge. XFEM integrates each piece over its own volume: the
// model's centre of mass is the slice's, which ends under the hinge. Element duplication gives
// the slice a full copy of every element it touches: the model's centre of mass is that of
// those elements, and the slice's own ends displaced by what the rotation that puts the other
// under the hinge does to it.
#include "../examples/cut_dynamics_scenes.hpp"

#include <doctest/doctest.h>

#include <cmath>

namespace {

// The slice [0, c] of the cube at rest after 8 s of damped swinging, its true centre of mass.
Eigen::Vector3d rest_centre_of_mass(double c, const kerf::PieceRuleFunction& rule) {
  const auto body = cut_dynamics::hinged_cube(c, cut_dynamics::cube_material, rule);
  body->system.rayleigh_alpha = 4.0;
  kerf::NonlinearNewmarkSettings settings;
  settings.update = kerf::RotationUpdate::newton;
  settings.tolerance = 1e-10;
  settings.newmark = {0.3025, 0.6};
  kerf::NonlinearNewmarkIntegrator integrator(body->system, 0.02, settings);
  kerf::DynamicState state = integrator.initial_state(body->zero(), body->zero(), 0.0);
  for (int n = 0; n < 400; ++n) REQUIRE(integrator.step(state).converged);
  return body->centre_of_mass(state.u, [c](const Eigen::Vector3d& x) { return x.x() < c; });
}

} // namespace

TEST_CASE("a hinged slice rests with its centre of mass under the hinge with XFEM, displaced with element duplication") {
  for (const double c : {0.3, 0.65}) {
    CAPTURE(c);
    // XFEM: 0 up to what is left of the swing after 8 s (kinetic energy ~1e-11 J, measured
    // offset 2e-8 m at c = 0.3); 1e-6 m is a millionth of the cube.
    const Eigen::Vector3d xfem = rest_centre_of_mass(c, cut_dynamics::piece_rule);
    CHECK(std::abs(xfem.x()) < 1e-6);
    // And it got there by swinging: the slice's centre of mass started at (c / 2, 0.5, 0.5),
    // at a distance sqrt(c^2 / 4 + 1 / 4) from the hinge line, which the rotation keeps (the
    // stiff cube strains 1e-4).
    CHECK(xfem.z() == doctest::Approx(1.0 - std::sqrt(c * c / 4 + 0.25)).epsilon(1e-3));
    // Duplication: every one of the five tets spans x in [0, 1], so the plane x = c cuts them
    // all, and the slice carries the whole cube: its model's centre of mass is the cube's
    // centre, (0.5, 0.5, 0.5), b = (0.5, -0.5) from the hinge in the x-z plane, which rest puts
    // under the hinge by a rotation of 45 degrees. The slice's own, a = (c / 2, -0.5), goes to
    // a_x cos 45 + a_z sin 45 = (c / 2 - 0.5) / sqrt(2): -0.2475 m for c = 0.3, the geometry's
    // prediction. Tolerance 1e-4 m: the elastic sag of the stiff cube, strain ~1e-4 over 1 m
    // (measured difference 7e-6 m).
    const Eigen::Vector3d duplication = rest_centre_of_mass(c, cut_dynamics::duplication_rule);
    const double predicted = (c / 2 - 0.5) / std::sqrt(2.0);
    CHECK(std::abs(duplication.x() - predicted) < 1e-4);
  }
}
