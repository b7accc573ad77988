// K by the interaction integral in domain form (fracture/interaction_integral.hpp) of the XFEM
// field with crack-tip functions: Williams's field of modes I, II and mixed
// prescribed on the boundary of the cracked slab (examples/williams_slab.hpp), solved with
// geometric enrichment, K read from the field's gradient (CutXfemModel::displacement_gradient_at)
// over the ring 0.1 m < r < 0.3 m around the front, against the K prescribed.
#include "../examples/williams_slab.hpp"

#include <doctest/doctest.h>

#include <cmath>

namespace ws = williams_slab;

namespace {

// The relative errors of (K_I, K_II) against the larger prescribed factor.
Eigen::Vector2d sif_errors(const ws::Setup& s, bool interpolant) {
  const ws::Slab slab(s);
  const Eigen::VectorXd u = interpolant ? slab.interpolant() : ws::solve(slab);
  const kerf::StressIntensityFactors K = ws::interaction_sifs(slab, u);
  const double scale = std::max(std::abs(s.K.K_I), std::abs(s.K.K_II));
  return Eigen::Vector2d(K.K_I - s.K.K_I, K.K_II - s.K.K_II).cwiseAbs() / scale;
}

} // namespace

TEST_CASE("K_I and K_II of the XFEM field within 1 % for modes I, II and mixed when the ring lies in the enriched zone") {
  // n = 9 (h = 0.11 m) and r_e = 0.35 m: every node of the ring where q falls carries the
  // branch functions, in which Williams's field is exact, so K errs by what the discrete field
  // misses there. Measured (examples/05_convergence_study.cpp, part "sif_radius";
  // figures/05_crack_tip/convergence.md): relative errors of (K_I, K_II)
  //   mode I 5.3e-3, 1.4e-3; mode II 1.3e-3, 2.1e-3; mixed (K_II = -0.6 K_I) 6.1e-3, 2.7e-3,
  // and on n = 17 at most 1.0e-3. The bound is Kerf's target of 1 %, 1.6 times the largest measured.
  // With r_e = 0.1 m (the ring outside the enriched zone, standard Tet4 there) K_I errs by
  // 4.0 %, 4.2 % and 1.9 % on n = 9, 17, 33 with Paulus's blending, not within 1 % before
  // n = 65 (the test below); Fries's correction brings it to 0.07-0.12 % from n = 17 on
  // (figures/05_crack_tip/convergence.md).
  for (const kerf::StressIntensityFactors K : {kerf::StressIntensityFactors{1.0e4, 0.0, 0.0}, kerf::StressIntensityFactors{0.0, 1.0e4, 0.0},
                                                kerf::StressIntensityFactors{1.0e4, -0.6e4, 0.0}}) {
    ws::Setup s;
    s.cells = 9;
    s.radius = 0.35;
    s.K = K;
    const Eigen::Vector2d errors = sif_errors(s, false);
    MESSAGE("K_I " << K.K_I << ", K_II " << K.K_II << ": relative errors " << errors.transpose());
    CAPTURE(K.K_I);
    CAPTURE(K.K_II);
    CHECK(errors[0] < 0.01);
    CHECK(errors[1] < 0.01);
  }
}

TEST_CASE("with the ring outside the enriched zone K is off by several percent, as the field there") {
  // The failure the radius cures, and a check that the test above can fail: r_e = 0.1 m on n = 9
  // (measured 4.0 % for K_I in mode I, against the bound 3 %).
  ws::Setup s;
  s.cells = 9;
  s.radius = 0.1;
  const Eigen::Vector2d errors = sif_errors(s, false);
  MESSAGE("r_e = 0.1 m, mode I: relative errors " << errors.transpose());
  CHECK(errors[0] > 0.03);
}
