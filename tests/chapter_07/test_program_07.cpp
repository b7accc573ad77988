// Chapter 7 from the command line: the demo scene is the example file; a long scripted cut in
// three passes loses no volume, no mass and no energy at any of its topology changes and keeps its
// energy bounded by the work of gravity; bad input is one line naming the field; a blade that
// leaves the organ and a cut that frees a piece, which then falls; the window driven by scripted
// mouse events under xvfb-run (Shift + drag cuts, a drag alone turns the camera), the PNG frames
// and their animated PNG; --help.
//
// The livers are small (--tets 2000 or 1000, "render": {"every": 0} where no frame is needed), so
// that each case takes seconds; the demo's 10 000 tets and 250 frames run as the example scene's
// test (tests/CMakeLists.txt).
#include "support/program_checks.hpp"
#include "support/run_program.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
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
const std::filesystem::path source_dir = KERF_SOURCE_DIR;

json example_scene() { return json::parse(kerf_test::read_text(source_dir / "examples" / "07_liver_cut.json")); }

// The demo scene with a liver of `tets` tets, `steps` steps, no frames and no .vtu but the last.
json small_scene(int tets, int steps) {
  json scene = example_scene();
  scene["mesh"]["liver"]["tets"] = tets;
  scene["time"]["steps"] = steps;
  scene["render"] = {{"every", 0}};
  scene["output"] = {{"every", steps}};
  return scene;
}

// A keyframe of the blade: its edge from `start` to `end` at `time`.
json keyframe(double time, const std::array<double, 3>& start, const std::array<double, 3>& end) {
  return {{"time", time}, {"edge", {start, end}}};
}

// Writes `scene` as dir/name.json and runs the program on it, out in dir/name.
kerf_test::ProgramResult run_scene(const json& scene, const std::filesystem::path& dir, const std::string& name,
                                   const std::string& more_options = "") {
  kerf_test::write_text(dir / (name + ".json"), scene.dump(2));
  return kerf_test::run_program(chapter_07 + " --scene " + quoted(dir / (name + ".json")) + " --out " + quoted(dir / name) + more_options,
                                dir / ("run_" + name));
}

// The columns of cuts.csv.
namespace column {
enum : std::size_t { change, t, crossed_tets, enrichments, unknowns, volume_error, mass_error, kinetic_before, kinetic_after, elastic_before, elastic_after };
} // namespace column

} // namespace

TEST_CASE("the demo scene written in 07_liver is examples/07_liver_cut.json") {
  // The program runs its demo without a file; the example is that demo as a file. The two must
  // not drift: we take the raw string literal demo_scene out of main.cpp and compare the scenes
  // as JSON values (the same fields and numbers, whatever the spacing).
  const std::string program = kerf_test::read_text(source_dir / "chapters" / "07_liver" / "main.cpp");
  const std::string opening = "demo_scene = R\"(";
  const std::size_t start = program.find(opening);
  REQUIRE(start != std::string::npos);
  const std::size_t end = program.find(")\";", start);
  REQUIRE(end != std::string::npos);
  const json demo = json::parse(program.substr(start + opening.size(), end - start - opening.size()));
  CHECK(demo == example_scene());
  CHECK(demo.at("blade").at("path").size() == 2);
}

TEST_CASE("nothing is lost over a long scripted cut: 10 s, three passes, every topology change checked") {
  // The demo's liver at 2000 tets, dt = 10 ms as in the demo, 1000 steps: 10 s simulated. The
  // blade makes three passes, each entering from outside and leaving on the other side: across
  // the whole organ along -x in the plane y = -0.005 down to z = 0 (0.5 s to 2.5 s); outside, to
  // y = -0.04, and back along +x down to z = -0.015 (3 s to 5 s); outside again, to y = -0.025,
  // and along -x down to z = -0.005 (5.5 s to 7.5 s); then 2.5 s at rest with three open wounds.
  // Each cut stops above the held underside, so the organ stays in one piece but for a sliver
  // between the sheets near the skin that the third pass cuts loose (measured: the kinetic
  // energy levels off at 2.9 mJ from 8 s on, a sliver of 0.24 g at its terminal speed
  // g / alpha = 4.9 m/s, 14 m down in the last .vtu). So the run does not end at rest; the
  // energy bound below holds all the same.
  const auto dir = kerf_test::fresh_dir("chapter07_long_cut");
  json scene = small_scene(2000, 1000);
  scene["blade"]["path"] = {keyframe(0.5, {0.12, -0.005, 0.09}, {0.12, -0.005, 0.0}),     keyframe(2.5, {-0.13, -0.005, 0.09}, {-0.13, -0.005, 0.0}),
                            keyframe(3.0, {-0.13, -0.04, 0.09}, {-0.13, -0.04, -0.015}),  keyframe(5.0, {0.13, -0.04, 0.09}, {0.13, -0.04, -0.015}),
                            keyframe(5.5, {0.13, -0.025, 0.09}, {0.13, -0.025, -0.005}), keyframe(7.5, {-0.13, -0.025, 0.09}, {-0.13, -0.025, -0.005})};
  const auto run = run_scene(scene, dir, "long");
  INFO(run.out, run.err);
  REQUIRE(run.exit_status == 0);
  CHECK(run.err.empty()); // no Newton step missed its tolerance

  std::string header;
  const auto cuts = kerf_test::read_csv_rows(dir / "long" / "cuts.csv", header);
  CHECK(header == "change,t,crossed_tets,enrichments,unknowns,volume_error,mass_error,kinetic_before,kinetic_after,elastic_before,elastic_after");
  // Measured: 68 topology changes, 237 tets crossed, changes in each pass's time.
  REQUIRE(cuts.size() >= 20);
  CHECK(number_after(run.out, "tets crossed, ") == cuts.size()); // "cut: K tets crossed, N topology changes"
  CHECK(number_after(run.out, "cut: ") == cuts.back()[column::crossed_tets]);
  std::smatch sheets;
  REQUIRE(std::regex_search(run.out, sheets, std::regex("([0-9]+) sheets of")));
  CHECK(std::stoi(sheets[1]) == 3); // one per pass
  const std::array<std::pair<double, double>, 3> passes = {{{0.5, 2.5}, {3.0, 5.0}, {5.5, 7.5}}};
  for (const auto& [from, to] : passes)
    CHECK(std::count_if(cuts.begin(), cuts.end(), [&](const auto& row) { return row[column::t] > from && row[column::t] <= to + 0.5; }) >= 3);
  int last_crossed = 0;
  for (const auto& row : cuts) {
    INFO("topology change ", row[column::change], " at t = ", row[column::t]);
    // The crossing state only grows: a crossed tet stays crossed.
    CHECK(row[column::crossed_tets] > last_crossed);
    last_crossed = static_cast<int>(row[column::crossed_tets]);
    // The pieces' volumes (the weights of their quadrature rules) and the mass of a unit
    // translation against the uncut mesh's: each a sum over the 2037 tets of positive terms,
    // exact up to the round-off of that sum, n eps ~ 2e-13 at worst. Measured: at most 8.9e-16
    // and 1.2e-15. The bound, 1e-12, is a lost sliver of 1e-12 of the organ, 1.6 pg of liver.
    CHECK(std::abs(row[column::volume_error]) < 1e-12);
    CHECK(std::abs(row[column::mass_error]) < 1e-12);
    // The state transfer carries the same field into the new DOFs (there is no "crack_tip" field,
    // whose branch functions could not represent the old field exactly): each energy recomputed
    // from the new matrices is the old one to round-off. Measured: relative differences of at most
    // 3.8e-16 (kinetic) and 1.7e-15 (elastic: the old model's W by energy(), the strain density,
    // the new one's by the assembly's 1/2 d^T K_q d), also when the kinetic energy was 7e-11 J.
    CHECK(std::abs(row[column::kinetic_after] - row[column::kinetic_before]) <= 1e-12 * std::abs(row[column::kinetic_before]));
    CHECK(std::abs(row[column::elastic_after] - row[column::elastic_before]) <= 1e-12 * std::abs(row[column::elastic_before]));
  }

  // The energy account: finite at every step, and kinetic + elastic never above the work of
  // gravity. On this path (nonlinear_newmark.hpp) the balance closes by definition: the numerical
  // column is its rest, so kinetic + elastic = work - damping - numerical (the run starts at rest
  // and unstressed), and with damping >= 0 "stored <= work" fails only if the integrator puts in
  // more than damping takes out. Measured: (kinetic + elastic) / work at most 0.92. The rest itself
  // is bounded below; dissipated = damping + numerical, each read back exactly.
  const auto energy = kerf_test::read_csv_rows(dir / "long" / "energy.csv", header);
  CHECK(header == "step,t,kinetic,elastic,external_work,dissipated,damping,numerical");
  REQUIRE(energy.size() == 1001);
  CHECK(energy.back()[1] == kerf_test::relative(10.0, 1e-12));
  enum : std::size_t { kinetic = 2, elastic, work_done, dissipated, damping, numerical };
  std::vector<double> change_times;
  for (const auto& row : cuts) change_times.push_back(row[column::t]);
  const auto at_change = [&](double t) {
    return std::any_of(change_times.begin(), change_times.end(), [t](double c) { return std::abs(c - t) < 1e-9; });
  };
  double largest_ratio = 0.0, largest_rest = 0.0, largest_step_rest = 0.0, largest_change_rest = 0.0;
  for (std::size_t n = 0; n < energy.size(); ++n) {
    const auto& row = energy[n];
    INFO("step ", row[0]);
    REQUIRE(row.size() == 8);
    CHECK(std::all_of(row.begin(), row.end(), [](double x) { return std::isfinite(x); }));
    const double stored = row[kinetic] + row[elastic], work = row[work_done];
    CHECK(stored <= work);
    if (work > 0.0) largest_ratio = std::max(largest_ratio, stored / work);
    CHECK(row[dissipated] == row[damping] + row[numerical]);
    largest_rest = std::max(largest_rest, std::abs(row[numerical]));
    if (n == 0) continue;
    // Each step's damping is dt v_bar^T C v_bar >= 0 (still clamps, C = 2 M + 0.01 K_R).
    CHECK(row[damping] >= energy[n - 1][damping] - 1e-14 * work);
    const double step_rest = std::abs(row[numerical] - energy[n - 1][numerical]);
    if (at_change(row[1])) largest_change_rest = std::max(largest_change_rest, step_rest);
    else largest_step_rest = std::max(largest_step_rest, step_rest);
  }
  const double total_work = energy.back()[work_done];
  MESSAGE("topology changes: " << cuts.size() << ", tets crossed: " << cuts.back()[column::crossed_tets]
                               << ", largest (kinetic + elastic) / work: " << largest_ratio << "; damping " << energy.back()[damping]
                               << " J, numerical rest " << energy.back()[numerical] << " J (largest |rest| " << largest_rest
                               << " J) of a work of " << total_work << " J; largest |rest| of one step " << largest_step_rest
                               << " J, of a step with a topology change " << largest_change_rest << " J");
  // The rest is the frozen step's error with the average acceleration rule's on the corotated
  // force, first order in dt: on this liver sagging before the blade enters (0.5 s, CHOLMOD) it is
  // 6.1, 3.7 and 2.0 mJ at dt = 10, 5 and 2.5 ms, Newton's 3.7 and 0.95 mJ; CG's tolerance 1e-3
  // moves it by 0.4 %. Measured here: 9.8 mJ, 3.0 % of the work, at the end (its largest). A tenth
  // of the work leaves a factor of three.
  CHECK(largest_rest <= 0.1 * total_work);
  // A change of topology carries the state (cuts.csv: the energies to round-off), so the step
  // that makes it leaves no more rest than an ordinary step. Measured: at most 2.2e-5 J at a
  // change, 4.4e-4 J at the other steps (the largest in the first swing under sudden gravity); a
  // transfer that made or lost 0.3 % of the elastic energy (0.16 J at the end) would fail this.
  CHECK(largest_change_rest <= largest_step_rest);

  // timings.csv: a row per step from 0, the topology flag set on exactly the steps of cuts.csv.
  const auto timings = kerf_test::read_csv_rows(dir / "long" / "timings.csv", header);
  CHECK(header == "step,t,unknowns,crossed_tets,topology_changed,blade_s,topology_s,assemble_s,solve_s,render_s,output_s");
  REQUIRE(timings.size() == 1001);
  CHECK(std::count_if(timings.begin(), timings.end(), [](const auto& row) { return row[4] == 1.0; }) == static_cast<long>(cuts.size()));
  CHECK(timings.back()[2] == cuts.back()[column::unknowns]);
}

TEST_CASE("with chapter 5's branch functions at the front the cut stays stable: every topology change keeps the energies") {
  // The demo's cut on a liver of 1000 tets with "crack_tip": the tets the front crosses get the
  // four branch functions (topological rule), and at each change of topology the field near the
  // front is fitted (cut_state_transfer.hpp) instead of carried. Two seconds: the whole cut and
  // 0.3 s after the blade stops. Before the fit, the rule that kept each node's branch values
  // put +19 % and +20 % elastic energy in at two changes and the run diverged at t = 1.3 s
  // (chapter 7's results).
  const auto dir = kerf_test::fresh_dir("chapter07_branch_cut");
  json scene = small_scene(1000, 200);
  scene["crack_tip"] = {{"enrichment", "branch"}, {"radius", 0}, {"front_points", 2}, {"front_grading", 4}};
  const auto run = run_scene(scene, dir, "branch");
  INFO(run.out, run.err);
  REQUIRE(run.exit_status == 0);
  CHECK(run.err.empty());

  std::string header;
  const auto cuts = kerf_test::read_csv_rows(dir / "branch" / "cuts.csv", header);
  // Measured: 17 topology changes, 50 tets crossed.
  REQUIRE(cuts.size() >= 10);
  double largest_elastic = 0.0, largest_total = 0.0, largest_volume = 0.0;
  for (const auto& row : cuts) {
    INFO("topology change ", row[column::change], " at t = ", row[column::t]);
    const double elastic_change = std::abs(row[column::elastic_after] - row[column::elastic_before]) / row[column::elastic_before];
    const double before = row[column::kinetic_before] + row[column::elastic_before];
    const double total_change = std::abs(row[column::kinetic_after] + row[column::elastic_after] - before) / before;
    largest_elastic = std::max(largest_elastic, elastic_change);
    largest_total = std::max(largest_total, total_change);
    largest_volume = std::max(largest_volume, std::abs(row[column::volume_error]));
    // Measured: at most 0.83 % of the elastic energy and 0.83 % of kinetic + elastic, up or down
    // (the new functions cannot hold the old front's field exactly). 2 % is the bound: a tenth of
    // what the old rule injected, and less than the damping takes out over the 40 ms between
    // two changes (alpha = 2 s^-1 on the kinetic energy alone: 8 % of it).
    CHECK(elastic_change < 0.02);
    CHECK(total_change < 0.02);
    // The rules of the tets with branch functions (collapsed and graded, front_points 2, grading 4)
    // do not sum to the tets' volumes to round-off, unlike the pieces' rules of chapter 4: measured
    // at most 7.8e-4 of the organ's volume (7.3e-4 with an earlier build: the cut follows the body, so
    // the numbers move with round-off); 2e-3 catches a rule that lost a piece.
    CHECK(std::abs(row[column::volume_error]) < 2e-3);
  }
  const auto energy = kerf_test::read_csv_rows(dir / "branch" / "energy.csv", header);
  REQUIRE(energy.size() == 201);
  for (const auto& row : energy) {
    INFO("step ", row[0]);
    CHECK(std::all_of(row.begin(), row.end(), [](double x) { return std::isfinite(x); }));
    CHECK(row[2] + row[3] <= row[4]); // kinetic + elastic <= the work of gravity
  }
  MESSAGE("branch functions: " << cuts.size() << " topology changes, largest change of the elastic energy " << largest_elastic
                               << ", of kinetic + elastic " << largest_total << ", largest volume error " << largest_volume);
}

TEST_CASE("the sinusoidal cut opens: opening.csv is 0 until the blade enters, then the gap grows as the sheet does") {
  // examples/07_liver_sine_cut.json (a blade whose edge swings as a sine while it crosses part of
  // the organ, Paulus section 5.3) at 2000 tets and 200 steps. Before the blade reaches the organ
  // there is no cut inside it: nothing to measure. Once it cuts, gravity pulls the lips apart: a
  // positive gap. The measured area only grows: the sheet's triangles, and with them the sample
  // points inside the organ, are never taken away (xfem/cut_opening.hpp).
  const auto dir = kerf_test::fresh_dir("chapter07_sine_cut");
  json scene = json::parse(kerf_test::read_text(source_dir / "examples" / "07_liver_sine_cut.json"));
  scene["mesh"]["liver"]["tets"] = 2000;
  scene["time"]["steps"] = 200;
  scene["render"] = {{"every", 0}};
  scene["output"] = {{"every", 200}};
  const auto run = run_scene(scene, dir, "sine");
  INFO(run.out, run.err);
  REQUIRE(run.exit_status == 0);
  std::string header;
  const auto opening = kerf_test::read_csv_rows(dir / "sine" / "opening.csv", header);
  CHECK(header == "step,t,cut_area,gap_volume,mean_opening,max_opening,max_jump");
  REQUIRE(opening.size() == 201);
  double last_area = 0.0;
  for (const auto& row : opening) {
    INFO("step ", row[0], ", t = ", row[1]);
    REQUIRE(row.size() == 7);
    CHECK(std::all_of(row.begin(), row.end(), [](double x) { return std::isfinite(x); }));
    if (row[1] < 0.5) CHECK(row[2] == 0.0); // the blade starts at 0.5 s, outside the organ
    CHECK(row[2] >= last_area);
    CHECK(row[6] >= row[5]); // |[[u]]| >= [[u]] . n
    last_area = row[2];
  }
  const auto& end = opening.back();
  MESSAGE("at t = " << end[1] << " s: cut area " << end[2] << " m^2, gap " << end[3] << " m^3, mean opening " << end[4]
                    << " m, largest " << end[5] << " m");
  CHECK(end[2] > 0.0);
  CHECK(end[3] > 0.0);
  CHECK(end[4] == kerf_test::relative(end[3] / end[2], 1e-6));
  CHECK(end[5] > 0.0);
}

TEST_CASE("bad input is one line on stderr naming the field, and exit status 2") {
  const auto dir = kerf_test::fresh_dir("chapter07_input");
  const auto run = [&](const json& scene, const std::string& name, const std::string& more = "") {
    return run_scene(scene, dir, name, " --quiet" + more);
  };
  const json small = small_scene(1000, 20);

  SUBCASE("the blade path") {
    // The demo's first keyframe moved into the right lobe: the cut would start from nowhere.
    json inside = small;
    inside["blade"]["path"][0] = keyframe(0.5, {0.05, -0.005, 0.09}, {0.05, -0.005, 0.0});
    check_refused(run(inside, "inside"), "blade.path");
    json repeated = small;
    repeated["blade"]["path"][1]["time"] = 0.5;
    check_refused(run(repeated, "repeated"), "blade.path");
    json backward = small;
    backward["blade"]["path"][1]["time"] = 0.2;
    check_refused(run(backward, "backward"), "blade.path");
    json point = small;
    point["blade"]["path"][1]["edge"] = {{-0.03, -0.005, 0.05}, {-0.03, -0.005, 0.05}};
    check_refused(run(point, "point"), "blade.path");
    json none = small;
    none.erase("blade");
    check_refused(run(none, "no_blade"), "blade");
  }
  SUBCASE("the liver's size, in the scene and on the command line") {
    for (const int tets : {999, 2'000'000}) {
      json size = small;
      size["mesh"]["liver"]["tets"] = tets;
      check_refused(run(size, "tets_" + std::to_string(tets)), "mesh.liver.tets");
      check_refused(run(small, "option_" + std::to_string(tets), " --tets " + std::to_string(tets)), "--tets");
    }
    check_refused(run(small, "option_text", " --tets many"), "--tets");
    check_refused(run(small, "option_fraction", " --tets 1500.5"), "--tets");
  }
  SUBCASE("what chapter 7 does not take") {
    json cuts = small;
    cuts["cuts"] = {{{"rectangle", {{"origin", {0.0, -0.1, 0.0}}, {"edge1", {0.0, 0.2, 0.0}}, {"edge2", {0.0, 0.0, 0.1}}}}}};
    check_refused(run(cuts, "cuts"), "cuts");
    json euler = small;
    euler["time"] = {{"integrator", "backward_euler"}, {"dt", 0.01}, {"steps", 20}};
    check_refused(run(euler, "backward_euler"), "time.integrator");
  }
  SUBCASE("the events file") {
    check_refused(run(small, "events_alone", " --events " + quoted(dir / "events.csv")), "--events");
    // A malformed script is read once the window is open, so this one needs the display.
    kerf_test::write_text(dir / "bad_events.csv", "step,event,x,y,shift\n2,press,480,360,1\n3,drag,500,360,1\n");
    const auto bad = kerf_test::run_program(with_display(chapter_07 + " --quiet --tets 1000 --interactive --events " + quoted(dir / "bad_events.csv") +
                                                         " --out " + quoted(dir / "bad_events")),
                                            dir / "run_bad_events");
    check_refused({bad.exit_status, bad.out, without_style_warning(bad.err)}, "row 3.event");
    kerf_test::write_text(dir / "no_header.csv", "2,press,480,360,1\n");
    const auto headless = kerf_test::run_program(with_display(chapter_07 + " --quiet --tets 1000 --interactive --events " +
                                                              quoted(dir / "no_header.csv") + " --out " + quoted(dir / "no_header")),
                                                 dir / "run_no_header");
    check_refused({headless.exit_status, headless.out, without_style_warning(headless.err)}, "header");
  }
}

TEST_CASE("a blade that leaves the organ closes its sheet; the run goes on") {
  const auto dir = kerf_test::fresh_dir("chapter07_through");
  // One pass across the whole organ (the demo's edge, from x = 0.12 to x = -0.13, beyond the
  // left lobe's tip at x = -0.10) in 0.8 s, then 0.2 s more: the sheet is closed by the edge
  // that has left the body.
  json through = small_scene(1000, 100);
  through["blade"]["path"] = {keyframe(0.1, {0.12, -0.005, 0.09}, {0.12, -0.005, 0.0}), keyframe(0.9, {-0.13, -0.005, 0.09}, {-0.13, -0.005, 0.0})};
  const auto result = run_scene(through, dir, "through");
  INFO(result.out, result.err);
  CHECK(result.exit_status == 0);
  CHECK(result.err.empty());
  CHECK(number_after(result.out, "cut: ") > 0);                   // "cut: K tets crossed"
  CHECK(number_after(result.out, "topology changes, ") == 1);    // "..., 1 sheets of N triangles"
}

TEST_CASE("a cut that frees a piece: the piece falls as a free body with the scene's damping") {
  const auto dir = kerf_test::fresh_dir("chapter07_free_piece");
  // A guillotine: an edge along x, wider than the organ (x from -0.15 to 0.15), in the plane
  // y = -0.05, coming down from above the organ (z = 0.12) to below it (z = -0.16) between 0.5 s
  // and 1.3 s. It cuts off the front of the right lobe, which overhangs the held back half. Two
  // probes: one in the front piece (y = -0.062), one behind the cut (y = 0.02).
  json guillotine = small_scene(2000, 200);
  guillotine["blade"] = {{"samples", 31},
                         {"path", {keyframe(0.5, {-0.15, -0.05, 0.12}, {0.15, -0.05, 0.12}), keyframe(1.3, {-0.15, -0.05, -0.16}, {0.15, -0.05, -0.16})}}};
  kerf_test::write_text(dir / "probes.csv", "x,y,z\n0.02,-0.062,0.02\n0.025,0.02,0.0\n");
  const auto result = run_scene(guillotine, dir, "guillotine",
                                " --probes " + quoted(dir / "probes.csv") + " --probes-history " + quoted(dir / "history.csv"));
  INFO(result.out, result.err);
  REQUIRE(result.exit_status == 0);
  CHECK(result.err.empty());
  std::string header;
  const auto cuts = kerf_test::read_csv_rows(dir / "guillotine" / "cuts.csv", header);
  REQUIRE(!cuts.empty());
  const auto history = kerf_test::read_csv_rows(dir / "history.csv", header);
  REQUIRE(history.size() == 2 * 201);
  // uz of probe p at step n.
  const auto uz = [&](int p, int n) { return history.at(static_cast<std::size_t>(2 * n + p))[5]; };
  // After the last topology change nothing holds the front piece: the sum of the forces on it
  // is its weight and the mass-proportional damping, -alpha m v (the stiffness part, beta K v,
  // and the elastic forces have no net force on a free body). Its centre of mass falls as
  //   z(T) = v0 (1 - e^(-alpha T)) / alpha - (g / alpha) (T - (1 - e^(-alpha T)) / alpha),
  // alpha = 2 / s, from the velocity v0 it has at the release, which we take from the probe
  // by a central difference.
  const double dt = 0.01, alpha = 2.0, g = 9.81;
  const int release = static_cast<int>(std::lround(cuts.back()[column::t] / dt)), last = 200;
  REQUIRE(release + 20 < last);
  const double v0 = (uz(0, release + 1) - uz(0, release - 1)) / (2 * dt);
  const double T = (last - release) * dt, decay = (1.0 - std::exp(-alpha * T)) / alpha;
  const double expected = v0 * decay - g / alpha * (T - decay);
  const double fallen = uz(0, last) - uz(0, release);
  MESSAGE("released at t = " << release * dt << " s with v0 = " << v0 << " m/s; fell " << fallen << " m in " << T
                             << " s, damped free fall " << expected << " m; the probe behind the cut moved " << uz(1, last) << " m");
  // Measured: released at t = 1.01 s with v0 = -0.23 m/s, fell 2.78 m in 0.99 s against 2.84 m,
  // 2.0 % short. The probe is one point of a piece that springs back from the stretch it hung
  // in: in the first 0.1 s its acceleration differs from -g - alpha v by up to 20 %, after 0.4 s
  // by 0.1 %. The bound, 5 %; a piece still attached hangs 0.1 m down, not 2.8 m.
  CHECK(fallen == kerf_test::relative(expected, 0.05));
  // Behind the cut the liver hangs as before: its probe has sagged by millimetres (measured
  // 4.9 mm), not metres.
  CHECK(std::abs(uz(1, last)) < 0.02);
}

TEST_CASE("the window under xvfb-run, driven by scripted mouse events: Shift + drag cuts, a drag alone turns the camera") {
  // The demo's window (960 x 720) with a 2000-tet liver. The script presses the left button left
  // of the window's centre, drags 300 pixels to the right of it across the organ in 20 steps,
  // releases, and lets 4 more steps run. Held Shift, the blade follows the cursor; without Shift
  // the same drag turns the camera and cuts nothing.
  const auto dir = kerf_test::fresh_dir("chapter07_window");
  const auto play = [&](bool shift) {
    const std::string name = shift ? "shift_drag" : "drag";
    std::string script = "step,event,x,y,shift\n2,press,330,360," + std::to_string(shift) + "\n";
    for (int k = 1; k <= 20; ++k) script += std::to_string(2 + k) + ",move," + std::to_string(330 + 15 * k) + ",360," + std::to_string(shift) + "\n";
    script += "23,release,630,360," + std::to_string(shift) + "\n26,key_q,0,0,0\n";
    kerf_test::write_text(dir / (name + ".csv"), script);
    const auto result = kerf_test::run_program(
        with_display(chapter_07 + " --interactive --events " + quoted(dir / (name + ".csv")) + " --tets 2000 --out " + quoted(dir / name)), dir / ("run_" + name));
    INFO(result.out, result.err);
    CHECK(result.exit_status == 0);
    CHECK(without_style_warning(result.err).empty());
    const std::regex played("played 23 events over 26 steps; ([0-9]+) tets cut");
    std::smatch match;
    REQUIRE(std::regex_search(result.out, match, played));
    // timings.csv has a row per step played.
    std::string header;
    CHECK(kerf_test::read_csv_rows(dir / name / "timings.csv", header).size() == 26);
    return std::stoi(match[1]);
  };
  const int cut = play(true), turned = play(false);
  MESSAGE("tets cut by the Shift drag: " << cut << ", by the plain drag: " << turned);
  CHECK(cut > 0);
  CHECK(turned == 0);
}

TEST_CASE("the frames: a PNG per step and the animated PNG of them") {
  // Four steps of the demo on 1000 tets, a frame every step (steps 0 to 4: five frames), small.
  const auto dir = kerf_test::fresh_dir("chapter07_frames");
  json scene = small_scene(1000, 4);
  scene["render"] = {{"every", 1}, {"width", 160}, {"height", 120}};
  kerf_test::write_text(dir / "frames.json", scene.dump(2));
  const auto result =
      kerf_test::run_program(with_display(chapter_07 + " --scene " + quoted(dir / "frames.json") + " --out " + quoted(dir / "out")), dir / "run");
  INFO(result.out, result.err);
  REQUIRE(result.exit_status == 0);
  CHECK(result.out.find("wrote 5 PNG frames") != std::string::npos);
  int frames = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir / "out" / "frames")) {
    const auto chunks = kerf_test::png_chunks(entry.path());
    REQUIRE(chunks.front().first == "IHDR");
    CHECK(kerf_test::big_endian_32(chunks.front().second, 0) == 160);
    CHECK(kerf_test::big_endian_32(chunks.front().second, 4) == 120);
    ++frames;
  }
  CHECK(frames == 5);
  // The animation: an acTL chunk (APNG's animation control) with 5 frames, and 5 fcTL chunks.
  const auto chunks = kerf_test::png_chunks(dir / "out" / "liver_cut.png");
  const auto control = std::find_if(chunks.begin(), chunks.end(), [](const auto& c) { return c.first == "acTL"; });
  REQUIRE(control != chunks.end());
  CHECK(kerf_test::big_endian_32(control->second, 0) == 5);
  CHECK(std::count_if(chunks.begin(), chunks.end(), [](const auto& c) { return c.first == "fcTL"; }) == 5);
  CHECK(chunks.back().first == "IEND");
}

TEST_CASE("--help names the chapter's options; a run says how many unknowns it solves for") {
  const auto dir = kerf_test::fresh_dir("chapter07_help");
  const auto help = kerf_test::run_program(chapter_07 + " --help", dir / "help");
  CHECK(help.exit_status == 0);
  for (const char* option : {"--tets", "--interactive", "--events", "--scene", "--out"}) CHECK(help.out.find(option) != std::string::npos);
  const auto run = run_scene(small_scene(1000, 3), dir, "short");
  INFO(run.out, run.err);
  CHECK(run.exit_status == 0);
  CHECK(number_after(run.out, "system: ") > 0); // "system: N unknowns before the cut"
  CHECK(run.out.find(" unknowns") != std::string::npos);
}
