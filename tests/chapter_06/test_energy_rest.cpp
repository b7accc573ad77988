// The energy account of the demo's corotated flap, through the program: energy.csv's damping
// column (the step's own rule applied to C, dt v_bar^T C v_bar) and its numerical column (the
// rest of the balance on this path, energy_account.hpp). With the rotations frozen the rest is
// the frozen step's error and shrinks like dt; with Newton it is the trapezoidal rule's error on
// the corotated force and shrinks like dt^2 (test_corotated_steps.cpp derives both orders on a
// cut block; here they are measured on the demo's own scene, in the columns a student reads).
#include "support/run_program.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

namespace {

const std::string chapter_06 = std::string(KERF_BINARY_DIR) + "/bin/06_newmark";
const std::string examples = std::string(KERF_SOURCE_DIR) + "/examples";

// The columns of energy.csv (energy_account.hpp).
enum Column { step, t, kinetic, elastic, external_work, dissipated, damping, numerical };

// examples/06_flap_linear.json is the demo's scene with the linear model; as "corotational" it
// is the demo (lumped mass, Rayleigh [3, 0.002]), here run for `duration` seconds of `dt`.
std::string demo_scene(double dt, double duration, const std::string& corotation) {
  std::string text = kerf_test::read_text(examples + "/06_flap_linear.json");
  const auto replace = [&text](const std::string& from, const std::string& to) {
    const std::size_t at = text.find(from);
    REQUIRE(at != std::string::npos);
    text.replace(at, from.size(), to);
  };
  replace("\"model\": \"linear\"", "\"model\": \"corotational\"");
  // Newton to a tight tolerance, solved by CHOLMOD, so that its rest is the time step's alone;
  // the frozen step as the demo runs it (CG-Jacobi to 1e-3: its error moves the rest by 0.4 %).
  const std::string newton = corotation == "newton" ? ", \"tolerance\": 1e-8" : "";
  replace("\"dt\": 0.005, \"steps\": 300",
          "\"dt\": " + std::to_string(dt) + ", \"steps\": " + std::to_string(std::lround(duration / dt)) + ", \"corotation\": \"" +
              corotation + "\"" + newton);
  replace("\"output\": {\"every\": 10}", std::string("\"output\": {\"every\": 1000}") +
                                             (corotation == "newton" ? ", \"solver\": {\"type\": \"cholmod\"}" : ""));
  return text;
}

// Runs the program on the scene and returns energy.csv's rows, after checking its columns.
std::vector<std::vector<double>> energy_rows(const std::string& name, const std::string& scene) {
  const auto dir = kerf_test::fresh_dir("chapter06_energy_rest_" + name);
  kerf_test::write_text(dir / "scene.json", scene);
  const auto run = kerf_test::run_program(chapter_06 + " --quiet --scene '" + (dir / "scene.json").string() + "' --out '" +
                                              (dir / "out").string() + "'",
                                          dir);
  INFO(run.err);
  REQUIRE(run.exit_status == 0);
  CHECK(run.err.empty()); // no Newton step missed its tolerance
  std::string header;
  const auto rows = kerf_test::read_csv_rows(dir / "out" / "energy.csv", header);
  CHECK(header == "step,t,kinetic,elastic,external_work,dissipated,damping,numerical");
  REQUIRE(rows.size() > 2);
  for (std::size_t n = 0; n < rows.size(); ++n) {
    INFO("step ", n);
    REQUIRE(rows[n].size() == 8);
    // dissipated is damping + numerical, each written at 17 digits (they read back exactly).
    CHECK(rows[n][dissipated] == rows[n][damping] + rows[n][numerical]);
    // Still clamps and the average acceleration rule: each step's damping is
    // dt v_bar^T C v_bar >= 0 with C = 3 M + 0.002 K_R positive semi-definite. The bound
    // allows the round-off of Delta u against dt v_bar (~1e-16 of the work).
    if (n > 0) CHECK(rows[n][damping] >= rows[n - 1][damping] - 1e-14 * rows.back()[external_work]);
  }
  return rows;
}

} // namespace

TEST_CASE("the demo flap's energy rest: the frozen-rotation step's is first order in dt, Newton's second") {
  // The first swing out and back, 0.4 s, where the rotations are largest (the flap's end moves
  // 9.4 cm along gravity at t = 0.2 s), at the demo's dt and half of it.
  const double duration = 0.4, demo_dt = 0.005;
  for (const std::string corotation : {"frozen", "newton"}) {
    CAPTURE(corotation);
    std::vector<double> rest, work, damped;
    for (const double dt : {demo_dt, demo_dt / 2}) {
      const auto rows = energy_rows(corotation + "_" + std::to_string(std::lround(dt * 1e4)), demo_scene(dt, duration, corotation));
      REQUIRE(rows.back()[t] == kerf_test::relative(duration, 1e-12));
      rest.push_back(rows.back()[numerical]);
      work.push_back(rows.back()[external_work]);
      damped.push_back(rows.back()[damping]);
      MESSAGE(corotation << ", dt " << dt << " s: work " << work.back() << " J, damping " << damped.back() << " J, numerical rest "
                         << rest.back() << " J (" << 100 * rest.back() / work.back() << " % of the work)");
    }
    CHECK(work[1] > 0.0);
    CHECK(damped[1] > 0.5 * work[1]); // Rayleigh damping takes most of gravity's work over the swing
    const double order = std::log2(std::abs(rest[0] / rest[1]));
    MESSAGE("observed order of the rest: " << order);
    // Measured: frozen -1.85 mJ and -0.795 mJ (order 1.22; at 10, 5, 2.5, 1.25 ms the orders
    // are 1.38, 1.22, 1.12: first order, reached from above); Newton +1.22 mJ and +0.319 mJ
    // (order 1.93). The bounds are test_corotated_steps.cpp's: they leave room for the
    // pre-asymptotic range and still tell the two orders apart.
    if (corotation == "frozen") {
      CHECK(order >= 0.8);
      CHECK(order <= 1.4);
      // Both runs of the frozen step put energy in (a negative rest): the sign is the frozen
      // step's (Newton's rest has the other sign), so the injection is not the time rule's.
      CHECK(rest[0] < 0.0);
      CHECK(rest[1] < 0.0);
    } else {
      CHECK(order >= 1.7);
      CHECK(rest[0] > 0.0);
      CHECK(rest[1] > 0.0);
    }
  }
}
