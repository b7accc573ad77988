// Chapter 5: a Dirichlet entry's "displacement_file". Malformed files are one-line
// errors naming the file and the line; a node without a row is an error naming the node and the
// file; a linear field prescribed by file on the whole boundary of a Tet4 and a Tet10 box is
// reproduced inside to round-off (the patch test through the file path); and chapter 4's program
// runs a cut body with its whole boundary prescribed by file.
#include "support/run_program.hpp"

#include "kerf/app/input_error.hpp"
#include "kerf/fem/solve_linear_static.hpp"
#include "kerf/fracture/williams_field.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"
#include "kerf/scene/scene.hpp"
#include "kerf/scene/scene_mesh.hpp"

#include <doctest/doctest.h>

#include <Eigen/Core>
#include <sstream>
#include <string>

namespace {

const std::string chapter_04 = std::string(KERF_BINARY_DIR) + "/bin/04_cut_quadrature";

// The message of the InputError that reading `scene` throws ("" if none).
std::string scene_error(const std::filesystem::path& scene) {
  try {
    kerf::read_scene_file(scene);
  } catch (const kerf::InputError& error) {
    return error.what();
  }
  return "";
}

// A scene on a unit box whose one Dirichlet entry is `entry`.
std::string unit_box_scene(const std::string& entry) {
  return R"({"mesh": {"box": {"min": [0, 0, 0], "max": [1, 1, 1], "cells": [1, 1, 1]}},
             "dirichlet": [)" + entry + "]}";
}

// The six faces of the box [min, max] as Dirichlet entries that all read `file`.
std::string whole_boundary_from(const Eigen::Vector3d& min, const Eigen::Vector3d& max, const std::string& file) {
  std::ostringstream out;
  out.precision(17);
  for (int axis = 0; axis < 3; ++axis)
    for (const double side : {min[axis], max[axis]}) {
      Eigen::Vector3d lo = min, hi = max;
      lo[axis] = hi[axis] = side;
      out << (axis == 0 && side == min[axis] ? "" : ",\n") << R"({"region": {"box": {"min": [)" << lo[0] << ", " << lo[1] << ", "
          << lo[2] << "], \"max\": [" << hi[0] << ", " << hi[1] << ", " << hi[2] << "]}}, \"displacement_file\": \"" << file << "\"}";
    }
  return out.str();
}

// Rows x,y,z,ux,uy,uz of u(x) = A x + c at the nodes of `mesh` on the boundary of [min, max].
std::string boundary_rows(const kerf::TetMesh& mesh, const Eigen::Vector3d& min, const Eigen::Vector3d& max, const Eigen::Matrix3d& A,
                          const Eigen::Vector3d& c, int& rows) {
  std::ostringstream out;
  out.precision(17);
  out << "x,y,z,ux,uy,uz\n";
  rows = 0;
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) {
    const Eigen::Vector3d x = mesh.nodes.row(v).transpose();
    if (!((x - min).minCoeff() < 1e-12 || (max - x).minCoeff() < 1e-12)) continue;
    const Eigen::Vector3d u = A * x + c;
    out << x[0] << "," << x[1] << "," << x[2] << "," << u[0] << "," << u[1] << "," << u[2] << "\n";
    ++rows;
  }
  return out.str();
}

} // namespace

TEST_CASE("a malformed displacement file is a one-line error naming the file and the line") {
  const auto dir = kerf_test::fresh_dir("displacement_file_malformed");
  const std::string good_row = "0,0,0,1,2,3\n";
  struct Case {
    std::string name, text, line, says;
  };
  const Case cases[] = {
      {"header", "x,y,z,ux,uy\n" + good_row, "line 1", "expected the header x,y,z,ux,uy,uz"},
      {"columns", "x,y,z,ux,uy,uz\n" + good_row + "1,0,0,1,2\n", "line 3", "expected 6 finite numbers"},
      {"extra", "x,y,z,ux,uy,uz\n1,0,0,1,2,3,4\n", "line 2", "expected 6 finite numbers"},
      {"trailing_comma", "x,y,z,ux,uy,uz\n1,0,0,1,2,3,\n", "line 2", "expected 6 finite numbers"},
      {"word", "x,y,z,ux,uy,uz\n\n1,0,0,1,two,3\n", "line 3", "expected 6 finite numbers"},
      {"nan", "x,y,z,ux,uy,uz\n" + good_row + "1,0,0,nan,2,3\n", "line 3", "expected 6 finite numbers"},
      {"inf", "x,y,z,ux,uy,uz\n1,0,0,1,2,inf\n", "line 2", "expected 6 finite numbers"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.name);
    kerf_test::write_text(dir / (c.name + ".csv"), c.text);
    kerf_test::write_text(dir / (c.name + ".json"),
                          unit_box_scene(R"({"region": {"nodes": [0]}, "displacement_file": ")" + c.name + R"(.csv"})"));
    const std::string message = scene_error(dir / (c.name + ".json"));
    CHECK(message.find((dir / (c.name + ".csv")).string() + ": " + c.line + ": " + c.says) == 0);
    CHECK(message.find('\n') == std::string::npos);
  }
}

TEST_CASE("the displacement_file field: a missing file, an empty path, and a file with a displacement are errors naming the field") {
  const auto dir = kerf_test::fresh_dir("displacement_file_field");
  kerf_test::write_text(dir / "u.csv", "x,y,z,ux,uy,uz\n0,0,0,1,2,3\n");
  const std::string field = "dirichlet[0].displacement_file: ";
  kerf_test::write_text(dir / "missing.json", unit_box_scene(R"({"region": {"nodes": [0]}, "displacement_file": "none.csv"})"));
  CHECK(scene_error(dir / "missing.json").find(field + "no such file") != std::string::npos);
  kerf_test::write_text(dir / "empty.json", unit_box_scene(R"({"region": {"nodes": [0]}, "displacement_file": ""})"));
  CHECK(scene_error(dir / "empty.json").find(field + "expected a non-empty path") != std::string::npos);
  kerf_test::write_text(dir / "both.json",
                        unit_box_scene(R"({"region": {"nodes": [0]}, "displacement": [0, 0, 0], "displacement_file": "u.csv"})"));
  CHECK(scene_error(dir / "both.json").find(field + "expected either") != std::string::npos);
  kerf_test::write_text(dir / "number.json", unit_box_scene(R"({"region": {"nodes": [0]}, "displacement_file": 3})"));
  CHECK(scene_error(dir / "number.json").find(field + "expected a string") != std::string::npos);
}

TEST_CASE("each node takes the row at its position; a node without a row is an error naming the node and the file") {
  const auto dir = kerf_test::fresh_dir("displacement_file_rows");
  // The unit box's 8 nodes; the rows in another order, one of them off by 1e-12 (inside the
  // tolerance of 1e-9 times the diagonal, 1.7e-9 m) and one row at no node (ignored).
  kerf_test::write_text(dir / "u.csv", "x,y,z,ux,uy,uz\n"
                                       "1,1,1,7,0,0\n0,0,0,0,0,0\n1,0,0,1,0,0\n0,1,0,2,0,0\n1,1,0,3,0,0\n"
                                       "0,0,1.000000000001,4,0,0\n1,0,1,5,0,0\n0,1,1,6,0,0\n0.5,0.5,0.5,99,0,0\n");
  kerf_test::write_text(dir / "all.json", unit_box_scene(R"({"region": {"box": {"min": [0, 0, 0], "max": [1, 1, 1]}}, "displacement_file": "u.csv"})"));
  const kerf::Scene scene = kerf::read_scene_file(dir / "all.json");
  const kerf::TetMesh mesh = kerf::make_scene_mesh(scene, nullptr);
  const Eigen::VectorXd u = kerf::scene_prescribed_displacements(scene, mesh, 0.5);
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) {
    const Eigen::Vector3d x = mesh.nodes.row(v).transpose();
    // The file's ux is the node's corner number x + 2 y + 4 z; the load factor 0.5 scales it.
    CHECK(u[3 * v] == 0.5 * (x[0] + 2 * x[1] + 4 * x[2]));
  }

  // The row at (1, 1, 1) moved by 1e-8 m: beyond the tolerance, so node (1, 1, 1) has no row.
  kerf_test::write_text(dir / "short.csv", "x,y,z,ux,uy,uz\n0,0,0,0,0,0\n1,1,1.00000001,7,0,0\n");
  kerf_test::write_text(dir / "short.json",
                        unit_box_scene(R"({"region": {"box": {"min": [0, 0, 0], "max": [1, 1, 1]}}, "displacement_file": "short.csv"})"));
  const kerf::Scene short_scene = kerf::read_scene_file(dir / "short.json");
  const kerf::TetMesh short_mesh = kerf::make_scene_mesh(short_scene, nullptr);
  std::string message;
  try {
    kerf::scene_dirichlet_nodes(short_scene, short_mesh);
  } catch (const kerf::InputError& error) {
    message = error.what();
  }
  // The first node without a row, in node order: the box mesher's node 1 is (1, 0, 0).
  CHECK(message.find((dir / "short.csv").string() + ": node 1: no row at the node's position (1, 0, 0)") == 0);
  CHECK(message.find("dirichlet[0] of " + (dir / "short.json").string()) != std::string::npos);
}

TEST_CASE("a linear field prescribed by file on the whole boundary is reproduced inside, Tet4 and Tet10 (the patch test)") {
  const Eigen::Vector3d min(0.0, 0.0, 0.0), max(0.03, 0.06, 0.1);
  Eigen::Matrix3d A;
  A << 1e-3, 2e-4, -3e-4, 5e-4, -7e-4, 1e-4, -2e-4, 3e-4, 6e-4;
  const Eigen::Vector3d c(1e-4, -2e-4, 5e-5);
  for (const int order : {1, 2}) {
    CAPTURE(order);
    const auto dir = kerf_test::fresh_dir("displacement_file_patch_" + std::to_string(order));
    kerf::TetMesh mesh = kerf::make_box_mesh(min, max, Eigen::Vector3i(3, 4, 5));
    if (order == 2) mesh = kerf::tet10_from_tet4(mesh);
    int rows = 0;
    kerf_test::write_text(dir / "linear.csv", boundary_rows(mesh, min, max, A, c, rows));
    kerf_test::write_text(dir / "patch.json", R"({"mesh": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0.1], "cells": [3, 4, 5]}, "order": )" +
                                                  std::to_string(order) + R"(},
      "material": {"young": 300e3, "poisson": 0.35},
      "dirichlet": [)" + whole_boundary_from(min, max, "linear.csv") + "]}");
    const kerf::Scene scene = kerf::read_scene_file(dir / "patch.json");
    const kerf::TetMesh scene_mesh = kerf::make_scene_mesh(scene, nullptr);
    const kerf::DofMap dofs = kerf::scene_dof_map(scene, scene_mesh, nullptr);
    // Only the interior nodes are free: the file has rows for the boundary nodes only.
    CHECK(dofs.num_free == 3 * (scene_mesh.num_nodes() - rows));
    REQUIRE(dofs.num_free > 0);
    const Eigen::VectorXd u = kerf::solve_linear_static(scene_mesh, scene.material, dofs, Eigen::VectorXd::Zero(3 * scene_mesh.num_nodes()), scene.solver);
    double error = 0.0, size = 0.0;
    for (Eigen::Index v = 0; v < scene_mesh.num_nodes(); ++v) {
      const Eigen::Vector3d exact = A * scene_mesh.nodes.row(v).transpose() + c;
      error = std::max(error, (u.segment<3>(3 * v) - exact).norm());
      size = std::max(size, exact.norm());
    }
    // A linear field is in the Tet4 and the Tet10 space and has no body force: the FE solution
    // is the field itself, up to the round-off of the solve (cond(K_ff) * 1e-16, small on this
    // 60-cell box): 1e-11 of the largest displacement.
    CHECK(error <= 1e-11 * size);
  }
}

TEST_CASE("chapter 4's program prescribes a uniaxial field by file on the whole boundary of a cut beam and reproduces it") {
  // u = eps (x, -nu y, -nu z): uniaxial stress sigma_xx = E eps. The cut lies in a plane z = const,
  // where this stress has no traction, so the cut body's solution is the field itself, on both
  // sides of the cut: the enrichments of the gripped boundary nodes are held at zero (their
  // standard DOFs take the file's value) and the free ones come out zero.
  const auto dir = kerf_test::fresh_dir("displacement_file_chapter_04");
  const Eigen::Vector3d min(0.0, 0.0, 0.0), max(0.03, 0.06, 0.2);
  const double eps = 1e-3, nu = 0.35;
  Eigen::Matrix3d A = Eigen::Vector3d(eps, -nu * eps, -nu * eps).asDiagonal();
  kerf::TetMesh mesh = kerf::make_box_mesh(min, max, Eigen::Vector3i(3, 6, 19));
  int rows = 0;
  kerf_test::write_text(dir / "uniaxial.csv", boundary_rows(mesh, min, max, A, Eigen::Vector3d::Zero(), rows));
  kerf_test::write_text(dir / "scene.json", R"({"name": "uniaxial",
    "mesh": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0.2], "cells": [3, 6, 19]}, "order": 1},
    "material": {"young": 300e3, "poisson": 0.35, "density": 1070},
    "model": "linear",
    "cuts": [{"rectangle": {"origin": [-0.01, -0.01, 0.1013], "edge1": [0.025, 0, 0], "edge2": [0, 0.08, 0]}}],
    "dirichlet": [)" + whole_boundary_from(min, max, "uniaxial.csv") + "]}");
  const std::vector<Eigen::Vector3d> probes{{0.005, 0.03, 0.1018}, {0.005, 0.03, 0.1008}, {0.025, 0.03, 0.1013}};
  std::ostringstream probe_text;
  probe_text.precision(17);
  probe_text << "x,y,z\n";
  for (const Eigen::Vector3d& p : probes) probe_text << p[0] << "," << p[1] << "," << p[2] << "\n";
  kerf_test::write_text(dir / "probes.csv", probe_text.str());
  const auto run = kerf_test::run_program(chapter_04 + " --scene '" + (dir / "scene.json").string() + "' --out '" + (dir / "out").string() +
                                              "' --probes '" + (dir / "probes.csv").string() + "' --probes-out '" +
                                              (dir / "probes_out.csv").string() + "'",
                                          dir);
  INFO(run.out, run.err);
  REQUIRE(run.exit_status == 0);
  std::string header;
  const auto values = kerf_test::read_csv_rows(dir / "probes_out.csv", header);
  REQUIRE(values.size() == probes.size());
  for (std::size_t p = 0; p < probes.size(); ++p) {
    const Eigen::Vector3d exact = A * probes[p];
    const Eigen::Vector3d computed(values[p][3], values[p][4], values[p][5]);
    CAPTURE(p);
    // Round-off of the solve, relative to the largest displacement (eps * 0.2 m * nu = 7e-5 m).
    CHECK((computed - exact).norm() <= 1e-11 * 7e-5);
  }
}

TEST_CASE("Williams's field written at a slab's nodes is what a scene prescribes on the slab's whole boundary") {
  // The validation scene's path: write_williams_displacement_file at the mesh's nodes, one entry
  // per face reading the file, and every boundary node gets the field's value, bit for bit (the
  // file holds 17 digits), the interior nodes nothing.
  const auto dir = kerf_test::fresh_dir("displacement_file_williams");
  const Eigen::Vector3d min(-0.01, -0.01, 0.0), max(0.01, 0.01, 0.005);
  const kerf::TetMesh mesh = kerf::tet10_from_tet4(kerf::make_box_mesh(min, max, Eigen::Vector3i(4, 4, 2)));
  const kerf::StraightFrontFrame front = kerf::make_straight_front_frame({0.0013, 0.0007, 0.0}, {1, 0, 0}, {0, 1, 0});
  const kerf::LinearMaterial material{300e3, 0.35, 1070};
  const kerf::StressIntensityFactors K{1.0, 0.3, 0.0};
  kerf::write_williams_displacement_file(dir / "williams.csv", front, K, material, mesh.nodes);
  kerf_test::write_text(dir / "slab.json", R"({"mesh": {"box": {"min": [-0.01, -0.01, 0], "max": [0.01, 0.01, 0.005], "cells": [4, 4, 2]}, "order": 2},
      "dirichlet": [)" + whole_boundary_from(min, max, "williams.csv") + "]}");
  const kerf::Scene scene = kerf::read_scene_file(dir / "slab.json");
  const kerf::TetMesh scene_mesh = kerf::make_scene_mesh(scene, nullptr);
  REQUIRE(scene_mesh.nodes == mesh.nodes);
  const kerf::DofMap dofs = kerf::scene_dof_map(scene, scene_mesh, nullptr);
  int boundary = 0;
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) {
    const Eigen::Vector3d x = mesh.nodes.row(v).transpose();
    const bool on_boundary = (x - min).minCoeff() < 1e-12 || (max - x).minCoeff() < 1e-12;
    boundary += on_boundary;
    CHECK((dofs.free_index[static_cast<std::size_t>(3 * v)] < 0) == on_boundary);
    if (on_boundary) CHECK(dofs.prescribed.segment<3>(3 * v) == kerf::williams_displacement(front, K, material, x));
  }
  CHECK(dofs.num_free == 3 * (mesh.num_nodes() - boundary));
}
