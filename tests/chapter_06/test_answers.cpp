// The answers chapter 6 must get exactly: a piece cut clean off the clamped beam falls at g
// (u = g t^2 / 2 at every step), linear and corotational, consistent and lumped mass, frozen
// rotations and Newton; the undamped average acceleration rule keeps kinetic + elastic -
// external work; and a clamp moved along the scene's ramp is where the ramp says at every step.
#include "support/run_program.hpp"

#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace {

const std::string chapter_06 = std::string(KERF_BINARY_DIR) + "/bin/06_newmark";
const std::string examples = std::string(KERF_SOURCE_DIR) + "/examples";

// The example free-fall scene with `replace` applied ("key": value pairs of its time field or model).
std::string edited(std::string text, const std::vector<std::pair<std::string, std::string>>& replace) {
  for (const auto& [from, to] : replace) {
    const std::size_t at = text.find(from);
    REQUIRE(at != std::string::npos);
    text.replace(at, from.size(), to);
  }
  return text;
}

// Runs the program on `scene` with `probes`, in `dir`, and returns the rows of its probe
// history (step, t, probe, ux, uy, uz); the run must succeed.
std::vector<std::vector<double>> probe_history(const std::filesystem::path& dir, const std::string& scene, const std::string& probes) {
  const auto run = kerf_test::run_program(chapter_06 + " --quiet --scene '" + scene + "' --out '" + (dir / "out").string() + "' --probes '" +
                                              probes + "' --probes-history '" + (dir / "history.csv").string() + "'",
                                          dir);
  INFO(run.err);
  REQUIRE(run.exit_status == 0);
  std::string header;
  const auto rows = kerf_test::read_csv_rows(dir / "history.csv", header);
  CHECK(header == "step,t,probe,ux,uy,uz");
  return rows;
}

// The largest kinetic + elastic energy of an energy.csv's rows, and the largest change of the
// balance kinetic + elastic + dissipated - external_work from its first row's value.
struct Balance {
  double largest = 0.0, drift = 0.0;
};
Balance energy_balance(const std::vector<std::vector<double>>& rows) {
  const auto balance = [](const std::vector<double>& row) { return row[2] + row[3] + row[5] - row[4]; };
  Balance b;
  for (const auto& row : rows) {
    b.largest = std::max(b.largest, row[2] + row[3]);
    b.drift = std::max(b.drift, std::abs(balance(row) - balance(rows[0])));
  }
  return b;
}

} // namespace

TEST_CASE("a piece cut clean off the clamped beam falls as g t^2 / 2 at every step") {
  // examples/06_free_fall_lumped.json: the beam cut through at z = 0.155, gravity 9.81 along +x,
  // no damping (mass damping would be a drag on the falling piece). The first three probes lie
  // in the freed piece (examples/06_free_fall_probes.csv), the fourth in the clamped beam. The
  // scene asks for CHOLMOD: chapter 6's default, CG to time.tolerance = 1e-3, would add its own
  // error (up to 4e-3 of the fall here), which this test, about the masses, is not about.
  const std::string base = kerf_test::read_text(examples + "/06_free_fall_lumped.json");
  struct Case {
    std::string name;
    std::vector<std::pair<std::string, std::string>> replace;
  };
  const std::vector<Case> cases{
      {"linear_lumped", {}},
      {"linear_consistent", {{"\"mass\": \"lumped\"", "\"mass\": \"consistent\""}}},
      {"corotational_lumped_frozen", {{"\"linear\"", "\"corotational\""}}},
      {"corotational_consistent_frozen", {{"\"linear\"", "\"corotational\""}, {"\"mass\": \"lumped\"", "\"mass\": \"consistent\""}}},
      {"corotational_lumped_newton", {{"\"linear\"", "\"corotational\""}, {"\"mass\": \"lumped\"", "\"mass\": \"lumped\", \"corotation\": \"newton\""}}},
      {"corotational_tet10_consistent", {{"\"linear\"", "\"corotational\""}, {"\"order\": 1", "\"order\": 2"}, {"\"mass\": \"lumped\"", "\"mass\": \"consistent\""}}},
  };
  for (const Case& c : cases) {
    CAPTURE(c.name);
    const auto dir = kerf_test::fresh_dir("chapter06_free_fall_" + c.name);
    kerf_test::write_text(dir / "scene.json", edited(base, c.replace));
    const auto rows = probe_history(dir, (dir / "scene.json").string(), examples + "/06_free_fall_probes.csv");
    REQUIRE(rows.size() == 21 * 4);
    // Newmark integrates a constant acceleration exactly (u~ + beta dt^2 g = u + dt v + dt^2 g / 2
    // for any beta), so the only error is the round-off of 20 solves with M + beta dt^2 K, whose
    // condition number is about beta dt^2 omega_max^2 <= 1e4 here: 1e4 * 2e-16 * 20 steps ~ 4e-11
    // relative; we allow 1e-9. The clamped beam's probe must not follow g (a test that can fail).
    double worst = 0.0;
    for (const auto& row : rows) {
      const double t = row[1], fall = 0.5 * 9.81 * t * t;
      if (row[2] == 3.0) {
        if (t > 0.1) CHECK(std::abs(row[3] - fall) > 0.1 * fall);
        continue;
      }
      worst = std::max({worst, std::abs(row[3] - fall), std::abs(row[4]), std::abs(row[5])});
    }
    const double final_fall = 0.5 * 9.81 * 0.2 * 0.2;
    CHECK(worst <= 1e-9 * final_fall);
    MESSAGE(c.name << ": worst deviation from g t^2 / 2 in the freed piece: " << worst / final_fall << " of the final fall");
  }
}

TEST_CASE("with the default solver the freed piece falls at g exactly, whatever the solver's tolerance") {
  // The same corotational scene with chapter 6's default solve: conjugate gradients to a
  // relative residual of time.tolerance (1e-3 unless given), from the last step's change of
  // acceleration, with Jacobi's scaling in the part basis (dynamics/part_basis.hpp). In that
  // basis the piece the cut freed shares no unknown with the beam, and neither does the
  // preconditioner, so the iterations that correct the beam never move the piece: with the
  // piece's residual zero when the solve starts (it falls at g, and its acceleration did not
  // change), it stays exact. In the enrichment's basis [u; a] the piece shares the u_i of the
  // cut's nodes with the beam, and its fall was off by about the tolerance (measured 1.03 and
  // 3.70 times it with lumped and consistent mass at 1e-3). The lumped mass is diagonal in
  // the part basis, so Jacobi's CG solves the first step's M a = f in one iteration, exactly:
  // the same 1e-9 as CHOLMOD's above. The consistent mass is not diagonal there, and its first
  // acceleration is solved only to the tolerance: at 1e-8, 1e-9 of the fall is asked.
  const std::string base = kerf_test::read_text(examples + "/06_free_fall_lumped.json");
  for (const double tolerance : {1e-3, 1e-8}) {
    for (const std::string mass : {"lumped", "consistent"}) {
      if (mass == "consistent" && tolerance == 1e-3) continue;
      CAPTURE(tolerance);
      CAPTURE(mass);
      std::vector<std::pair<std::string, std::string>> replace{{"\"linear\"", "\"corotational\""}, {",\n  \"solver\": {\"type\": \"cholmod\"}", ""}};
      if (tolerance != 1e-3 || mass != "lumped") // the first case is the default as it is: no tolerance given
        replace.push_back({"\"mass\": \"lumped\"", "\"mass\": \"" + mass + "\", \"tolerance\": " + (tolerance == 1e-3 ? "1e-3" : "1e-8")});
      const auto dir = kerf_test::fresh_dir("chapter06_free_fall_default_" + mass + (tolerance == 1e-3 ? "_3" : "_8"));
      kerf_test::write_text(dir / "scene.json", edited(base, replace));
      const auto rows = probe_history(dir, (dir / "scene.json").string(), examples + "/06_free_fall_probes.csv");
      REQUIRE(rows.size() == 21 * 4);
      double worst = 0.0;
      for (const auto& row : rows)
        if (row[2] < 3.0) worst = std::max({worst, std::abs(row[3] - 0.5 * 9.81 * row[1] * row[1]), std::abs(row[4]), std::abs(row[5])});
      const double final_fall = 0.5 * 9.81 * 0.2 * 0.2;
      MESSAGE(mass << ", tolerance " << tolerance << ": worst deviation " << worst / final_fall << " of the final fall");
      // The CHOLMOD test's bound: the round-off of 20 solves.
      CHECK(worst <= 1e-9 * final_fall);
    }
  }
}

TEST_CASE("with eqs. 81-82 as printed the freed piece does not fall at g") {
  // The same run with Schoch et al.'s lumping: a freed piece gets the inertia of whole elements and
  // the consistent body load, so its probes miss g t^2 / 2: the test above can fail.
  const auto dir = kerf_test::fresh_dir("chapter06_free_fall_eq81");
  kerf_test::write_text(dir / "scene.json", edited(kerf_test::read_text(examples + "/06_free_fall_lumped.json"),
                                                   {{"\"mass\": \"lumped\"", "\"mass\": \"schoch_eq_81_82\""}}));
  const auto rows = probe_history(dir, (dir / "scene.json").string(), examples + "/06_free_fall_probes.csv");
  REQUIRE(rows.size() == 21 * 4);
  double worst = 0.0;
  for (const auto& row : rows)
    if (row[2] < 3.0) worst = std::max(worst, std::abs(row[3] - 0.5 * 9.81 * row[1] * row[1]));
  CHECK(worst > 1e-3 * 0.5 * 9.81 * 0.2 * 0.2);
}

TEST_CASE("undamped linear Newmark with the average acceleration rule keeps kinetic + elastic - external work") {
  // The hanging flap of examples/06_flap_linear.json without damping, consistent and lumped mass,
  // 60 steps. newmark.hpp's energy identity makes the balance exact for the discrete solution;
  // what is left is the solves' round-off, about cond(M + dt^2 K / 4) eps ~ 1e-12 of the energy
  // per step, and the CSV's 17 digits: 1e-10 of the largest kinetic + elastic energy has a
  // margin of about ten over 60 steps.
  for (const std::string mass : {"lumped", "consistent"}) {
    CAPTURE(mass);
    const auto dir = kerf_test::fresh_dir("chapter06_energy_" + mass);
    kerf_test::write_text(dir / "scene.json", edited(kerf_test::read_text(examples + "/06_flap_linear.json"),
                                                     {{"\"steps\": 300", "\"steps\": 60"},
                                                      {"\"mass\": \"lumped\", \"rayleigh\": [3, 0.002]", "\"mass\": \"" + mass + "\""}}));
    const auto run = kerf_test::run_program(chapter_06 + " --quiet --scene '" + (dir / "scene.json").string() + "' --out '" + (dir / "out").string() + "'", dir);
    INFO(run.err);
    REQUIRE(run.exit_status == 0);
    std::string header;
    const auto rows = kerf_test::read_csv_rows(dir / "out" / "energy.csv", header);
    REQUIRE(rows.size() == 61);
    const auto [largest, drift] = energy_balance(rows);
    for (const auto& row : rows) CHECK(std::abs(row[5]) <= 1e-10 * largest); // nothing dissipated
    CHECK(largest > 1e-4); // the flap does swing (joules)
    CHECK(drift <= 1e-10 * largest);
    MESSAGE(mass << ": largest |kinetic + elastic - work - start| = " << drift / largest << " of the largest energy");
  }
}

TEST_CASE("a clamp moved along its ramp is where the ramp puts it, and its work is booked") {
  // examples/06_beam_shaken.json: the clamp at z = 0 is moved 2 cm along x and turned by 20
  // degrees about y through (0.015, 0.03, 0) along the smooth ramp of 0.2 s. A probe at a
  // clamped node must follow p(s(t / 0.2)) to round-off; the energy balance holds by the
  // bookkeeping (so it is not checked here), and the clamp did work on the beam.
  const auto dir = kerf_test::fresh_dir("chapter06_moving_clamp");
  kerf_test::write_text(dir / "probes.csv", "x,y,z\n0.03,0.06,0\n0,0,0\n");
  const auto rows = probe_history(dir, examples + "/06_beam_shaken.json", (dir / "probes.csv").string());
  REQUIRE(rows.size() == 81 * 2);
  double worst = 0.0;
  for (const auto& row : rows) {
    const double tau = std::min(row[1] / 0.2, 1.0);
    const double s = tau * tau * tau * (10 - 15 * tau + 6 * tau * tau);
    const Eigen::Vector3d X = row[2] == 0.0 ? Eigen::Vector3d(0.03, 0.06, 0) : Eigen::Vector3d(0, 0, 0);
    const Eigen::Vector3d c(0.015, 0.03, 0);
    const Eigen::Matrix3d Q = Eigen::AngleAxisd(s * 20 * M_PI / 180, Eigen::Vector3d::UnitY()).toRotationMatrix();
    const Eigen::Vector3d expected = (Q - Eigen::Matrix3d::Identity()) * (X - c) + s * Eigen::Vector3d(0.02, 0, 0);
    worst = std::max(worst, (Eigen::Vector3d(row[3], row[4], row[5]) - expected).norm());
  }
  // The probe sits on a node: its barycentric coordinates are 1 and 0 up to round-off (~1e-16),
  // times displacements of about 0.02 m.
  CHECK(worst <= 1e-14);
  std::string header;
  const auto energy = kerf_test::read_csv_rows(dir / "out" / "energy.csv", header);
  REQUIRE(energy.size() == 81);
  CHECK(energy[40][2] > 0.0);     // the beam moves
  CHECK(energy.back()[4] > 0.0);  // because the clamp worked on it
}

TEST_CASE("every integrator the program offers balances its energy account") {
  // The hanging flap of examples/06_flap_linear.json with Rayleigh damping, each integrator on
  // the linear model. Newmark, backward Euler and the central difference book their numerical
  // dissipation in closed form (dynamics/*.hpp), so the balance kinetic + elastic + dissipated -
  // work = start is a check of the program's wiring to round-off (1e-9 of the largest energy
  // leaves a margin of ~100 over the solves' ~1e-12 per step, 40 steps); HHT-alpha books the rest
  // of its balance as numerical by construction, so for it the balance proves nothing and is not
  // checked. (Which integrator dissipates more is not checked either: the damping's work
  // depends on each one's trajectory, and HHT-alpha's is below the average acceleration rule's
  // here.)
  struct Case {
    std::string name, time;
  };
  const std::vector<Case> cases{
      {"average_acceleration", R"("integrator": "newmark")"},
      {"newmark_damped", R"("integrator": "newmark", "beta": 0.3025, "gamma": 0.6)"},
      {"hht_alpha", R"("integrator": "hht_alpha", "alpha": -0.3)"},
      {"backward_euler", R"("integrator": "backward_euler")"},
      {"central_difference", R"("integrator": "central_difference")"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.name);
    const auto dir = kerf_test::fresh_dir("chapter06_integrator_" + c.name);
    const bool explicit_step = c.name == "central_difference";
    kerf_test::write_text(dir / "scene.json",
                          edited(kerf_test::read_text(examples + "/06_flap_linear.json"),
                                 {{"\"cells\": [3, 6, 19]", "\"cells\": [3, 3, 10]"},
                                  {"\"integrator\": \"newmark\", \"dt\": 0.005, \"steps\": 300",
                                   c.time + (explicit_step ? ", \"dt\": 0.0001, \"steps\": 40" : ", \"dt\": 0.005, \"steps\": 40")}}));
    const auto run = kerf_test::run_program(chapter_06 + " --scene '" + (dir / "scene.json").string() + "' --out '" + (dir / "out").string() + "'", dir);
    INFO(run.out, run.err);
    REQUIRE(run.exit_status == 0);
    if (explicit_step) CHECK(run.out.find("critical step 2 / omega_max = ") != std::string::npos);
    std::string header;
    const auto rows = kerf_test::read_csv_rows(dir / "out" / "energy.csv", header);
    REQUIRE(rows.size() == 41);
    const auto [largest, drift] = energy_balance(rows);
    CHECK(largest > 0.0);
    CHECK(rows.back()[5] > 0.0); // Rayleigh damping dissipates in every case
    if (c.name != "hht_alpha") CHECK(drift <= 1e-9 * largest);
    MESSAGE(c.name << ": dissipated " << rows.back()[5] << " J, balance drift " << drift / largest << " of the largest energy");
  }
}
