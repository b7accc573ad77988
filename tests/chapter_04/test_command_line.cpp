// Chapter 4 from the command line: the demo opens its curved cut and writes its blade; the blade
// read back from a scene gives the same answer; --moments-out; two cuts mixed; the bad inputs
// (a degenerate surface, a surface that misses the mesh, a rule a Tet10 cannot use), and the
// options and fields that chapter 3 refuses.
#include "support/run_program.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <Eigen/Core>
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {

const std::string chapter_04 = std::string(KERF_BINARY_DIR) + "/bin/04_cut_quadrature";
const std::string chapter_03 = std::string(KERF_BINARY_DIR) + "/bin/03_xfem_heaviside";

// The demo blade's height at y: z = 0.1 + 0.01 sin(pi y / 0.06).
double blade_z(double y) { return 0.1 + 0.01 * std::sin(M_PI * y / 0.06); }

// Probe pairs 0.5 mm above and below the blade at (x, y), for each x and y = 0.03.
std::string blade_probes(const std::vector<double>& xs) {
  std::ostringstream out;
  out.precision(17);
  out << "x,y,z\n";
  for (const double x : xs) out << x << ",0.03," << blade_z(0.03) + 5e-4 << "\n" << x << ",0.03," << blade_z(0.03) - 5e-4 << "\n";
  return out.str();
}

// The beam, clamped at z = 0 and its whole top face moved up 2 mm: a cut clean through leaves
// each part held.
const std::string tet4_scene_start = R"({
  "mesh": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0.2], "cells": [3, 6, 19]}, "order": ORDER},
  "material": {"young": 300e3, "poisson": 0.35, "density": 1070},
  "dirichlet": [{"region": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0]}}},
                {"region": {"box": {"min": [0, 0, 0.2], "max": [0.03, 0.06, 0.2]}}, "displacement": [0, 0, 0.002]}],)";

std::string scene_with(const std::string& order, const std::string& rest) {
  std::string text = tet4_scene_start;
  text.replace(text.find("ORDER"), 5, order);
  return text + rest + "}";
}

} // namespace

TEST_CASE("the demo opens its curved cut, and the blade it writes gives the same answer from a scene") {
  const auto dir = kerf_test::fresh_dir("chapter04_demo");
  kerf_test::write_text(dir / "probes.csv", blade_probes({0.005, 0.025}));
  const auto demo = kerf_test::run_program(chapter_04 + " --out '" + (dir / "out").string() + "' --probes '" + (dir / "probes.csv").string() +
                                               "' --probes-out '" + (dir / "demo_probes.csv").string() + "'",
                                           dir);
  INFO(demo.out, demo.err);
  REQUIRE(demo.exit_status == 0);
  CHECK(demo.out.find("unknowns") != std::string::npos);
  CHECK(std::filesystem::exists(dir / "out" / "beam_curved_cut.vtu"));
  CHECK(std::filesystem::exists(dir / "out" / "beam_curved_cut_pieces.vtu"));
  REQUIRE(std::filesystem::exists(dir / "out" / "blade.obj"));
  std::string header;
  const auto rows = kerf_test::read_csv_rows(dir / "demo_probes.csv", header);
  CHECK(header == "x,y,z,ux,uy,uz");
  REQUIRE(rows.size() == 4);
  // In the cut (x = 0.005) the two sides part: the upper one is pulled up by the top edge.
  const double opening = rows[0][5] - rows[1][5];
  // Beyond the front (x = 0.025) the material is whole: the two points differ by the strain
  // over their 1 mm only.
  const double beyond = std::abs(rows[2][5] - rows[3][5]);
  CHECK(opening > 1e-3);
  CHECK(beyond < 0.05 * opening);

  // The blade as a file in a scene of its own, the demo's scene otherwise: the same probe values.
  std::filesystem::copy_file(dir / "out" / "blade.obj", dir / "blade.obj");
  kerf_test::write_text(dir / "scene.json", R"({
  "name": "beam_curved_cut",
  "mesh": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0.2], "cells": [3, 6, 19]}, "order": 2},
  "material": {"young": 300e3, "poisson": 0.35, "density": 1070},
  "model": "corotational",
  "dirichlet": [
    {"region": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0]}}},
    {"region": {"box": {"min": [0, 0, 0.2], "max": [0, 0.06, 0.2]}}, "displacement": [0, 0, 0.02]}],
  "cuts": [{"surface": "blade.obj"}],
  "quasi_static": {"load_steps": 5}
})");
  const auto again = kerf_test::run_program(chapter_04 + " --quiet --scene '" + (dir / "scene.json").string() + "' --out '" +
                                                (dir / "again").string() + "' --probes '" + (dir / "probes.csv").string() +
                                                "' --probes-out '" + (dir / "scene_probes.csv").string() + "'",
                                            dir);
  INFO(again.err);
  REQUIRE(again.exit_status == 0);
  CHECK(again.out.empty());
  const auto rows_again = kerf_test::read_csv_rows(dir / "scene_probes.csv", header);
  REQUIRE(rows_again.size() == rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k)
    for (std::size_t c = 3; c < 6; ++c) CHECK(rows_again[k][c] == kerf_test::relative(rows[k][c], 1e-9));
}

TEST_CASE("--moments-out writes every piece's moments, which add up to each cut tet's") {
  const auto dir = kerf_test::fresh_dir("chapter04_moments");
  // A plane z = 0.1 + 0.2 x clean through: cut tets have two pieces each.
  kerf_test::write_text(dir / "scene.json",
                        scene_with("1", R"("cuts": [{"rectangle": {"origin": [-0.01, -0.01, 0.098], "edge1": [0.05, 0, 0.01], "edge2": [0, 0.08, 0]}}],
  "quadrature": {"rule": "subtets"})"));
  const auto run = kerf_test::run_program(chapter_04 + " --quiet --scene '" + (dir / "scene.json").string() + "' --out '" +
                                              (dir / "out").string() + "' --moments-out '" + (dir / "moments.csv").string() + "'",
                                          dir);
  INFO(run.err);
  REQUIRE(run.exit_status == 0);
  std::string header;
  const auto rows = kerf_test::read_csv_rows(dir / "moments.csv", header);
  CHECK(header == "element,piece,volume,mx,my,mz,mxx,myy,mzz,mxy,myz,mxz");
  REQUIRE(!rows.empty());
  // Per element: the pieces' volumes add up to the tet's. The box mesher splits every cell
  // (0.01 x 0.01 x 0.2 / 19 m) into six tets around its diagonal (Kuhn), all of volume cell / 6.
  std::map<int, double> volume;
  std::map<int, int> count;
  for (const auto& row : rows) {
    REQUIRE(row.size() == 12);
    CHECK(row[2] > 0.0);
    volume[static_cast<int>(row[0])] += row[2];
    ++count[static_cast<int>(row[0])];
  }
  const double cell = 0.01 * 0.01 * (0.2 / 19.0);
  for (const auto& [element, v] : volume) {
    CHECK(count[element] == 2);
    CHECK(v == kerf_test::relative(cell / 6.0, 1e-12));
  }
}

TEST_CASE("two cuts, a rectangle and a surface, in one scene") {
  const auto dir = kerf_test::fresh_dir("chapter04_two_cuts");
  // The second cut: the plane z = 0.11 as a triangle-mesh file, reaching out of the beam.
  kerf_test::write_text(dir / "sheet.obj", "v -0.01 -0.01 0.11\nv 0.04 -0.01 0.11\nv 0.04 0.07 0.11\nv -0.01 0.07 0.11\nf 1 2 3\nf 1 3 4\n");
  kerf_test::write_text(dir / "scene.json",
                        scene_with("1", R"("cuts": [{"rectangle": {"origin": [0, 0, 0.1], "edge1": [0.015, 0, 0], "edge2": [0, 0.06, 0]}},
           {"surface": {"file": "sheet.obj", "scale": 1.0}}])"));
  const auto run =
      kerf_test::run_program(chapter_04 + " --scene '" + (dir / "scene.json").string() + "' --out '" + (dir / "out").string() + "'", dir);
  INFO(run.out, run.err);
  REQUIRE(run.exit_status == 0);
  // The cuts lie 0.01 m apart, less than two element layers (0.2 / 19 = 0.0105 m): the support of
  // a node in the layer between them reaches both, and falls in three parts.
  CHECK(run.out.find("at most 2 on one node") != std::string::npos);
}

TEST_CASE("bad cut surfaces, rules and options get a one-line error or a warning") {
  const auto dir = kerf_test::fresh_dir("chapter04_bad_input");
  const auto run_scene = [&](const std::string& name, const std::string& scene_text, const std::string& extra = "") {
    kerf_test::write_text(dir / (name + ".json"), scene_text);
    return kerf_test::run_program(chapter_04 + " --quiet --scene '" + (dir / (name + ".json")).string() + "' --out '" +
                                      (dir / name).string() + "'" + extra,
                                  dir);
  };
  SUBCASE("a degenerate triangle names the file and the triangle") {
    kerf_test::write_text(dir / "flat.obj", "v 0 0 0.1\nv 0.01 0 0.1\nv 0.02 0 0.1\nf 1 2 3\n");
    const auto run = run_scene("flat", scene_with("1", R"("cuts": [{"surface": "flat.obj"}])"));
    CHECK(run.exit_status == 2);
    CHECK(run.err.find("flat.obj") != std::string::npos);
    CHECK(run.err.find("degenerate") != std::string::npos);
  }
  SUBCASE("a surface that misses the mesh: a warning and an uncut run") {
    kerf_test::write_text(dir / "far.obj", "v 1 1 1\nv 2 1 1\nv 1 2 1\nf 1 2 3\n");
    const auto run = run_scene("far", scene_with("1", R"("cuts": [{"surface": "far.obj"}])"));
    CHECK(run.exit_status == 0);
    CHECK(run.err.find("does not meet the mesh") != std::string::npos);
  }
  SUBCASE("volume ratios on a Tet10 mesh") {
    const auto run = run_scene("ratio", scene_with("2", R"("cuts": [{"rectangle": {"origin": [0, 0, 0.1], "edge1": [0.015, 0, 0], "edge2": [0, 0.06, 0]}}],
  "quadrature": {"rule": "volume_ratio"})"));
    CHECK(run.exit_status == 2);
    CHECK(run.err.find("quadrature.rule") != std::string::npos);
  }
  SUBCASE("an unknown rule") {
    const auto run = run_scene("unknown", scene_with("1", R"("quadrature": {"rule": "gauss"})"));
    CHECK(run.exit_status == 2);
    CHECK(run.err.find("quadrature.rule") != std::string::npos);
  }
  SUBCASE("chapter 3 refuses --moments-out, surfaces and the quadrature field") {
    kerf_test::write_text(dir / "sheet.obj", "v -0.01 -0.01 0.12\nv 0.04 -0.01 0.12\nv 0.04 0.07 0.12\nf 1 2 3\n");
    const auto moments = kerf_test::run_program(chapter_03 + " --quiet --moments-out x.csv", dir);
    CHECK(moments.exit_status == 2);
    CHECK(moments.err.find("chapter 4") != std::string::npos);
    kerf_test::write_text(dir / "surface.json", scene_with("1", R"("cuts": [{"surface": "sheet.obj"}])"));
    const auto surface = kerf_test::run_program(chapter_03 + " --quiet --scene '" + (dir / "surface.json").string() + "'", dir);
    CHECK(surface.exit_status == 2);
    CHECK(surface.err.find("chapter 4") != std::string::npos);
    kerf_test::write_text(dir / "rule.json", scene_with("1", R"("cuts": [{"rectangle": {"origin": [0, 0, 0.1], "edge1": [0.015, 0, 0], "edge2": [0, 0.06, 0]}}],
  "quadrature": {"rule": "exact"})"));
    const auto rule = kerf_test::run_program(chapter_03 + " --quiet --scene '" + (dir / "rule.json").string() + "'", dir);
    CHECK(rule.exit_status == 2);
    CHECK(rule.err.find("chapter 4") != std::string::npos);
  }
}
