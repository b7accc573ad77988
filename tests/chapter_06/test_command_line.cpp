// Chapter 6 from the command line: --help, a short run of a cut beam with every output
// (energy.csv, the probes' history and last state, the .pvd series, the moments), and the bad
// inputs: a static scene, an integrator the corotated model is not stepped with here, an
// explicit step above its limit, a run that diverges, and the options other chapters refuse.
#include "kerf/app/command_line.hpp"
#include "kerf/app/input_error.hpp"
#include "support/run_program.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

namespace {

const std::string chapter_06 = std::string(KERF_BINARY_DIR) + "/bin/06_newmark";
const std::string chapter_04 = std::string(KERF_BINARY_DIR) + "/bin/04_cut_quadrature";

// A coarse beam (3 x 3 x 10 Tet4 cells) clamped at z = 0 with a flap cut at z = 0.15 that hangs
// by a strip at x = 0.03, gravity along +x; `model` and `time` fill the rest.
std::string flap_scene(const std::string& model, const std::string& time) {
  return R"({
  "name": "flap",
  "mesh": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0.2], "cells": [3, 3, 10]}, "order": 1},
  "material": {"young": 300e3, "poisson": 0.35, "density": 1070},
  "model": ")" + model + R"(",
  "gravity": [9.81, 0, 0],
  "dirichlet": [{"region": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0]}}}],
  "cuts": [{"rectangle": {"origin": [-0.005, -0.005, 0.15], "edge1": [0.03, 0, 0], "edge2": [0, 0.07, 0]}}],
  "time": )" + time + R"(,
  "output": {"every": 5}
})";
}

const std::string probes = "x,y,z\n0.015,0.03,0.19\n0.015,0.03,0.1\n0.015,0.03,0.5\n";

std::size_t count_of(const std::string& text, const std::string& what) {
  std::size_t count = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++count;
  return count;
}

} // namespace

TEST_CASE("--help lists the chapter's options") {
  const auto dir = kerf_test::fresh_dir("chapter06_help");
  const auto help = kerf_test::run_program(chapter_06 + " --help", dir);
  CHECK(help.exit_status == 0);
  CHECK(help.out.find("--probes-history") != std::string::npos);
  CHECK(help.out.find("--moments-out") != std::string::npos);
}

TEST_CASE("a short corotational run writes energy.csv, the probes' history, the last probes and a .pvd series") {
  const auto dir = kerf_test::fresh_dir("chapter06_outputs");
  kerf_test::write_text(dir / "flap.json", flap_scene("corotational", R"({"integrator": "newmark", "dt": 0.005, "steps": 12, "mass": "lumped", "rayleigh": [2, 0.001]})"));
  kerf_test::write_text(dir / "probes.csv", probes);
  const auto run = kerf_test::run_program(chapter_06 + " --scene '" + (dir / "flap.json").string() + "' --out '" + (dir / "out").string() +
                                              "' --probes '" + (dir / "probes.csv").string() + "' --probes-out '" + (dir / "last.csv").string() +
                                              "' --probes-history '" + (dir / "history.csv").string() + "' --moments-out '" +
                                              (dir / "moments.csv").string() + "'",
                                          dir);
  INFO(run.out, run.err);
  REQUIRE(run.exit_status == 0);
  CHECK(run.out.find("unknowns") != std::string::npos);
  // One point lies outside the beam: a warning, and nan in its rows.
  CHECK(run.err.find("outside") != std::string::npos);

  std::string header;
  const auto energy = kerf_test::read_csv_rows(dir / "out" / "energy.csv", header);
  CHECK(header == "step,t,kinetic,elastic,external_work,dissipated,damping,numerical");
  REQUIRE(energy.size() == 13); // steps 0 .. 12
  for (std::size_t n = 0; n < energy.size(); ++n) {
    CHECK(energy[n][0] == static_cast<double>(n));
    CHECK(energy[n][1] == kerf_test::relative(0.005 * static_cast<double>(n), 1e-12));
  }
  CHECK(energy[0][2] == 0.0); // at rest at the start
  CHECK(energy.back()[2] > 0.0); // and moving at the end, with gravity having done work
  CHECK(energy.back()[4] > 0.0);

  const auto history = kerf_test::read_csv_rows(dir / "history.csv", header);
  CHECK(header == "step,t,probe,ux,uy,uz");
  REQUIRE(history.size() == 13 * 3);
  for (std::size_t row = 0; row < history.size(); ++row) {
    CHECK(history[row][0] == static_cast<double>(row / 3));
    CHECK(history[row][2] == static_cast<double>(row % 3));
    CHECK(std::isnan(history[row][3]) == (row % 3 == 2));
  }
  // --probes-out is the last step: the same doubles as the history's last rows.
  const auto last = kerf_test::read_csv_rows(dir / "last.csv", header);
  CHECK(header == "x,y,z,ux,uy,uz");
  REQUIRE(last.size() == 3);
  for (std::size_t p = 0; p < 2; ++p)
    for (int c = 0; c < 3; ++c) CHECK(last[p][3 + c] == history[12 * 3 + p][3 + c]);
  CHECK(history[12 * 3][3] > 1e-4); // the flap has moved along gravity

  // Frames at steps 0, 5, 10 and the last, 12, in a series ParaView plays.
  const std::string pvd = kerf_test::read_text(dir / "out" / "flap_pieces.pvd");
  CHECK(count_of(pvd, "<DataSet") == 4);
  CHECK(std::filesystem::exists(dir / "out" / "flap_pieces_000012.vtu"));
  CHECK(std::filesystem::exists(dir / "moments.csv"));
}

TEST_CASE("bad inputs get a one-line error naming the field, and a diverging run stops at its step") {
  const auto dir = kerf_test::fresh_dir("chapter06_bad");
  kerf_test::write_text(dir / "probes.csv", probes);
  const auto run_scene = [&](const std::string& name, const std::string& text, const std::string& extra = "") {
    kerf_test::write_text(dir / (name + ".json"), text);
    return kerf_test::run_program(chapter_06 + " --quiet --scene '" + (dir / (name + ".json")).string() + "' --out '" + (dir / name).string() + "'" + extra, dir);
  };
  struct Case {
    std::string name, scene, field;
  };
  const std::vector<Case> cases{
      {"static", flap_scene("linear", R"({"integrator": "static"})"), "time.integrator"},
      {"hht_corotational", flap_scene("corotational", R"({"integrator": "hht_alpha", "dt": 0.01, "steps": 2})"), "time.integrator"},
      {"explicit_too_long", flap_scene("linear", R"({"integrator": "central_difference", "dt": 0.01, "steps": 2})"), "time.dt"},
      {"corotation", flap_scene("corotational", R"({"integrator": "newmark", "dt": 0.01, "steps": 2, "corotation": "sometimes"})"), "time.corotation"},
      {"massless", [] {
         std::string text = flap_scene("linear", R"({"integrator": "newmark", "dt": 0.01, "steps": 2})");
         text.replace(text.find("\"density\": 1070"), 15, "\"density\": 0");
         return text;
       }(), "material.density"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.name);
    const auto result = run_scene(c.name, c.scene);
    CHECK(result.exit_status == 2);
    CHECK(count_of(result.err, "\n") == 1);
    CHECK(result.err.find(c.field + ": ") != std::string::npos);
    if (c.name == "explicit_too_long") CHECK(result.err.find("critical step") != std::string::npos);
  }

  // Forced above the limit, the central difference blows up: the run stops with the step, exit
  // 3, and what it wrote before is finite.
  const auto diverged = run_scene("diverged", flap_scene("linear", R"({"integrator": "central_difference", "dt": 0.002, "steps": 200, "allow_unstable": true})"),
                                  " --probes '" + (dir / "probes.csv").string() + "' --probes-history '" + (dir / "diverged_history.csv").string() + "'");
  CHECK(diverged.exit_status == 3);
  CHECK(diverged.err.find("diverged at step") != std::string::npos);
  const std::string energy = kerf_test::read_text(dir / "diverged" / "energy.csv");
  CHECK(count_of(energy, "\n") > 2);
  CHECK(count_of(energy, "\n") < 201);
  CHECK(energy.find("nan") == std::string::npos);
  CHECK(energy.find("inf") == std::string::npos);
  const std::string history = kerf_test::read_text(dir / "diverged_history.csv");
  CHECK(count_of(history, "inf") == 0);
  CHECK(count_of(history, "nan") == count_of(history, "\n") - 1); // 3 in each row of the outside probe, a third of the rows

  // Options: --probes-history needs --probes; chapter 4 has not taught it.
  kerf_test::write_text(dir / "ok.json", flap_scene("linear", R"({"integrator": "newmark", "dt": 0.01, "steps": 2})"));
  const auto lonely = kerf_test::run_program(chapter_06 + " --scene '" + (dir / "ok.json").string() + "' --probes-history h.csv", dir);
  CHECK(lonely.exit_status == 2);
  CHECK(lonely.err.find("--probes") != std::string::npos);
  const auto chapter4 = kerf_test::run_program(chapter_04 + " --probes '" + (dir / "probes.csv").string() + "' --probes-history h.csv", dir);
  CHECK(chapter4.exit_status == 2);
  CHECK(chapter4.err.find("chapter 6") != std::string::npos);
}

TEST_CASE("--probes goes with --probes-out, --probes-history or both") {
  const auto parse = [](std::vector<const char*> args) {
    args.insert(args.begin(), "06_newmark");
    return kerf::parse_command_line(static_cast<int>(args.size()), args.data());
  };
  const kerf::CommandLine history = parse({"--probes", "in.csv", "--probes-history", "h.csv"});
  CHECK(history.probes_history == std::filesystem::path("h.csv"));
  CHECK_FALSE(history.probes_out.has_value());
  const kerf::CommandLine both = parse({"--probes-history", "h.csv", "--probes", "in.csv", "--probes-out", "o.csv"});
  CHECK(both.probes_out == std::filesystem::path("o.csv"));
  CHECK_THROWS_AS(parse({"--probes", "in.csv"}), kerf::InputError);
  CHECK_THROWS_AS(parse({"--probes-history", "h.csv"}), kerf::InputError);
  CHECK_THROWS_AS(parse({"--probes-out", "o.csv"}), kerf::InputError);
  CHECK_THROWS_AS(parse({"--probes", "in.csv", "--probes-history"}), kerf::InputError); // no value
}
