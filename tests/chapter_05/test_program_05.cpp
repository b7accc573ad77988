// Chapter 5 from the command line: the demo's cut, which ends inside elements, opens as the
// conforming mesh cut exactly to its front does; the front it writes as a poly line; the same scene
// without branch functions; a triangle-mesh cut with a curved front, whose length is that of the
// surface's boundary inside the beam; bad "crack_tip" input and the corotated model.
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/cut/split_mesh_along_cut.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/evaluate_displacement.hpp"
#include "kerf/fem/linear_material.hpp"
#include "kerf/fem/solve_linear_static.hpp"
#include "kerf/mesh/box_mesh.hpp"

#include "support/run_program.hpp"

#include <doctest/doctest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <regex>
#include <string>
#include <vector>

namespace {

const std::string chapter_05 = std::string(KERF_BINARY_DIR) + "/bin/05_crack_tip";

// The number written after `key` in the program's output (e.g. "length " -> 0.06).
double number_after(const std::string& text, const std::string& key) {
  const std::size_t at = text.find(key);
  REQUIRE(at != std::string::npos);
  return std::stod(text.substr(at + key.size()));
}

// The NumberOfPoints attribute of a .vtp file.
int vtp_points(const std::filesystem::path& file) {
  const std::string text = kerf_test::read_text(file);
  std::smatch match;
  REQUIRE(std::regex_search(text, match, std::regex("NumberOfPoints=\"([0-9]+)\"")));
  return std::stoi(match[1]);
}

// The demo's probes: 0.5 mm above and below the cut plane at the free face x = 0 and at
// x = 0.0075 (in the cut), and at x = 0.025 (beyond the front), all at y = 0.03.
const std::vector<double> probe_x = {0.0, 0.0075, 0.025};
std::string opening_probes() {
  std::string text = "x,y,z\n";
  for (const double x : probe_x) text += std::to_string(x) + ",0.03,0.1005\n" + std::to_string(x) + ",0.03,0.0995\n";
  return text;
}

// u_z above minus u_z below at each probe pair of a --probes-out file.
std::vector<double> openings(const std::filesystem::path& file) {
  std::string header;
  const auto rows = kerf_test::read_csv_rows(file, header);
  REQUIRE(header == "x,y,z,ux,uy,uz");
  REQUIRE(rows.size() == 2 * probe_x.size());
  std::vector<double> result;
  for (std::size_t k = 0; k < probe_x.size(); ++k) result.push_back(rows[2 * k][5] - rows[2 * k + 1][5]);
  return result;
}

// The reference without XFEM: the beam on a box mesh with node planes on x = 0.015 and z = 0.1,
// opened along the demo's rectangle by split_mesh_along_cut (duplicated nodes), solved by plain
// linear FEM with the demo's conditions (z = 0 clamped, the edge x = 0, z = 0.2 moved up 0.02 m).
// Its cut ends exactly at the front, as the branch-enriched one should.
std::vector<double> conforming_openings(const Eigen::Vector3i& cells) {
  const kerf::TetMesh box = kerf::make_box_mesh({0, 0, 0}, {0.03, 0.06, 0.2}, cells);
  const kerf::SplitMesh split = kerf::split_mesh_along_cut(box, kerf::RectangleCut({0, 0, 0.1}, {0.015, 0, 0}, {0, 0.06, 0}), 1e-9);
  REQUIRE(split.duplicated_nodes > 0);
  kerf::DirichletNodes clamped, pulled;
  pulled.displacement = {0, 0, 0.02};
  for (Eigen::Index v = 0; v < split.mesh.num_nodes(); ++v) {
    const Eigen::Vector3d x = split.mesh.nodes.row(v).transpose();
    if (std::abs(x.z()) < 1e-12) clamped.nodes.push_back(static_cast<int>(v));
    if (std::abs(x.z() - 0.2) < 1e-12 && std::abs(x.x()) < 1e-12) pulled.nodes.push_back(static_cast<int>(v));
  }
  const kerf::DofMap dofs = kerf::make_dof_map(split.mesh.num_nodes(), {clamped, pulled});
  const kerf::LinearMaterial material{300e3, 0.35, 1070};
  const Eigen::VectorXd u =
      kerf::solve_linear_static(split.mesh, material, dofs, Eigen::VectorXd::Zero(3 * split.mesh.num_nodes()), kerf::SolverSettings{});
  Eigen::MatrixXd points(2 * static_cast<Eigen::Index>(probe_x.size()), 3);
  for (std::size_t k = 0; k < probe_x.size(); ++k) {
    points.row(2 * static_cast<Eigen::Index>(k)) << probe_x[k], 0.03, 0.1005;
    points.row(2 * static_cast<Eigen::Index>(k) + 1) << probe_x[k], 0.03, 0.0995;
  }
  Eigen::Index outside = 0;
  const Eigen::MatrixXd at = kerf::evaluate_displacement_at(split.mesh, u, points, outside);
  REQUIRE(outside == 0);
  std::vector<double> result;
  for (std::size_t k = 0; k < probe_x.size(); ++k) result.push_back(at(2 * static_cast<Eigen::Index>(k), 2) - at(2 * static_cast<Eigen::Index>(k) + 1, 2));
  return result;
}

// The demo's scene as a scene file, with `crack_tip` (and the model) of a test's choosing.
std::string demo_scene_with(const std::string& model, const std::string& crack_tip) {
  return R"({"name": "beam", "mesh": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0.2], "cells": [3, 6, 19]}, "order": 1},
  "material": {"young": 300e3, "poisson": 0.35, "density": 1070}, "model": ")" + model + R"(",
  "dirichlet": [{"region": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0]}}},
                {"region": {"box": {"min": [0, 0, 0.2], "max": [0, 0.06, 0.2]}}, "displacement": [0, 0, 0.02]}],
  "cuts": [{"rectangle": {"origin": [0, 0, 0.1], "edge1": [0.015, 0, 0], "edge2": [0, 0.06, 0]}}],
  "crack_tip": )" + crack_tip + "}";
}

// The conforming reference's opening at the free face, computed once: the finest mesh of the
// ladder 6x6x20, 6x12x40, 12x12x40, 12x24x60, whose openings at x = 0 were 7.78, 8.46, 8.82 and
// 9.04 mm, still rising by 2.5 % at the last step (the front's singularity converges slowly).
double reference_opening() {
  static const double opening = conforming_openings({12, 24, 60})[0];
  return opening;
}

} // namespace

TEST_CASE("the demo: the cut ends at its front inside the elements, which it writes as a poly line") {
  const auto dir = kerf_test::fresh_dir("chapter05_demo");
  kerf_test::write_text(dir / "probes.csv", opening_probes());
  const auto demo = kerf_test::run_program(chapter_05 + " --out '" + (dir / "out").string() + "' --probes '" + (dir / "probes.csv").string() +
                                               "' --probes-out '" + (dir / "demo.csv").string() + "'",
                                           dir);
  INFO(demo.out, demo.err);
  REQUIRE(demo.exit_status == 0);
  CHECK(demo.err.empty());
  CHECK(demo.out.find(" unknowns ") != std::string::npos);
  // The rectangle's only edge inside the beam is x = 0.015, z = 0.1 across its 0.06 m width (the
  // other three lie in the beam's faces): one straight front of one segment, two points, 0.06 m.
  CHECK(number_after(demo.out, "front: ") == 1);
  CHECK(number_after(demo.out, "length ") == doctest::Approx(0.06).epsilon(1e-12).scale(0.0));
  CHECK(vtp_points(dir / "out" / "beam_crack_tip_front.vtp") == 2);
  CHECK(std::filesystem::exists(dir / "out" / "beam_crack_tip_pieces.vtu"));

  // Geometric enrichment: the branch nodes are the nodes within the printed radius of the line
  // x = 0.015, z = 0.1 (the front tets' corners lie within it too), counted here on the box
  // mesher's grid of 4 x 7 x 20 nodes.
  const double radius = number_after(demo.out, "geometric, radius ");
  int within = 0;
  for (int i = 0; i <= 3; ++i)
    for (int j = 0; j <= 6; ++j)
      for (int k = 0; k <= 19; ++k) within += std::hypot(0.01 * i - 0.015, 0.2 * k / 19.0 - 0.1) <= radius;
  CHECK(number_after(demo.out, "(default); ") == within); // "... (default); N branch nodes"

  // The opening against the conforming mesh cut exactly to x = 0.015. Measured: 11.3 mm against
  // the reference's 9.04 mm, 25 % above it, where chapter 4's rule on the same mesh opens 4.1 mm
  // (the next test): the default radius (25.7 mm) enriches every node of the cut on this coarse
  // mesh (three elements across the depth), and the finest conforming mesh is itself still
  // rising. The bound, 30 %, says "the cut reaches its front", which chapter 4's misses by 55 %.
  const std::vector<double> xfem = openings(dir / "demo.csv");
  const double reference = reference_opening();
  MESSAGE("opening (m) at x = 0, 0.0075, 0.025: " << xfem[0] << ", " << xfem[1] << ", " << xfem[2] << "; conforming 12x24x60 at x = 0: "
                                                  << reference);
  CHECK(std::abs(xfem[0] - reference) < 0.30 * reference);
  // In the cut the gap closes towards the front; beyond it the material is whole: what is left
  // between the two probes 1 mm apart is the strain (measured 1e-6 m against 7e-3 m).
  CHECK(xfem[1] < xfem[0]);
  CHECK(std::abs(xfem[2]) < 0.01 * xfem[0]);
}

TEST_CASE("the same scene without branch functions, and with the topological rule") {
  const auto dir = kerf_test::fresh_dir("chapter05_rules");
  kerf_test::write_text(dir / "probes.csv", opening_probes());
  const auto run = [&](const std::string& name, const std::string& crack_tip) {
    kerf_test::write_text(dir / (name + ".json"), demo_scene_with("linear", crack_tip));
    const auto result = kerf_test::run_program(chapter_05 + " --scene '" + (dir / (name + ".json")).string() + "' --out '" +
                                                   (dir / name).string() + "' --probes '" + (dir / "probes.csv").string() + "' --probes-out '" +
                                                   (dir / (name + ".csv")).string() + "'",
                                               dir);
    INFO(result.out, result.err);
    REQUIRE(result.exit_status == 0);
    return std::make_pair(result.out, openings(dir / (name + ".csv")));
  };
  const double reference = reference_opening();
  // Chapter 4's rule: no node whose support the front enters is enriched, so the simulated cut
  // ends at x = 0.01, the last node plane before the front, and opens less than half as far
  // (measured 4.1 mm against 9.0 mm).
  const auto [none_out, none] = run("none", R"({"enrichment": "none"})");
  CHECK(none_out.find("0 branch nodes") != std::string::npos);
  CHECK(none[0] < 0.5 * reference);
  // The topological rule (radius 0): the corners of the tets the front passes through, all of
  // them corners of the 6 hex cells it crosses, which have 4 x 7 = 28 corners (measured: 21).
  // Its opening, measured 8.1 mm, is 10 % below the reference, which is still rising itself:
  // within 15 %.
  const auto [topological_out, topological] = run("topological", R"({"enrichment": "branch", "radius": 0})");
  CHECK(topological_out.find("enrichment: branch, topological") != std::string::npos);
  const double topological_nodes = number_after(topological_out, "topological; ");
  CHECK(topological_nodes > 0);
  CHECK(topological_nodes <= 28);
  CHECK(std::abs(topological[0] - reference) < 0.15 * reference);
}

TEST_CASE("a triangle-mesh cut with a curved front: its length is that of the surface's edges inside the beam") {
  const auto dir = kerf_test::fresh_dir("chapter05_curved");
  const std::string scene = std::string(KERF_SOURCE_DIR) + "/examples/05_beam_curved_front_tet4.json";
  const auto run = kerf_test::run_program(chapter_05 + " --scene '" + scene + "' --out '" + dir.string() + "' --moments-out '" +
                                              (dir / "moments.csv").string() + "'",
                                          dir);
  INFO(run.out, run.err);
  REQUIRE(run.exit_status == 0);
  // examples/05_curved_front.obj: the front is the chain of its edges between the vertices
  // (0.015 + 0.004 sin(pi y / 0.06), y, 0.1) at y = 0, 0.005, ..., 0.06: 12 chords, 13 points,
  // the sum of the chords' lengths (the edges beyond the beam's faces y = 0 and y = 0.06 are
  // outside the mesh, and the edges at x = -0.005 too).
  const auto front_x = [](double y) { return 0.015 + 0.004 * std::sin(M_PI * y / 0.06); };
  double length = 0.0;
  for (int j = 0; j < 12; ++j) {
    const double y0 = 0.005 * j, y1 = 0.005 * (j + 1);
    length += std::hypot(front_x(y1) - front_x(y0), y1 - y0);
  }
  CHECK(number_after(run.out, "front: ") == 1);
  CHECK(number_after(run.out, "polylines, ") == 12);
  CHECK(number_after(run.out, "length ") == doctest::Approx(length).epsilon(1e-5).scale(0.0)); // printed with 6 digits
  CHECK(vtp_points(dir / "beam_curved_front_front.vtp") == 13);
  std::string header;
  CHECK(!kerf_test::read_csv_rows(dir / "moments.csv", header).empty());
  CHECK(header == "element,piece,volume,mx,my,mz,mxx,myy,mzz,mxy,myz,mxz");
}

TEST_CASE("bad crack_tip input is one line naming the field; the corotated model with branch functions runs") {
  const auto dir = kerf_test::fresh_dir("chapter05_bad");
  const auto run = [&](const std::string& name, const std::string& text) {
    kerf_test::write_text(dir / (name + ".json"), text);
    return kerf_test::run_program(chapter_05 + " --quiet --scene '" + (dir / (name + ".json")).string() + "' --out '" + (dir / name).string() + "'",
                                  dir);
  };
  const auto one_line_naming = [](const kerf_test::ProgramResult& result, const std::string& field) {
    INFO(result.err);
    CHECK(result.exit_status == 2);
    CHECK(result.err.find(field) != std::string::npos);
    CHECK(std::count(result.err.begin(), result.err.end(), '\n') == 1);
  };
  one_line_naming(run("enrichment", demo_scene_with("linear", R"({"enrichment": "tip"})")), "crack_tip.enrichment");
  one_line_naming(run("radius", demo_scene_with("linear", R"({"radius": -0.01})")), "crack_tip.radius");
  one_line_naming(run("unknown", demo_scene_with("linear", R"({"radius": 0.01, "rule": "geometric"})")), "crack_tip");
  one_line_naming(run("blending", demo_scene_with("linear", R"({"blending": "ramp"})")), "crack_tip.blending");
  // Fries's correction is refused with the corotated model (its Newton stalled: 314 iterations
  // over 10 load steps, final relative residual 0.91, every one on the warped fallback)...
  one_line_naming(run("corrected_corotated", demo_scene_with("corotational", R"({"radius": 0, "blending": "corrected"})")), "crack_tip.blending");
  // ... and runs with the linear one: the ramp nodes are counted, and the two null vectors of
  // the straight front are held (branch_null_space.hpp), so that CHOLMOD factorises.
  kerf_test::write_text(dir / "corrected.json", demo_scene_with("linear", R"({"radius": 0, "blending": "corrected"})"));
  const auto corrected =
      kerf_test::run_program(chapter_05 + " --scene '" + (dir / "corrected.json").string() + "' --out '" + (dir / "corrected").string() + "'", dir);
  INFO(corrected.out, corrected.err);
  CHECK(corrected.exit_status == 0);
  CHECK(corrected.out.find("ramp nodes (blending corrected)") != std::string::npos);
  CHECK(number_after(corrected.out, "sign nodes, ") > 0); // "... N sign nodes, M ramp nodes"
  CHECK(corrected.err.empty());
  // The corotated model with branch functions runs: Newton converges in every load step (the
  // program warns on stderr if a step misses the tolerance, even with --quiet). Its answers are
  // tested in test_corotational_branch.cpp.
  const auto corotated = run("corotated", demo_scene_with("corotational", R"({"radius": 0})"));
  INFO(corotated.err);
  CHECK(corotated.exit_status == 0);
  CHECK(corotated.err.empty());
}
