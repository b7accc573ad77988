// Chapter 3 from the command line: the demo and its two VTU files, the probe contract with the
// jump across the cut, and the scenes chapter 3 refuses (two cuts, Tet10, no cut).
#include "support/run_program.hpp"

#include <doctest/doctest.h>

#include <Eigen/Core>
#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

namespace {

const std::string chapter_03 = std::string(KERF_BINARY_DIR) + "/bin/03_xfem_heaviside";

// The rows of a probe output file: x, y, z, ux, uy, uz.
std::vector<std::vector<double>> probe_rows(const std::filesystem::path& file, std::string& header) {
  std::stringstream in(kerf_test::read_text(file));
  std::string line;
  std::getline(in, header);
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::stringstream cells(line);
    std::string cell;
    std::vector<double> row;
    while (std::getline(cells, cell, ',')) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

const std::string beam_box = R"("box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0.2], "cells": [2, 3, 8]})";
const std::string clamped = R"("dirichlet": [{"region": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0]}}}])";
const std::string one_cut = R"({"rectangle": {"origin": [0, 0, 0.1], "edge1": [0.015, 0, 0], "edge2": [0, 0.06, 0]}})";
const std::string other_cut = R"({"rectangle": {"origin": [0, 0, 0.05], "edge1": [0.015, 0, 0], "edge2": [0, 0.06, 0]}})";

} // namespace

TEST_CASE("xfem command line: the demo pulls the cut beam open and writes the mesh and its pieces") {
  const auto dir = kerf_test::fresh_dir("chapter03_demo");
  const auto result = kerf_test::run_program(chapter_03 + " --out '" + dir.string() + "'", dir);
  REQUIRE(result.exit_status == 0);
  CHECK(result.err.empty()); // converged: no warning
  CHECK(result.out.find("enriched nodes") != std::string::npos);
  CHECK(std::filesystem::file_size(dir / "beam_cut_pulled.vtu") > 1000);
  CHECK(std::filesystem::file_size(dir / "beam_cut_pulled_pieces.vtu") > 1000);
  // The pieces file holds more cells than the mesh: the enriched tets are written piece by piece.
  const std::string pieces = kerf_test::read_text(dir / "beam_cut_pulled_pieces.vtu");
  CHECK(pieces.find("\"side\"") != std::string::npos);
  CHECK(pieces.find("\"parent_tet\"") != std::string::npos);
  const std::string history = kerf_test::read_text(dir / "beam_cut_pulled_newton.csv");
  CHECK(history.rfind("step,iteration,relative_residual,warped_fallback\n", 0) == 0);
}

TEST_CASE("xfem command line: probes in the gravity example show the jump across the cut") {
  const auto dir = kerf_test::fresh_dir("chapter03_probes");
  // 0.1 mm above and below the cut at the free face x = 0, and one point far from the cut.
  kerf_test::write_text(dir / "probes.csv", "x,y,z\n0,0.03,0.1001\n0,0.03,0.0999\n0.03,0.03,0.2\n");
  const std::string scene = std::string(KERF_SOURCE_DIR) + "/examples/03_beam_cut_gravity_linear.json";
  const auto result = kerf_test::run_program(chapter_03 + " --quiet --scene '" + scene + "' --probes '" + (dir / "probes.csv").string() +
                                                 "' --probes-out '" + (dir / "u.csv").string() + "' --out '" + dir.string() + "'",
                                             dir);
  REQUIRE(result.exit_status == 0);
  CHECK(result.err.empty());
  CHECK(std::filesystem::exists(dir / "beam_cut_gravity_linear.vtu"));
  CHECK(std::filesystem::exists(dir / "beam_cut_gravity_linear_pieces.vtu"));
  std::string header;
  const auto rows = probe_rows(dir / "u.csv", header);
  CHECK(header == "x,y,z,ux,uy,uz");
  REQUIRE(rows.size() == 3);
  for (const auto& row : rows) REQUIRE(row.size() == 6);
  // Gravity along x bends the clamped beam toward +x; the face x = 0 is stretched and the cut
  // there opens by a few mm (measured 3.7 mm). A continuous field would differ by ~1e-6 m over
  // 0.2 mm, so 1e-4 m separates a jump from a gradient.
  const double jump = rows[0][5] - rows[1][5];
  MESSAGE("uz above - uz below the cut at x = 0: " << jump << " m");
  CHECK(std::abs(jump) > 1e-4);
  CHECK(jump > 0.0); // it opens: the side above moves up relative to the side below
}

TEST_CASE("xfem command line: two cuts, a Tet10 mesh and no cut are refused with one line naming file and field") {
  const auto dir = kerf_test::fresh_dir("chapter03_refuses");
  kerf_test::write_text(dir / "two_cuts.json", "{\"mesh\": {" + beam_box + ", \"order\": 1}, " + clamped + ", \"cuts\": [" + one_cut +
                                                   ", " + other_cut + "]}");
  kerf_test::write_text(dir / "tet10.json", "{\"mesh\": {" + beam_box + ", \"order\": 2}, " + clamped + ", \"cuts\": [" + one_cut + "]}");
  kerf_test::write_text(dir / "no_cut.json", "{\"mesh\": {" + beam_box + ", \"order\": 1}, " + clamped + "}");
  for (const auto& [file, expected] : {std::pair<std::string, std::string>{"two_cuts.json", "two_cuts.json: cuts:"},
                                       {"tet10.json", "tet10.json: mesh.order:"},
                                       {"no_cut.json", "no_cut.json: cuts:"}}) {
    CAPTURE(file);
    const auto result = kerf_test::run_program(chapter_03 + " --quiet --scene '" + (dir / file).string() + "' --out '" + dir.string() + "'", dir);
    CAPTURE(result.err);
    CHECK(result.exit_status == 2);
    CHECK(result.err.find(expected) != std::string::npos);
    CHECK(std::count(result.err.begin(), result.err.end(), '\n') == 1);
  }
}
