// Chapter 2 from the command line: the demo, the corotational model through the probe
// contract, the linear model giving chapter 1's answer, and what chapter 2 still refuses.
#include "support/run_program.hpp"

#include <doctest/doctest.h>

#include <Eigen/Core>
#include <sstream>

namespace {

const std::string chapter_01 = std::string(KERF_BINARY_DIR) + "/bin/01_linear_fem";
const std::string chapter_02 = std::string(KERF_BINARY_DIR) + "/bin/02_corotation";

// The displacement columns of a probe output file, #P by 3.
Eigen::MatrixXd probe_displacements(const std::filesystem::path& file) {
  std::stringstream in(kerf_test::read_text(file));
  std::string line;
  std::getline(in, line);
  std::vector<Eigen::Vector3d> rows;
  while (std::getline(in, line)) {
    std::stringstream cells(line);
    std::string cell;
    Eigen::Vector3d u;
    for (int c = 0; c < 6; ++c) {
      std::getline(cells, cell, ',');
      if (c >= 3) u[c - 3] = std::stod(cell);
    }
    rows.push_back(u);
  }
  Eigen::MatrixXd values(static_cast<Eigen::Index>(rows.size()), 3);
  for (std::size_t r = 0; r < rows.size(); ++r) values.row(static_cast<Eigen::Index>(r)) = rows[r].transpose();
  return values;
}

std::string run_scene(const std::string& program, const std::filesystem::path& dir, const std::string& scene_json) {
  kerf_test::write_text(dir / "scene.json", scene_json);
  kerf_test::write_text(dir / "probes.csv", "x,y,z\n0.015,0.03,0.2\n0.0,0.0,0.2\n0.03,0.06,0.1\n");
  const auto result = kerf_test::run_program(program + " --quiet --scene '" + (dir / "scene.json").string() + "' --probes '" +
                                                 (dir / "probes.csv").string() + "' --probes-out '" + (dir / "u.csv").string() +
                                                 "' --out '" + dir.string() + "'",
                                             dir);
  CHECK(result.exit_status == 0);
  return result.err;
}

const std::string beam_mesh = R"("mesh": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0.2], "cells": [2, 3, 8]}, "order": 2})";
const std::string clamped = R"("dirichlet": [{"region": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0]}}}])";

} // namespace

TEST_CASE("the chapter 2 demo bends the beam into a quarter circle and writes its history") {
  const auto dir = kerf_test::fresh_dir("chapter02_demo");
  const auto result = kerf_test::run_program(chapter_02 + " --out '" + dir.string() + "'", dir);
  REQUIRE(result.exit_status == 0);
  CHECK(result.err.empty()); // converged: no warning
  CHECK(std::filesystem::file_size(dir / "beam_bent_90.vtu") > 1000);
  const std::string history = kerf_test::read_text(dir / "beam_bent_90_newton.csv");
  CHECK(history.rfind("step,iteration,relative_residual,warped_fallback\n", 0) == 0);
  // The last line is the converged iteration of step 10.
  const auto last = history.substr(history.rfind('\n', history.size() - 2) + 1);
  CHECK(last.rfind("10,", 0) == 0);
}

TEST_CASE("model linear in chapter 2 gives chapter 1's answer") {
  const std::string scene = "{" + beam_mesh + "," + clamped + R"(, "gravity": [9.81, 0, 0]})";
  const auto dir1 = kerf_test::fresh_dir("ch2_linear_vs_ch1/one"), dir2 = kerf_test::fresh_dir("ch2_linear_vs_ch1/two");
  run_scene(chapter_01, dir1, scene);
  run_scene(chapter_02, dir2, scene);
  const Eigen::MatrixXd u1 = probe_displacements(dir1 / "u.csv"), u2 = probe_displacements(dir2 / "u.csv");
  REQUIRE(u1.rows() == 3);
  CHECK((u1 - u2).cwiseAbs().maxCoeff() <= 1e-14 * u1.cwiseAbs().maxCoeff());
}

TEST_CASE("under a large tip load, corotational and linear answers part ways, and the corotational one keeps the length") {
  // A tip load bending the beam by about a third of its length. Linear FEM moves the tip
  // sideways only (it cannot shorten the projected length); a rotating beam must also drop:
  // its tip's z displacement is negative, of the order of u_x^2 / L.
  const std::string loads = R"(, "traction": [{"region": {"box": {"min": [0, 0, 0.2], "max": [0.03, 0.06, 0.2]}}, "total_force": [1.0, 0, 0]}])";
  const auto linear_dir = kerf_test::fresh_dir("ch2_tip/linear"), corotational_dir = kerf_test::fresh_dir("ch2_tip/corotational");
  run_scene(chapter_02, linear_dir, "{" + beam_mesh + "," + clamped + loads + "}");
  run_scene(chapter_02, corotational_dir,
            "{" + beam_mesh + "," + clamped + loads + R"(, "model": "corotational", "quasi_static": {"load_steps": 5}})");
  const Eigen::MatrixXd linear = probe_displacements(linear_dir / "u.csv");
  const Eigen::MatrixXd corotational = probe_displacements(corotational_dir / "u.csv");
  const double ux_linear = linear(0, 0), ux = corotational(0, 0), uz = corotational(0, 2);
  MESSAGE("tip: linear ux " << ux_linear << ", corotational ux " << ux << " uz " << uz);
  CHECK(ux_linear > 0.05);
  CHECK(std::abs(linear(0, 2)) < 1e-3 * ux_linear); // linear: no shortening to speak of
  CHECK(ux < ux_linear);                            // the rotating beam deflects less under a dead load
  CHECK(uz < -0.2 * ux * ux / 0.2);                 // and its tip drops, as an inextensible beam's must
}

TEST_CASE("chapter 2 refuses cuts and dynamics with one line naming the chapter that teaches them") {
  const auto dir = kerf_test::fresh_dir("ch2_refuses");
  kerf_test::write_text(dir / "cut.json", "{" + beam_mesh + "," + clamped +
                                              R"(, "cuts": [{"rectangle": {"origin": [0,0,0.1], "edge1": [0.015,0,0], "edge2": [0,0.06,0]}}]})");
  kerf_test::write_text(dir / "newmark.json", "{" + beam_mesh + "," + clamped + R"(, "time": {"integrator": "newmark", "dt": 0.01, "steps": 5}})");
  kerf_test::write_text(dir / "tangent.json", "{" + beam_mesh + "," + clamped + R"(, "quasi_static": {"tangent": "exact"}})");
  for (const auto& [file, expected] : {std::pair<std::string, std::string>{"cut.json", "cut.json: cuts: cuts are taught from chapter 3"},
                                       {"newmark.json", "newmark.json: time.integrator:"},
                                       {"tangent.json", "tangent.json: quasi_static.tangent:"}}) {
    const auto result = kerf_test::run_program(chapter_02 + " --quiet --scene '" + (dir / file).string() + "'", dir);
    CHECK(result.exit_status == 2);
    CHECK(result.err.find(expected) != std::string::npos);
    CHECK(std::count(result.err.begin(), result.err.end(), '\n') == 1);
  }
}
