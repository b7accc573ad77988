// Kerf's chapter 1 against CalculiX on the same imported mesh (C3D4 and C3D10).
//
// The mesh: the beam 0.03 x 0.06 x 0.2 m, 2 x 3 x 8 cells with every interior node moved by up
// to 10% of a cell, written as a Gmsh file. Kerf runs from the command line on a scene that
// imports that file and samples its solution at every node through the probe contract;
// CalculiX gets the mesh Kerf imported.
//
// Two comparisons, because ccx prints only 7 digits (see calculix_deck.hpp):
//  - to 1e-8 relative: CalculiX's own assembled K and M (14 digits) solved in double precision,
//    gravity as M g, a traction as nodal loads from the closed-form face integrals;
//  - to ccx's printing precision (2e-6 of the largest displacement): ccx's own static solve,
//    with its own gravity load and, for the traction, a *DLOAD face pressure that ccx integrates.
#include "support/run_program.hpp"

#include "kerf/io/calculix_deck.hpp"
#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/node_region.hpp"
#include "kerf/mesh/read_mesh.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <random>
#include <sstream>

namespace {

const std::string program = std::string(KERF_BINARY_DIR) + "/bin/01_linear_fem";
const std::string ccx = KERF_CCX;

void write_gmsh_v2(const std::filesystem::path& file, const kerf::TetMesh& mesh) {
  std::stringstream out;
  out.precision(17);
  out << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n" << mesh.num_nodes() << "\n";
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v)
    out << v + 1 << " " << mesh.nodes(v, 0) << " " << mesh.nodes(v, 1) << " " << mesh.nodes(v, 2) << "\n";
  out << "$EndNodes\n$Elements\n" << mesh.num_tets() << "\n";
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    out << t + 1 << " 4 2 0 1 " << mesh.tets(t, 0) + 1 << " " << mesh.tets(t, 1) + 1 << " " << mesh.tets(t, 2) + 1 << " "
        << mesh.tets(t, 3) + 1 << "\n";
  out << "$EndElements\n";
  kerf_test::write_text(file, out.str());
}

// Runs 01_linear_fem on `scene_json` with a probe at every node of `mesh`; returns #V by 3.
Eigen::MatrixXd kerf_nodal_displacements(const std::filesystem::path& dir, const std::string& scene_json,
                                         const kerf::TetMesh& mesh) {
  kerf_test::write_text(dir / "scene.json", scene_json);
  std::stringstream probes;
  probes.precision(17);
  probes << "x,y,z\n";
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) probes << mesh.nodes(v, 0) << "," << mesh.nodes(v, 1) << "," << mesh.nodes(v, 2) << "\n";
  kerf_test::write_text(dir / "nodes.csv", probes.str());
  const auto result = kerf_test::run_program(program + " --quiet --scene '" + (dir / "scene.json").string() + "' --probes '" +
                                                 (dir / "nodes.csv").string() + "' --probes-out '" + (dir / "u.csv").string() +
                                                 "' --out '" + dir.string() + "'",
                                             dir);
  REQUIRE(result.exit_status == 0);
  std::stringstream in(kerf_test::read_text(dir / "u.csv"));
  std::string line;
  std::getline(in, line);
  Eigen::MatrixXd u(mesh.num_nodes(), 3);
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) {
    REQUIRE(std::getline(in, line));
    std::stringstream cells(line);
    std::string cell;
    for (int c = 0; c < 6; ++c) {
      std::getline(cells, cell, ',');
      if (c >= 3) u(v, c - 3) = std::stod(cell);
    }
  }
  return u;
}

double relative_max_difference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& reference) {
  return (a - reference).cwiseAbs().maxCoeff() / reference.cwiseAbs().maxCoeff();
}

} // namespace

TEST_CASE("Kerf agrees with CalculiX (C3D4, C3D10) on an imported mesh, for gravity and traction") {
  REQUIRE_MESSAGE(!ccx.empty(), "calculix-ccx is required for the validation tests (./kerf.sh installs it)");
  const auto root = kerf_test::fresh_dir("kerf_vs_calculix");

  kerf::TetMesh written = kerf::make_box_mesh({0, 0, 0}, {0.03, 0.06, 0.2}, {2, 3, 8});
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> shift(-0.1, 0.1);
  const Eigen::RowVector3d cell(0.015, 0.02, 0.025);
  for (Eigen::Index v = 0; v < written.num_nodes(); ++v) {
    const Eigen::RowVector3d x = written.nodes.row(v);
    const bool interior = x[0] > 1e-9 && x[0] < 0.03 - 1e-9 && x[1] > 1e-9 && x[1] < 0.06 - 1e-9 && x[2] > 1e-9 && x[2] < 0.2 - 1e-9;
    if (interior) written.nodes.row(v) += Eigen::RowVector3d(shift(rng), shift(rng), shift(rng)).cwiseProduct(cell);
  }
  write_gmsh_v2(root / "beam.msh", written);

  const kerf::LinearMaterial material{300e3, 0.35, 1070};
  const std::string fixed = R"("dirichlet": [{"region": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0]}}}])";
  const std::string top_region = R"({"box": {"min": [0, 0, 0.2], "max": [0.03, 0.06, 0.2]}})";

  for (int order : {1, 2}) {
    CAPTURE(order);
    // The mesh exactly as Kerf imports and promotes it: same nodes, same numbering.
    kerf::TetMesh mesh = kerf::read_mesh(root / "beam.msh", nullptr);
    if (order == 2) mesh = kerf::tet10_from_tet4(mesh);
    const std::string mesh_json = R"("mesh": {"file": "beam.msh", "order": )" + std::to_string(order) + "}";

    kerf::NodeRegion bottom, top;
    bottom.box_max = {0.03, 0.06, 0};
    top.box_min = {0, 0, 0.2};
    top.box_max = {0.03, 0.06, 0.2};
    kerf::CalculixJob base;
    base.material = material;
    base.dirichlet = {{kerf::nodes_in_region(mesh, bottom), {0, 0, 0}}};

    // The top faces, their areas and their closed-form nodal weights: A/3 at each corner of a
    // flat three-node face; 0 at the corners and A/3 at the mid-edge nodes of a six-node face.
    const kerf::BoundaryFaces boundary = kerf::boundary_faces(mesh);
    const std::vector<char> on_top = kerf::node_mask(mesh, top);
    std::vector<Eigen::Index> top_faces;
    double top_area = 0.0;
    for (Eigen::Index f = 0; f < boundary.faces.rows(); ++f) {
      bool inside = true;
      for (int c = 0; c < boundary.faces.cols(); ++c) inside = inside && on_top[static_cast<std::size_t>(boundary.faces(f, c))];
      if (!inside) continue;
      top_faces.push_back(f);
      top_area += kerf::face_area(mesh, boundary, f);
    }
    CHECK(top_area == kerf_test::relative(0.03 * 0.06, 1e-12));

    SUBCASE("gravity") {
      const auto dir = root / ("gravity_order" + std::to_string(order));
      std::filesystem::create_directories(dir);
      std::filesystem::copy_file(root / "beam.msh", dir / "beam.msh");
      const Eigen::MatrixXd u_kerf = kerf_nodal_displacements(dir, "{" + mesh_json + "," + fixed + R"(, "gravity": [9.81, 0, 0]})", mesh);
      kerf::CalculixJob job = base;
      job.gravity = {9.81, 0, 0};
      const kerf::CalculixSolution ccx_solution = kerf::solve_with_calculix(ccx, dir / "ccx", "beam", mesh, job);
      MESSAGE("order " << order << " gravity: max |u| = " << u_kerf.cwiseAbs().maxCoeff() << " m, Kerf vs ccx matrices "
                       << relative_max_difference(u_kerf, ccx_solution.displacement) << ", vs ccx static "
                       << relative_max_difference(u_kerf, ccx_solution.static_displacement));
      CHECK(relative_max_difference(u_kerf, ccx_solution.displacement) < 1e-8);
      CHECK(relative_max_difference(u_kerf, ccx_solution.static_displacement) < 2e-6);
    }

    SUBCASE("oblique traction on the top face, as nodal loads") {
      const auto dir = root / ("traction_order" + std::to_string(order));
      std::filesystem::create_directories(dir);
      std::filesystem::copy_file(root / "beam.msh", dir / "beam.msh");
      const Eigen::Vector3d force(0.2, 0.1, -0.5);
      const Eigen::MatrixXd u_kerf = kerf_nodal_displacements(
          dir, "{" + mesh_json + "," + fixed + R"(, "traction": [{"region": )" + top_region + R"(, "total_force": [0.2, 0.1, -0.5]}]})", mesh);
      kerf::CalculixJob job = base;
      job.nodal_loads = Eigen::VectorXd::Zero(3 * mesh.num_nodes());
      for (Eigen::Index f : top_faces) {
        const Eigen::Vector3d face_force = force * kerf::face_area(mesh, boundary, f) / top_area;
        for (int c = 0; c < boundary.faces.cols(); ++c) {
          const double share = order == 1 ? 1.0 / 3.0 : (c < 3 ? 0.0 : 1.0 / 3.0);
          job.nodal_loads.segment<3>(3 * boundary.faces(f, c)) += share * face_force;
        }
      }
      const kerf::CalculixSolution ccx_solution = kerf::solve_with_calculix(ccx, dir / "ccx", "beam", mesh, job);
      MESSAGE("order " << order << " traction: Kerf vs ccx matrices " << relative_max_difference(u_kerf, ccx_solution.displacement));
      CHECK(relative_max_difference(u_kerf, ccx_solution.displacement) < 1e-8);
      CHECK(relative_max_difference(u_kerf, ccx_solution.static_displacement) < 2e-6);
    }

    SUBCASE("normal traction, integrated by CalculiX as a face pressure") {
      const auto dir = root / ("pressure_order" + std::to_string(order));
      std::filesystem::create_directories(dir);
      std::filesystem::copy_file(root / "beam.msh", dir / "beam.msh");
      const Eigen::MatrixXd u_kerf = kerf_nodal_displacements(
          dir, "{" + mesh_json + "," + fixed + R"(, "traction": [{"region": )" + top_region + R"(, "total_force": [0, 0, -0.5]}]})", mesh);
      kerf::CalculixJob job = base;
      std::filesystem::create_directories(dir / "ccx");
      for (Eigen::Index f : top_faces) job.face_pressures.push_back({boundary.tet[static_cast<std::size_t>(f)], boundary.local_face[static_cast<std::size_t>(f)], 0.5 / top_area});
      kerf::write_calculix_deck(dir / "ccx" / "pressure.inp", mesh, job);
      kerf::run_calculix(ccx, dir / "ccx", "pressure");
      const Eigen::MatrixXd u_ccx = kerf::read_calculix_displacements(dir / "ccx" / "pressure.dat", mesh.num_nodes());
      MESSAGE("order " << order << " pressure: Kerf vs ccx static " << relative_max_difference(u_kerf, u_ccx));
      CHECK(relative_max_difference(u_kerf, u_ccx) < 2e-6);
    }
  }
}
