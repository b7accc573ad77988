// Chapter 1 from the command line: the demo, a scene with probes (a linear field reproduced
// exactly at arbitrary points), a bar hanging under its own weight (a quadratic field, exact
// with Tet10), and every kind of bad input refused with one line and a non-zero exit status.
#include "support/hanging_bar.hpp"
#include "support/run_program.hpp"

#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"

#include <doctest/doctest.h>

#include <Eigen/Core>
#include <random>
#include <sstream>

namespace {

const std::string program = std::string(KERF_BINARY_DIR) + "/bin/01_linear_fem";

int count_lines(const std::string& text) {
  int lines = 0;
  for (char c : text) lines += c == '\n';
  return lines;
}

// Reads the probe output back: #P by 6 (x, y, z, ux, uy, uz), NaN for "nan".
Eigen::MatrixXd read_probe_output(const std::filesystem::path& file, std::string& header) {
  std::stringstream in(kerf_test::read_text(file));
  std::getline(in, header);
  std::vector<std::array<double, 6>> rows;
  std::string line;
  while (std::getline(in, line)) {
    std::array<double, 6> row{};
    std::stringstream cells(line);
    std::string cell;
    for (auto& value : row) {
      std::getline(cells, cell, ',');
      value = std::stod(cell); // stod reads "nan" as NaN
    }
    rows.push_back(row);
  }
  Eigen::MatrixXd values(static_cast<Eigen::Index>(rows.size()), 6);
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (int c = 0; c < 6; ++c) values(static_cast<Eigen::Index>(r), c) = rows[r][static_cast<std::size_t>(c)];
  return values;
}

} // namespace

TEST_CASE("the demo runs without arguments and writes its .vtu file") {
  const auto dir = kerf_test::fresh_dir("demo");
  const auto result = kerf_test::run_program(program + " --out '" + dir.string() + "'", dir);
  CHECK(result.exit_status == 0);
  CHECK(result.err.empty());
  CHECK(std::filesystem::file_size(dir / "beam_gravity.vtu") > 1000);
  CHECK(result.out.find("2160 Tet10") != std::string::npos);
}

TEST_CASE("--help prints the usage and exits 0") {
  const auto dir = kerf_test::fresh_dir("help");
  const auto result = kerf_test::run_program(program + " --help", dir);
  CHECK(result.exit_status == 0);
  CHECK(result.out.find("usage: 01_linear_fem") == 0);
}

TEST_CASE("a scene with probes: a linear field is reproduced exactly at arbitrary points") {
  // Dirichlet data u = c + A x on every boundary node of a box (one region per node, by index),
  // no load: the exact solution is that linear field, which Tet4 and Tet10 contain, so the
  // probe values must equal it to round-off, wherever the probes are.
  const Eigen::Vector3d lo(0, 0, 0), hi(0.03, 0.06, 0.2);
  Eigen::Matrix3d A;
  A << 0.01, 0.002, -0.003, 0.0, -0.004, 0.001, 0.002, 0.003, 0.02;
  const Eigen::Vector3d c(1e-4, -2e-4, 3e-4);

  for (int order : {1, 2}) {
    CAPTURE(order);
    const auto dir = kerf_test::fresh_dir("probes_order" + std::to_string(order));
    // The node numbering of the mesh the program builds: Tet4 nodes first, then mid-edge nodes.
    kerf::TetMesh mesh = kerf::make_box_mesh(lo, hi, {2, 3, 6});
    if (order == 2) mesh = kerf::tet10_from_tet4(mesh);
    const kerf::BoundaryFaces boundary = kerf::boundary_faces(mesh);
    std::vector<char> on_boundary(static_cast<std::size_t>(mesh.num_nodes()), 0);
    for (Eigen::Index f = 0; f < boundary.faces.rows(); ++f)
      for (int k = 0; k < boundary.faces.cols(); ++k) on_boundary[static_cast<std::size_t>(boundary.faces(f, k))] = 1;
    std::stringstream scene;
    scene.precision(17);
    scene << R"({"mesh": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0.2], "cells": [2, 3, 6]}, "order": )" << order
          << R"(}, "dirichlet": [)";
    bool first = true;
    for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) {
      if (!on_boundary[static_cast<std::size_t>(v)]) continue;
      const Eigen::Vector3d u = c + A * mesh.nodes.row(v).transpose();
      scene << (first ? "" : ",") << R"({"region": {"nodes": [)" << v << R"(]}, "displacement": [)" << u[0] << "," << u[1] << ","
            << u[2] << "]}";
      first = false;
    }
    scene << "]}";
    kerf_test::write_text(dir / "patch.json", scene.str());

    std::stringstream probes;
    probes.precision(17);
    probes << "x,y,z\n";
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> t(0.0, 1.0);
    std::vector<Eigen::Vector3d> points;
    for (int p = 0; p < 20; ++p) points.push_back(lo + Eigen::Vector3d(t(rng), t(rng), t(rng)).cwiseProduct(hi - lo));
    points.push_back(hi);                           // a corner node
    points.push_back(Eigen::Vector3d(0.5, 0, 0));   // outside: nan
    for (const auto& x : points) probes << x[0] << "," << x[1] << "," << x[2] << "\n";
    kerf_test::write_text(dir / "probes.csv", probes.str());

    const auto result = kerf_test::run_program(program + " --quiet --scene '" + (dir / "patch.json").string() + "' --probes '" +
                                                   (dir / "probes.csv").string() + "' --probes-out '" +
                                                   (dir / "out/probes_out.csv").string() + "' --out '" + (dir / "out").string() + "'",
                                               dir);
    REQUIRE(result.exit_status == 0);
    CHECK(result.out.empty()); // --quiet
    CHECK(result.err.find("1 of 22 probe points are outside the mesh") != std::string::npos);
    std::string header;
    const Eigen::MatrixXd values = read_probe_output(dir / "out/probes_out.csv", header);
    CHECK(header == "x,y,z,ux,uy,uz");
    REQUIRE(values.rows() == 22);
    for (int p = 0; p < 21; ++p) {
      CHECK((values.row(p).head<3>().transpose() - points[static_cast<std::size_t>(p)]).norm() == 0.0);
      const Eigen::Vector3d exact = c + A * points[static_cast<std::size_t>(p)];
      CHECK((values.row(p).tail<3>().transpose() - exact).norm() < 1e-13);
    }
    CHECK(std::isnan(values(21, 3)));
  }
}

TEST_CASE("probes under gravity and a traction: a bar hanging under its own weight is exact with Tet10") {
  // The independent reference is the closed-form solution of support::HangingBar (quadratic,
  // so in the Tet10 space): the probe values must equal it to round-off at arbitrary points.
  const support::HangingBar bar;
  const auto dir = kerf_test::fresh_dir("probes_gravity");
  kerf_test::write_text(dir / "bar.json", bar.scene_json(2));
  std::vector<Eigen::Vector3d> points{{0.015, 0.03, 0.2}, {0.03, 0.06, 0.1}, {0.01, 0.02, 0.05}, {0.0, 0.0, 0.0}};
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> t(0.0, 1.0);
  for (int p = 0; p < 16; ++p) points.emplace_back(0.03 * t(rng), 0.06 * t(rng), 0.2 * t(rng));
  std::stringstream probes;
  probes.precision(17);
  probes << "x,y,z\n";
  for (const auto& x : points) probes << x[0] << "," << x[1] << "," << x[2] << "\n";
  kerf_test::write_text(dir / "probes.csv", probes.str());
  const auto result = kerf_test::run_program(program + " --quiet --scene '" + (dir / "bar.json").string() + "' --probes '" +
                                                 (dir / "probes.csv").string() + "' --probes-out '" + (dir / "p.csv").string() +
                                                 "' --out '" + dir.string() + "'",
                                             dir);
  REQUIRE(result.exit_status == 0);
  CHECK(result.err.empty());
  std::string header;
  const Eigen::MatrixXd values = read_probe_output(dir / "p.csv", header);
  REQUIRE(values.rows() == static_cast<Eigen::Index>(points.size()));
  double worst = 0.0, largest = 0.0;
  for (std::size_t p = 0; p < points.size(); ++p) {
    const Eigen::Vector3d exact = bar.displacement(points[p]);
    largest = std::max(largest, exact.norm());
    worst = std::max(worst, (values.row(static_cast<Eigen::Index>(p)).tail<3>().transpose() - exact).norm());
  }
  MESSAGE("hanging bar, Tet10: max probe error " << worst << " m, largest |u| " << largest << " m");
  // u_z grows from nu rho g r^2 / (2E) ~ 7 um at the bottom corners to rho g L^2 / (2E) = 0.70 mm
  // at the top centre, and the section contracts laterally: the field is not trivial.
  CHECK(largest > 6e-4);
  // Round-off only: a 2x3x8 Tet10 system held at three points has a condition number of
  // ~1e7 or less, so the solve loses at most ~1e-9 relative; 1e-8 of |u| is still a thousand
  // times below any consistency error (a wrong load or stiffness entry changes u at O(1)).
  CHECK(worst <= 1e-8 * largest);
}

TEST_CASE("bad input: one line on stderr naming the file and field, and a non-zero exit") {
  const auto dir = kerf_test::fresh_dir("bad_input");
  const std::string box = R"("mesh": {"box": {"min": [0, 0, 0], "max": [1, 1, 1], "cells": [1, 1, 1]}})";
  const std::string fixed = R"("dirichlet": [{"region": {"box": {"min": [0, 0, 0], "max": [1, 1, 0]}}}])";
  kerf_test::write_text(dir / "truncated.json", R"({"mesh": {"box": )");
  kerf_test::write_text(dir / "unknown.json", "{" + box + R"(, "gravty": [0, 0, -9.81]})");
  kerf_test::write_text(dir / "cut.json", "{" + box + "," + fixed +
                                              R"(, "cuts": [{"rectangle": {"origin": [0,0,0.5], "edge1": [1,0,0], "edge2": [0,1,0]}}]})");
  kerf_test::write_text(dir / "corotational.json", "{" + box + "," + fixed + R"(, "model": "corotational"})");
  kerf_test::write_text(dir / "free.json", "{" + box + R"(, "gravity": [0, 0, -9.81]})");
  kerf_test::write_text(dir / "empty_region.json", "{" + box + R"(, "dirichlet": [{"region": {"box": {"min": [5, 5, 5], "max": [6, 6, 6]}}}]})");
  kerf_test::write_text(dir / "node_index.json", "{" + box + R"(, "dirichlet": [{"region": {"nodes": [0, 1, 999]}}]})");
  kerf_test::write_text(dir / "no_faces.json", "{" + box + "," + fixed + R"(, "traction": [{"region": {"nodes": [0]}, "total_force": [1, 0, 0]}]})");
  kerf_test::write_text(dir / "missing_mesh.json", R"({"mesh": {"file": "nowhere.msh"}})");
  kerf_test::write_text(dir / "bad_mesh.json", R"({"mesh": {"file": "bad.msh"}})");
  kerf_test::write_text(dir / "bad.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n");
  kerf_test::write_text(dir / "good.json", "{" + box + "," + fixed + "}");
  kerf_test::write_text(dir / "bad_probes.csv", "x,y,z\n0.1,0.2\n");

  struct Case {
    std::string arguments, must_mention;
  };
  const std::string d = dir.string() + "/";
  const Case cases[] = {
      {"--scene " + d + "truncated.json", "truncated.json: JSON:"},
      {"--scene " + d + "unknown.json", "unknown.json: gravty: unknown field"},
      {"--scene " + d + "cut.json", "cut.json: cuts: cuts are taught from chapter 3"},
      {"--scene " + d + "corotational.json", "corotational.json: model:"},
      {"--scene " + d + "free.json", "free.json: dirichlet: the conditions leave 6 rigid motions"},
      {"--scene " + d + "empty_region.json", "empty_region.json: dirichlet[0].region: the region contains no node"},
      {"--scene " + d + "node_index.json", "node_index.json: dirichlet[0].region.nodes: node index 999"},
      {"--scene " + d + "no_faces.json", "no_faces.json: traction[0].region: no boundary face"},
      {"--scene " + d + "missing_mesh.json", "missing_mesh.json: mesh.file: no such file"},
      {"--scene " + d + "bad_mesh.json", "bad.msh"},
      {"--scene " + d + "nonexistent.json", "nonexistent.json: file: cannot open"},
      {"--scene " + d + "good.json --probes " + d + "bad_probes.csv --probes-out " + d + "o.csv", "bad_probes.csv: line 2:"},
      {"--scene " + d + "good.json --probes " + d + "bad_probes.csv", "command line: --probes:"},
      {"--frobnicate", "command line: --frobnicate: unknown option"},
      {"--scene", "command line: --scene: expected a value"},
  };
  for (const auto& c : cases) {
    CAPTURE(c.arguments);
    const auto result = kerf_test::run_program(program + " --quiet --out " + d + "out " + c.arguments, dir);
    CHECK(result.exit_status == 2);
    CHECK(count_lines(result.err) == 1);
    CHECK(result.err.rfind("01_linear_fem: error: ", 0) == 0);
    CHECK(result.err.find(c.must_mention) != std::string::npos);
    CAPTURE(result.err);
  }
}
