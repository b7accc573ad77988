// Chapter 8 from the command line: the demo scene is the example file; chapter 7's scene runs
// unchanged and stays within 2 % of chapter 7 solved tightly (and equals it solved tightly
// itself); where the step fails and where it holds (a blade over the same tets twice, many
// passes for 1000 steps, thin slabs at 4 iterations a step, a freed piece); the window paced by
// the wall clock under xvfb-run, driven by scripted events keyed by time; bad input; the frames;
// --help.
//
// The livers are small (1000 or 2000 tets, no frames where none is needed), so that each case
// takes seconds; the demo's 10 000 tets run as the example scene's test (tests/CMakeLists.txt).
#include "support/program_checks.hpp"
#include "support/run_program.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace {

using kerf_test::check_refused;
using kerf_test::number_after;
using kerf_test::quoted;
using kerf_test::with_display;
using kerf_test::without_style_warning;
using nlohmann::json;

const std::string chapter_07 = std::string(KERF_BINARY_DIR) + "/bin/07_liver";
const std::string chapter_08 = std::string(KERF_BINARY_DIR) + "/bin/08_real_time";
const std::filesystem::path source_dir = KERF_SOURCE_DIR;

json read_json(const std::filesystem::path& file) { return json::parse(kerf_test::read_text(file)); }

// Chapter 7's example scene with a liver of `tets` tets, `steps` steps, no frames and no .vtu but
// the last.
json small_scene(int tets, int steps) {
  json scene = read_json(source_dir / "examples" / "07_liver_cut.json");
  scene["mesh"]["liver"]["tets"] = tets;
  scene["time"]["steps"] = steps;
  scene["render"] = {{"every", 0}};
  scene["output"] = {{"every", steps}};
  return scene;
}

// A keyframe of the blade: an upright edge at (x, y) from z_top down to z_bottom at `time`.
json upright(double time, double x, double y, double z_top = 0.09, double z_bottom = 0.0) {
  return {{"time", time}, {"edge", {std::array{x, y, z_top}, std::array{x, y, z_bottom}}}};
}

// Writes `scene` as dir/name.json and runs `program` on it, out in dir/name.
kerf_test::ProgramResult run_scene(const std::string& program, const json& scene, const std::filesystem::path& dir, const std::string& name,
                                   const std::string& more_options = "") {
  kerf_test::write_text(dir / (name + ".json"), scene.dump(2));
  return kerf_test::run_program(program + " --scene " + quoted(dir / (name + ".json")) + " --out " + quoted(dir / name) + more_options,
                                dir / ("run_" + name));
}

// A CSV file's rows as maps from its header's names.
std::vector<std::map<std::string, double>> read_table(const std::filesystem::path& file) {
  std::string header;
  const auto rows = kerf_test::read_csv_rows(file, header);
  std::vector<std::string> names;
  std::size_t start = 0;
  for (std::size_t comma; (comma = header.find(',', start)) != std::string::npos; start = comma + 1) names.push_back(header.substr(start, comma - start));
  names.push_back(header.substr(start));
  std::vector<std::map<std::string, double>> table;
  for (const auto& row : rows) {
    REQUIRE(row.size() == names.size());
    std::map<std::string, double> named;
    for (std::size_t k = 0; k < names.size(); ++k) named[names[k]] = row[k];
    table.push_back(named);
  }
  return table;
}

// Nothing lost at any change of topology (cuts.csv): the pieces' volume and the body's mass
// equal the uncut mesh's to round-off, the kinetic energy of the state is the same before and
// after (the field is carried over unchanged), and so is the elastic energy, but where the new
// DOF map holds an enrichment at the clamp: chapter 7's transfer sets it to the value the step
// will hold it at (cut_state_transfer.hpp), which moves the elastic energy a little (measured:
// at one change in 212 of the deep passes below, by 0.24 %; the bound, 1 %). Returns how many
// changes moved it by more than round-off.
int check_nothing_lost(const std::filesystem::path& cuts_csv) {
  const auto cuts = read_table(cuts_csv);
  REQUIRE(!cuts.empty());
  int moved = 0;
  for (const auto& c : cuts) {
    INFO("change ", c.at("change"), " at t = ", c.at("t"));
    CHECK(std::abs(c.at("volume_error")) < 1e-12);
    CHECK(std::abs(c.at("mass_error")) < 1e-12);
    CHECK(c.at("kinetic_after") == kerf_test::relative(c.at("kinetic_before"), 1e-9));
    CHECK(c.at("elastic_after") == kerf_test::relative(c.at("elastic_before"), 0.01));
    if (std::abs(c.at("elastic_after") - c.at("elastic_before")) > 1e-9 * c.at("elastic_before")) ++moved;
  }
  return moved;
}

// The energy stays bounded by what gravity put in: kinetic + elastic <= work at every step.
void check_energy_bounded(const std::filesystem::path& energy_csv) {
  for (const auto& e : read_table(energy_csv)) {
    INFO("step ", e.at("step"));
    CHECK(std::isfinite(e.at("kinetic") + e.at("elastic")));
    CHECK(e.at("kinetic") + e.at("elastic") <= e.at("external_work") + 1e-12);
  }
}

// Probe p's displacement at step n from a --probes-history file.
struct History {
  std::vector<std::vector<double>> rows; // step, t, probe, ux, uy, uz
  int probes = 0;
  explicit History(const std::filesystem::path& file) {
    std::string header;
    rows = kerf_test::read_csv_rows(file, header);
    for (const auto& row : rows) probes = std::max(probes, static_cast<int>(row[2]) + 1);
  }
  int steps() const { return static_cast<int>(rows.size()) / probes - 1; }
  std::array<double, 3> u(int n, int p) const {
    const auto& row = rows.at(static_cast<std::size_t>(n * probes + p));
    return {row[3], row[4], row[5]};
  }
};

double distance(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

} // namespace

TEST_CASE("the demo scene written in 08_real_time is examples/08_liver_real_time.json") {
  const std::string program = kerf_test::read_text(source_dir / "chapters" / "08_real_time" / "main.cpp");
  const std::string opening = "demo_scene = R\"(";
  const std::size_t start = program.find(opening);
  REQUIRE(start != std::string::npos);
  const std::size_t end = program.find(")\";", start);
  REQUIRE(end != std::string::npos);
  const json demo = json::parse(program.substr(start + opening.size(), end - start - opening.size()));
  CHECK(demo == read_json(source_dir / "examples" / "08_liver_real_time.json"));
}

TEST_CASE("chapter 7's scene, unchanged, against chapter 7 solved tightly: within 2 % at 4 iterations a step, equal when solved tightly") {
  // Chapter 7's example at 2000 tets, 2.5 s: the blade cuts 6 cm deep across the right lobe
  // from 0.5 s to 1.7 s and the liver rings down. The reference is chapter 7's Newton step
  // (CHOLMOD) to a relative residual of 1e-9. Six probes in the front half, which sags and
  // swings: the largest displacement is about 6 cm.
  const auto dir = kerf_test::fresh_dir("chapter08_against_07");
  kerf_test::write_text(dir / "probes.csv", "x,y,z\n0.05,-0.04,0.0\n-0.04,-0.04,0.0\n0.09,-0.02,0.02\n0.0,-0.05,0.01\n0.06,0.01,0.03\n0.02,-0.02,0.02\n");
  const std::string probes = " --probes " + quoted(dir / "probes.csv") + " --probes-history ";
  const json scene = small_scene(2000, 250);
  json newton = scene;
  newton["time"]["corotation"] = "newton";
  newton["time"]["tolerance"] = 1e-9;
  newton["solver"] = {{"type", "cholmod"}};
  json tight = scene;
  tight["time"]["iterations"] = 0;
  tight["time"]["tolerance"] = 1e-9;
  const auto reference = run_scene(chapter_07, newton, dir, "newton", probes + quoted(dir / "newton.csv"));
  const auto fast = run_scene(chapter_08, scene, dir, "fast", probes + quoted(dir / "fast.csv"));
  const auto exact = run_scene(chapter_08, tight, dir, "tight", probes + quoted(dir / "tight.csv"));
  INFO(reference.err, fast.err, exact.err);
  REQUIRE(reference.exit_status == 0);
  REQUIRE(fast.exit_status == 0);
  REQUIRE(exact.exit_status == 0);
  CHECK(fast.err.empty());
  const History newton_history(dir / "newton.csv"), fast_history(dir / "fast.csv"), tight_history(dir / "tight.csv");
  REQUIRE(newton_history.steps() == 250);
  REQUIRE(fast_history.steps() == 250);
  double largest = 0.0, fast_error = 0.0, tight_error = 0.0;
  for (int n = 0; n <= 250; ++n)
    for (int p = 0; p < newton_history.probes; ++p) {
      largest = std::max(largest, distance(newton_history.u(n, p), {0, 0, 0}));
      fast_error = std::max(fast_error, distance(newton_history.u(n, p), fast_history.u(n, p)));
      tight_error = std::max(tight_error, distance(newton_history.u(n, p), tight_history.u(n, p)));
    }
  // The final sag: the largest downward displacement of a probe at 2.5 s; the mean opening of
  // the wound at 2.5 s (opening.csv).
  const auto sag = [](const History& h) {
    double s = 0.0;
    for (int p = 0; p < h.probes; ++p) s = std::max(s, -h.u(250, p)[2]);
    return s;
  };
  const double opening_07 = read_table(dir / "newton" / "opening.csv").back().at("mean_opening");
  const double opening_08 = read_table(dir / "fast" / "opening.csv").back().at("mean_opening");
  MESSAGE("largest displacement " << largest << " m; 4 iterations a step: trajectories within " << 100 * fast_error / largest
                                  << " %, sag " << sag(fast_history) << " m against " << sag(newton_history) << " m, mean opening "
                                  << opening_08 << " m against " << opening_07 << " m; solved tightly: within " << tight_error / largest);
  // Measured: 0.73 %, sag 42.62 against 42.61 mm, mean opening 6.285 against 6.276 mm (0.15 %
  // here, 0.78-0.80 % in other runs: which tets the blade crosses depends on the state to
  // round-off, and the BLAS's threads and the order of the pieces' sums change the rounding);
  // tightly, equal to the printed digits. The goal, and the bound: 2 %.
  CHECK(largest > 0.05);
  CHECK(fast_error <= 0.02 * largest);
  CHECK(sag(fast_history) == kerf_test::relative(sag(newton_history), 0.02));
  CHECK(opening_08 == kerf_test::relative(opening_07, 0.02));
  // Solved to 1e-9, chapter 8's step is chapter 7's Newton step, cut for cut: the bound is the
  // probes' printed digits (%.9e of centimetres) and the two solves' 1e-9.
  CHECK(tight_error <= 1e-6 * largest);
  CHECK(check_nothing_lost(dir / "fast" / "cuts.csv") == 0);
  // timings.csv: a row a step, its wall clock increasing, simulate_ms the sum of its parts.
  const auto timings = read_table(dir / "fast" / "timings.csv");
  REQUIRE(timings.size() == 250);
  for (std::size_t k = 0; k < timings.size(); ++k) {
    const auto& r = timings[k];
    CHECK(r.at("step") == k + 1);
    if (k > 0) CHECK(r.at("wall_s") >= timings[k - 1].at("wall_s"));
    CHECK(r.at("simulate_ms") ==
          kerf_test::relative(r.at("blade_ms") + r.at("topology_ms") + r.at("local_ms") + r.at("global_ms") + r.at("other_ms"), 1e-3));
  }
}

TEST_CASE("a blade over the same tets twice, and a freed piece, which falls as a free body") {
  const auto dir = kerf_test::fresh_dir("chapter08_twice");
  SUBCASE("the same plane cut twice") {
    // The demo's blade across the right lobe (0.2 s to 0.8 s), lifted above the organ and
    // carried back, then down into the same plane again for a second pass (1.1 s to 1.7 s): the
    // second sheet lies in the tets the first crossed.
    json twice = small_scene(1000, 250);
    twice["blade"]["path"] = {upright(0.2, 0.12, -0.005), upright(0.8, -0.03, -0.005), upright(0.9, -0.03, -0.005, 0.2, 0.11),
                              upright(1.0, 0.12, -0.005, 0.2, 0.11), upright(1.1, 0.12, -0.005), upright(1.7, -0.03, -0.005)};
    const auto result = run_scene(chapter_08, twice, dir, "twice");
    INFO(result.out, result.err);
    REQUIRE(result.exit_status == 0);
    CHECK(result.err.empty());
    CHECK(number_after(result.out, "topology changes, ") == 2); // "..., 2 sheets"
    CHECK(check_nothing_lost(dir / "twice" / "cuts.csv") == 0);
    check_energy_bounded(dir / "twice" / "energy.csv");
  }
  SUBCASE("a guillotine frees the front of the right lobe: it falls at g, slowed by the mass damping only") {
    // Chapter 7's guillotine: an edge along x, wider than the organ, coming down through it in
    // the plane y = -0.05 between 0.5 s and 1.3 s. After the last change nothing holds the
    // front piece: its centre falls as z(T) = v0 (1 - e^(-alpha T)) / alpha - (g / alpha)
    // (T - (1 - e^(-alpha T)) / alpha), alpha = 2 / s; the probe in it follows within 5 %
    // (chapter 7's test says why 5 %: the piece springs back from the stretch it hung in).
    json guillotine = small_scene(2000, 200);
    guillotine["blade"] = {{"samples", 31},
                           {"path", {{{"time", 0.5}, {"edge", {std::array{-0.15, -0.05, 0.12}, std::array{0.15, -0.05, 0.12}}}},
                                     {{"time", 1.3}, {"edge", {std::array{-0.15, -0.05, -0.16}, std::array{0.15, -0.05, -0.16}}}}}}};
    kerf_test::write_text(dir / "probes.csv", "x,y,z\n0.02,-0.062,0.02\n0.025,0.02,0.0\n");
    const auto result =
        run_scene(chapter_08, guillotine, dir, "guillotine", " --probes " + quoted(dir / "probes.csv") + " --probes-history " + quoted(dir / "history.csv"));
    INFO(result.out, result.err);
    REQUIRE(result.exit_status == 0);
    const auto cuts = read_table(dir / "guillotine" / "cuts.csv");
    REQUIRE(!cuts.empty());
    const History history(dir / "history.csv");
    const double dt = 0.01, alpha = 2.0, g = 9.81;
    const int release = static_cast<int>(std::lround(cuts.back().at("t") / dt)), last = 200;
    REQUIRE(release + 20 < last);
    const double v0 = (history.u(release + 1, 0)[2] - history.u(release - 1, 0)[2]) / (2 * dt);
    const double T = (last - release) * dt, decay = (1.0 - std::exp(-alpha * T)) / alpha;
    const double expected = v0 * decay - g / alpha * (T - decay);
    const double fallen = history.u(last, 0)[2] - history.u(release, 0)[2];
    MESSAGE("released at t = " << release * dt << " s with v0 = " << v0 << " m/s; fell " << fallen << " m in " << T << " s, damped free fall "
                               << expected << " m; behind the cut " << history.u(last, 1)[2] << " m");
    CHECK(fallen == kerf_test::relative(expected, 0.05));
    CHECK(std::abs(history.u(last, 1)[2]) < 0.02);
    CHECK(check_nothing_lost(dir / "guillotine" / "cuts.csv") == 0);
  }
}

TEST_CASE("many passes: 1000 steps with the blade cutting, and where 4 iterations a step fail") {
  const auto dir = kerf_test::fresh_dir("chapter08_passes");
  // Fourteen passes of the blade between x = `from` and x = `to` and back, 6 mm apart in y, each
  // 0.7 s, turning in one step: a new sheet each pass that leaves the organ.
  const auto passes = [](double from, double to, double z_bottom) {
    json path = json::array();
    double t = 0.02;
    for (int k = 0; k < 14; ++k) {
      const double y = -0.045 + 0.006 * k;
      path.push_back(upright(t, k % 2 == 0 ? from : to, y, 0.09, z_bottom));
      t += 0.7;
      path.push_back(upright(t, k % 2 == 0 ? to : from, y, 0.09, z_bottom));
      t += 0.01;
    }
    return path;
  };
  SUBCASE("shallow passes through the organ (to 3 cm above its base) on 1000 tets: nothing lost, energy bounded") {
    json shallow = small_scene(1000, 1000);
    shallow["blade"]["path"] = passes(0.13, -0.13, 0.03);
    const auto result = run_scene(chapter_08, shallow, dir, "shallow");
    INFO(result.out, result.err);
    REQUIRE(result.exit_status == 0);
    CHECK(result.err.empty());
    MESSAGE(result.out.substr(result.out.find("cut: ")));
    // "..., N sheets": a pass whose blade passes above the sagging organ leaves none (measured: 12)
    CHECK(number_after(result.out, "topology changes, ") >= 10);
    CHECK(check_nothing_lost(dir / "shallow" / "cuts.csv") == 0);
    check_energy_bounded(dir / "shallow" / "energy.csv");
  }
  SUBCASE("a spiral inside the right lobe on 2000 tets: the blade cuts at every step for 1000 steps, nothing lost, energy bounded") {
    // The blade plunges through the skin in the first two steps and then follows an Archimedean
    // spiral about the right lobe's axis, r from 7 cm to 1.5 cm in three turns, at a constant
    // 0.8 mm a step, its edge from 9 cm above the lobe's centre to 2 cm below it. It never
    // leaves the tissue, so the cut is one sheet, offered the blade's edge at every step and
    // keeping one every four or five (the default quad, a quarter of the mean edge); a spiral
    // never turns back on itself, so the sheet refuses no quad. The coils it leaves hang from
    // the lobe's base. (Quads of 0.2 mm, one a step, change the topology at 363 steps for the
    // same 788 tets, but the sheet's 9000 slivers make the run take 39 s instead of 5.)
    const int steps = 1000;
    const double dt = 0.01, centre_x = 0.025, centre_y = -0.005, r_in = 0.07, r_out = 0.015, turns = 3.0;
    json spiral = small_scene(2000, steps);
    const auto at = [&](double time, double r, double theta) { return upright(time, centre_x + r * std::cos(theta), centre_y + r * std::sin(theta), 0.09, -0.02); };
    json path = json::array({at(0.0, 0.085, 0.0)});
    const int keys = 400;
    const double theta_end = 2.0 * std::acos(-1.0) * turns;
    const auto radius = [&](double theta) { return r_in - (r_in - r_out) * theta / theta_end; };
    double length = 0.0; // the spiral's arc length, summed over the keyframes' chords
    std::vector<double> lengths{0.0};
    for (int k = 1; k <= keys; ++k) {
      const double a = theta_end * (k - 1) / keys, b = theta_end * k / keys;
      length += std::hypot(radius(b) * std::cos(b) - radius(a) * std::cos(a), radius(b) * std::sin(b) - radius(a) * std::sin(a));
      lengths.push_back(length);
    }
    const double start = 2 * dt, end = (steps - 0.5) * dt; // in the tissue from the second step to the last
    for (int k = 0; k <= keys; ++k) {
      const double theta = theta_end * k / keys;
      path.push_back(at(start + (end - start) * lengths[static_cast<std::size_t>(k)] / length, radius(theta), theta));
    }
    spiral["blade"] = {{"path", path}};
    const auto result = run_scene(chapter_08, spiral, dir, "spiral");
    INFO(result.out, result.err);
    REQUIRE(result.exit_status == 0);
    CHECK(result.err.empty());
    MESSAGE(result.out.substr(result.out.find("cut: ")));
    // One sheet: had the blade left the tissue at any step, its next entry would start another.
    CHECK(std::regex_search(result.out, std::regex("topology changes, 1 sheets")));
    // The topology changes wherever a kept quad crosses a tet (measured: 158 changes, 788 tets).
    const auto timings = read_table(dir / "spiral" / "timings.csv");
    REQUIRE(timings.size() == steps);
    int changed = 0, first_change = steps;
    for (const auto& row : timings)
      if (row.at("topology_changed") == 1.0) {
        ++changed;
        first_change = std::min(first_change, static_cast<int>(row.at("step")));
      }
    CHECK(first_change <= 5);
    CHECK(changed >= 140);
    CHECK(check_nothing_lost(dir / "spiral" / "cuts.csv") == 0);
    check_energy_bounded(dir / "spiral" / "energy.csv");
  }
  SUBCASE("deep passes on 2000 tets carve thin slabs: 4 iterations a step make energy, 12 do not") {
    // Seven deep passes leave slabs 6 mm thick, a third of a tet, hanging from the back; they
    // swing faster than four quasi-Newton iterations a step follow. Without the step's energy
    // check the run diverged at step 484; with it (a step that would create more than 1 % of the
    // body's energy is solved on) the run ends, its stored energy bounded by gravity's work, but
    // its steps create energy that the damping then takes: the rest of the balance is negative,
    // by a large part of the work (measured: -0.64 J of 0.73 J). The slabs' motion is wrong.
    // Twelve iterations a step (or chapter 7's checked Newton step) dissipate, as the tight
    // step does (measured: +0.050 J).
    json deep = small_scene(2000, 1000);
    deep["blade"]["path"] = passes(0.11, -0.09, -0.015);
    const auto four = run_scene(chapter_08, deep, dir, "deep_4");
    INFO(four.out, four.err);
    REQUIRE(four.exit_status == 0);
    check_energy_bounded(dir / "deep_4" / "energy.csv");
    const double rest_4 = read_table(dir / "deep_4" / "energy.csv").back().at("numerical");
    deep["time"]["iterations"] = 12;
    const auto twelve = run_scene(chapter_08, deep, dir, "deep_12");
    INFO(twelve.out, twelve.err);
    REQUIRE(twelve.exit_status == 0);
    CHECK(check_nothing_lost(dir / "deep_12" / "cuts.csv") <= 2);
    check_energy_bounded(dir / "deep_12" / "energy.csv");
    const auto energy_12 = read_table(dir / "deep_12" / "energy.csv").back();
    MESSAGE("the rest of the balance after 1000 steps: " << rest_4 << " J at 4 iterations a step, " << energy_12.at("numerical")
                                                        << " J at 12 (gravity's work " << energy_12.at("external_work") << " J)");
    CHECK(rest_4 < -0.2 * energy_12.at("external_work"));
    CHECK(energy_12.at("numerical") > 0.0);
    // Newmark's numerical damping, gamma = 0.6 and beta = (gamma + 1/2)^2 / 4, damps the slabs'
    // fast modes, which four iterations then need not follow: they dissipate (measured: +0.024 J;
    // gamma = 0.55, the demo's, is not enough here: -0.22 J).
    deep["time"]["iterations"] = 4;
    deep["time"]["gamma"] = 0.6;
    deep["time"]["beta"] = 0.3025;
    const auto damped = run_scene(chapter_08, deep, dir, "deep_damped");
    INFO(damped.out, damped.err);
    REQUIRE(damped.exit_status == 0);
    check_energy_bounded(dir / "deep_damped" / "energy.csv");
    const double rest_damped = read_table(dir / "deep_damped" / "energy.csv").back().at("numerical");
    MESSAGE("4 iterations a step at gamma = 0.6: " << rest_damped << " J");
    CHECK(rest_damped > 0.0);
    // Cut through its 1000 steps: the topology changes every four or five steps (measured: 220
    // changes, 816 tets crossed), and nothing is lost at any change but where an enrichment is
    // held at the clamp (check_nothing_lost).
    const auto changes = read_table(dir / "deep_damped" / "cuts.csv");
    MESSAGE(changes.size() << " changes of topology, " << changes.back().at("crossed_tets") << " tets crossed");
    CHECK(changes.size() >= 200);
    CHECK(check_nothing_lost(dir / "deep_damped" / "cuts.csv") <= 2);
  }
}

TEST_CASE("the demo's numerical damping: on the wedge at 10k tets, four iterations a step make energy under the average acceleration rule") {
  // The demo's scene, 200 steps (the blade from 0.5 s to 2 s), frames off: as it is (gamma =
  // 0.55) and with the average acceleration rule (gamma = 1/2, beta = 1/4). Under the latter the
  // wedge's small tets and the cut's slivers ring (their accelerations change sign every step),
  // four iterations from a_{n+1} = a_n do not follow them, and steps make energy: the energy
  // check solves many on (measured: 79 steps of more than 8 evaluations) and the rest of the
  // balance ends negative (-10 mJ). With gamma = 0.55 no step is sent on and the step dissipates,
  // as chapter 7's Newton step does (measured: +10 mJ).
  const auto dir = kerf_test::fresh_dir("chapter08_damping");
  json scene = read_json(source_dir / "examples" / "08_liver_real_time.json");
  scene["time"]["steps"] = 200;
  scene["render"] = {{"every", 0}};
  scene["output"] = {{"every", 200}};
  const auto run = [&](const json& s, const std::string& name) {
    const auto result = run_scene(chapter_08, s, dir, name);
    INFO(result.out, result.err);
    REQUIRE(result.exit_status == 0);
    int sent_on = 0;
    for (const auto& r : read_table(dir / name / "timings.csv")) sent_on += r.at("iterations") > 8;
    const double rest = read_table(dir / name / "energy.csv").back().at("numerical");
    MESSAGE(name << ": " << sent_on << " steps sent on, the rest of the balance " << rest << " J");
    return std::pair{sent_on, rest};
  };
  const auto [damped_sent_on, damped_rest] = run(scene, "gamma_055");
  scene["time"]["gamma"] = 0.5;
  scene["time"]["beta"] = 0.25;
  const auto [average_sent_on, average_rest] = run(scene, "average_acceleration");
  CHECK(damped_sent_on == 0);
  CHECK(damped_rest > 0.0);
  CHECK(average_sent_on >= 20);
  CHECK(average_rest < 0.0);
}

TEST_CASE("the window under xvfb-run, paced by the wall clock, driven by events keyed by time") {
  // A 2000-tet liver (about 2.5 ms a step against a dt of 10 ms: real time with room to spare on
  // a shared core) in a 480 x 360 window. The script presses the left button left of the
  // organ's centre at 0.5 s, drags across it for 2 s, releases, and closes the window at 3 s.
  const auto dir = kerf_test::fresh_dir("chapter08_window");
  const auto play = [&](bool shift) {
    const std::string name = shift ? "shift_drag" : "drag";
    const std::string s = shift ? "1" : "0";
    std::string script = "time,event,x,y,shift\n0.5,press,165,180," + s + "\n";
    for (int k = 1; k <= 20; ++k) script += std::to_string(0.5 + 0.1 * k) + ",move," + std::to_string(165 + 8 * k) + ",180," + s + "\n";
    script += "2.6,release,325,180," + s + "\n3.0,key_q,0,0,0\n";
    kerf_test::write_text(dir / (name + ".csv"), script);
    json scene = read_json(source_dir / "examples" / "08_liver_real_time.json");
    scene["mesh"]["liver"]["tets"] = 2000;
    scene["render"]["width"] = 480;
    scene["render"]["height"] = 360;
    kerf_test::write_text(dir / (name + ".json"), scene.dump());
    const auto result = kerf_test::run_program(with_display(chapter_08 + " --interactive --events " + quoted(dir / (name + ".csv")) + " --scene " +
                                                            quoted(dir / (name + ".json")) + " --out " + quoted(dir / name)),
                                               dir / ("run_" + name));
    INFO(result.out, result.err);
    CHECK(result.exit_status == 0);
    // Nothing on stderr but the meter's warning: on a loaded machine (the suite runs two tests at
    // once, and the software OpenGL's threads draw beside the step's) one second may fall below
    // 0.95 of real time, which the program must say; the run must still end in real time (below).
    std::istringstream err_lines(without_style_warning(result.err));
    for (std::string line; std::getline(err_lines, line);) {
      if (line.rfind("warning: behind real time: ", 0) == 0) MESSAGE(line);
      else CHECK(line.empty());
    }
    const std::regex summary("real time: ([0-9.]+) s simulated in ([0-9.]+) s of wall-clock time \\(factor ([0-9.]+)\\); ([0-9]+) frames "
                             "drawn .*; ([0-9]+) tets cut .*; played 23 events");
    std::smatch match;
    REQUIRE(std::regex_search(result.out, match, summary));
    // Simulated time is wall time: the last step's t within 5 % of its wall clock (measured:
    // 3.11 s in 3.11 s, factor 0.9998), and every step waits for its time, so none is ahead.
    const auto timings = read_table(dir / name / "timings.csv");
    REQUIRE(timings.size() > 200);
    CHECK(timings.back().at("t") == kerf_test::relative(timings.back().at("wall_s"), 0.05));
    for (const auto& r : timings) CHECK(r.at("wall_s") >= r.at("t") - 1e-4);
    CHECK(std::stod(match[4]) >= 20); // frames drawn: the window did not wait for the steps (measured: 156)
    return std::stoi(match[5]);
  };
  const int cut = play(true), turned = play(false);
  MESSAGE("tets cut by the Shift drag: " << cut << ", by the plain drag: " << turned);
  // The Shift drag cuts along its 160 pixels across the organ (measured: 188 tets in 20
  // changes of topology); the plain drag turns the camera and cuts nothing.
  CHECK(cut >= 100);
  CHECK(turned == 0);
}

TEST_CASE("bad input is one line on stderr naming the field, and exit status 2") {
  const auto dir = kerf_test::fresh_dir("chapter08_bad_input");
  const json scene = small_scene(1000, 3);
  const auto refused = [&](json bad, const std::string& name, const std::string& field) {
    check_refused(run_scene(chapter_08, bad, dir, name), field);
  };
  json tet10 = scene;
  tet10["mesh"]["order"] = 2;
  refused(tet10, "tet10", "mesh.order");
  json tip = scene;
  tip["crack_tip"] = json::object();
  refused(tip, "crack_tip", "crack_tip");
  json linear = scene;
  linear["model"] = "linear";
  refused(linear, "linear", "model");
  json moved = scene;
  moved["dirichlet"][0]["displacement"] = {0.0, 0.0, 0.01};
  refused(moved, "moved", "dirichlet[0]");
  json negative = scene;
  negative["time"]["iterations"] = -1;
  refused(negative, "negative", "time.iterations");
  json euler = scene;
  euler["time"]["integrator"] = "backward_euler";
  refused(euler, "euler", "time.integrator");
  json no_blade = scene;
  no_blade.erase("blade");
  refused(no_blade, "no_blade", "blade");
  // Chapter 7 has no iterations to set.
  json iterations = scene;
  iterations["time"]["iterations"] = 4;
  check_refused(run_scene(chapter_07, iterations, dir, "iterations_07"), "time.iterations");
  check_refused(kerf_test::run_program(chapter_08 + " --tets 10 --out " + quoted(dir / "tets"), dir / "run_tets"), "--tets");
  // The events file: a row whose time is not a number, one out of order, an unknown event, a step
  // header (chapter 7's) where chapter 8 keys by time.
  for (const auto& [name, text, field] : std::vector<std::array<std::string, 3>>{
           {"not_a_time", "time,event,x,y,shift\n0.5,press,10,10,1\nsoon,move,20,10,1\n", "row 3.time"},
           {"backwards", "time,event,x,y,shift\n0.5,press,10,10,1\n0.4,move,20,10,1\n", "row 3.time"},
           {"drag", "time,event,x,y,shift\n0.5,drag,10,10,1\n", "row 2.event"},
           {"steps", "step,event,x,y,shift\n2,press,10,10,1\n", "header"}}) {
    kerf_test::write_text(dir / (name + ".csv"), text);
    const auto result = kerf_test::run_program(with_display(chapter_08 + " --quiet --tets 1000 --interactive --events " + quoted(dir / (name + ".csv")) +
                                                            " --out " + quoted(dir / name)),
                                               dir / ("run_" + name));
    check_refused({result.exit_status, result.out, without_style_warning(result.err)}, field);
  }
}

TEST_CASE("the frames: a PNG every render.every steps and the animated PNG; --help") {
  const auto dir = kerf_test::fresh_dir("chapter08_frames");
  json scene = small_scene(1000, 4);
  scene["render"] = {{"every", 2}, {"width", 160}, {"height", 120}};
  kerf_test::write_text(dir / "frames.json", scene.dump(2));
  const auto result =
      kerf_test::run_program(with_display(chapter_08 + " --scene " + quoted(dir / "frames.json") + " --out " + quoted(dir / "out")), dir / "run");
  INFO(result.out, result.err);
  REQUIRE(result.exit_status == 0);
  CHECK(result.out.find("wrote 2 PNG frames") != std::string::npos); // steps 2 and 4
  const auto chunks = kerf_test::png_chunks(dir / "out" / "liver_cut.png");
  const auto control = std::find_if(chunks.begin(), chunks.end(), [](const auto& c) { return c.first == "acTL"; });
  REQUIRE(control != chunks.end());
  CHECK(kerf_test::big_endian_32(control->second, 0) == 2);
  const auto help = kerf_test::run_program(chapter_08 + " --help", dir / "help");
  CHECK(help.exit_status == 0);
  for (const char* option : {"--tets", "--interactive", "--events", "--scene", "--out", "--probes-history", "time,event,x,y,shift"})
    CHECK(help.out.find(option) != std::string::npos);
}
