// CalculiX (ccx) as an independent solver: the two routes of kerf/io/calculix_deck.hpp agree
// with each other, and the matrices ccx writes are what they must be. The Kerf-side comparison
// (Kerf's own assembly and solve against ccx to 1e-8) builds on solve_with_calculix.
#include "kerf/io/calculix_deck.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"

#include "support/calculix_path.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace {

/// A folder of the build tree for one test's decks and ccx's output.
std::filesystem::path work_folder(const std::string& name) {
  return std::filesystem::path(KERF_BINARY_DIR) / "tests" / "calculix" / name;
}

constexpr double length_z = 0.2; // m, the long side of the bar

/// A 0.03 x 0.06 x 0.2 m bar, 2 x 2 x 4 cells, six tets per cell; Tet10 by edge midpoints.
kerf::TetMesh bar_mesh(int order) {
  const kerf::TetMesh tet4 =
      kerf::make_box_mesh(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.03, 0.06, length_z), Eigen::Vector3i(2, 2, 4));
  return order == 1 ? tet4 : kerf::tet10_from_tet4(tet4);
}

/// The nodes on the plane z = z0.
std::vector<int> nodes_at_z(const kerf::TetMesh& mesh, double z0) {
  std::vector<int> nodes;
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v)
    if (std::abs(mesh.nodes(v, 2) - z0) < 1e-12) nodes.push_back(static_cast<int>(v));
  return nodes;
}

/// Soft tissue clamped at z = 0, with gravity and/or a force on the nodes of the free end.
kerf::CalculixJob bar_job(const kerf::TetMesh& mesh, bool gravity, bool end_load) {
  kerf::CalculixJob job;
  job.material = {300e3, 0.45, 1000.0}; // soft tissue, nearly incompressible
  job.dirichlet.push_back({nodes_at_z(mesh, 0.0), Eigen::Vector3d::Zero()});
  if (gravity) job.gravity = Eigen::Vector3d(0.0, -5.886, -7.848); // 9.81 m/s^2, tilted
  if (end_load) {
    job.nodal_loads = Eigen::VectorXd::Zero(3 * mesh.num_nodes());
    for (int v : nodes_at_z(mesh, length_z)) job.nodal_loads.segment<3>(3 * v) = Eigen::Vector3d(0.01, 0.0, -0.02);
  }
  return job;
}

/// Checks that the full-precision matrix route and ccx's own 7-digit static solve agree.
///
/// The .dat prints 1p,e13.6: 7 significant digits, so each static value is off by at most half
/// a unit in its 7th digit, 0.5e-6 * 10^floor(log10 |u|). The matrix route has its own, much
/// smaller error: the .sti rounds K to 14 digits, which moves u by about cond(K_ff) * 2e-16
/// (measured: 3e-11 of max |u| for this C3D4 bar, cond 6e4; 2e-10 for C3D10, cond 1.2e6).
/// So every printed value must lie within half a unit of its 7th digit plus 1e-9 max |u| of the
/// full-precision one; a wrong load, DOF map or elimination would show in the 1st to 3rd digit.
/// The global check, 2e-6 of the largest displacement, is the looser summary of the same.
void check_routes_agree(const kerf::CalculixSolution& s, const std::string& what) {
  const double scale = s.static_displacement.cwiseAbs().maxCoeff();
  const double difference = (s.displacement - s.static_displacement).cwiseAbs().maxCoeff();
  double worst = 0.0; // largest difference in units of the allowed per-value error
  for (Eigen::Index i = 0; i < s.static_displacement.size(); ++i) {
    const double printed = std::abs(s.static_displacement(i));
    const double diff = std::abs(s.displacement(i) - s.static_displacement(i));
    // A printed 0 is a constrained DOF (exact in both routes) or a value below 1e-99.
    const double half_unit = printed > 0.0 ? 0.5e-6 * std::pow(10.0, std::floor(std::log10(printed))) : 1e-15 * scale;
    worst = std::max(worst, diff / (half_unit + 1e-9 * scale));
  }
  MESSAGE(what << ": max |u| = " << scale << " m, max |u_matrices - u_static| / max |u| = " << difference / scale
               << ", worst difference / (half unit of 7th digit + 1e-9 max |u|) = " << worst
               << ", ccx wall time static " << s.static_seconds << " s, matrices " << s.matrix_seconds << " s");
  CHECK(scale > 1e-6);
  CHECK(difference <= 2e-6 * scale);
  CHECK(worst <= 1.0);
}

} // namespace

TEST_CASE("CalculiX is installed") {
  const std::string ccx = support::ccx_path();
  CHECK_MESSAGE(std::filesystem::exists(ccx), "ccx was found at configure time but is gone: " << ccx);
}

TEST_CASE("CalculiX: the full-precision matrix route reproduces ccx's static solve (gravity and end load)") {
  const std::string ccx = support::ccx_path();
  for (int order : {1, 2}) {
    const kerf::TetMesh mesh = bar_mesh(order);
    const std::string element = order == 1 ? "C3D4" : "C3D10";
    CAPTURE(element);
    {
      const auto s = kerf::solve_with_calculix(ccx, work_folder(element), "gravity", mesh, bar_job(mesh, true, false));
      check_routes_agree(s, element + " gravity");
    }
    {
      const auto s = kerf::solve_with_calculix(ccx, work_folder(element), "end_load", mesh, bar_job(mesh, false, true));
      check_routes_agree(s, element + " end load");
    }
  }
}

TEST_CASE("CalculiX: a nonzero prescribed displacement is lifted the same way by both routes") {
  const std::string ccx = support::ccx_path();
  for (int order : {1, 2}) {
    const kerf::TetMesh mesh = bar_mesh(order);
    const std::string element = order == 1 ? "C3D4" : "C3D10";
    CAPTURE(element);
    kerf::CalculixJob job = bar_job(mesh, true, false);
    job.dirichlet.push_back({nodes_at_z(mesh, length_z), Eigen::Vector3d(0.002, 0.0, -0.01)}); // pull the end
    const auto s = kerf::solve_with_calculix(ccx, work_folder(element), "stretch", mesh, job);
    check_routes_agree(s, element + " prescribed end");
    for (int v : nodes_at_z(mesh, length_z)) CHECK(s.displacement(v, 2) == -0.01); // exact, not solved for
  }
}

TEST_CASE("CalculiX: the stored K and M are symmetric, annihilate translations and weigh the bar") {
  const std::string ccx = support::ccx_path();
  for (int order : {1, 2}) {
    const kerf::TetMesh mesh = bar_mesh(order);
    const std::string element = order == 1 ? "C3D4" : "C3D10";
    CAPTURE(element);
    kerf::CalculixJob job = bar_job(mesh, false, false);
    job.procedure = kerf::CalculixProcedure::matrix_storage;
    const auto folder = work_folder(element);
    std::filesystem::create_directories(folder);
    kerf::write_calculix_deck(folder / "matrices.inp", mesh, job);
    kerf::run_calculix(ccx, folder, "matrices");
    const auto m = kerf::read_calculix_matrices(folder / "matrices", mesh.num_nodes());

    // Without *BOUNDARY every DOF of every node is an equation.
    REQUIRE(static_cast<Eigen::Index>(m.dof.size()) == 3 * mesh.num_nodes());
    const Eigen::Index n = m.stiffness.rows();
    const double k_scale = m.stiffness.coeffs().cwiseAbs().maxCoeff();
    CHECK((Eigen::SparseMatrix<double>(m.stiffness.transpose()) - m.stiffness).norm() == 0.0);

    // A rigid translation stores no strain energy: K t = 0 to the 14 digits ccx writes.
    for (int p = 0; p < 3; ++p) {
      Eigen::VectorXd t = Eigen::VectorXd::Zero(n);
      for (Eigen::Index r = 0; r < n; ++r)
        if (m.dof[static_cast<std::size_t>(r)] % 3 == p) t[r] = 1.0;
      CHECK((m.stiffness * t).cwiseAbs().maxCoeff() <= 1e-12 * k_scale);
      // t^T M t is the mass of the bar: rho V = 1000 * 0.03 * 0.06 * 0.2 = 0.36 kg.
      CHECK(t.dot(m.mass * t) == kerf_test::relative(0.36, 1e-12));
    }
  }
}

TEST_CASE("CalculiX: a broken deck gives a one-line error naming the log") {
  const std::string ccx = support::ccx_path();
  const auto folder = work_folder("broken");
  std::filesystem::create_directories(folder);
  {
    std::ofstream deck(folder / "broken.inp");
    // A valid one-tet model whose *BOUNDARY names a node set that does not exist.
    deck << "*NODE, NSET=NALL\n1, 0, 0, 0\n2, 1, 0, 0\n3, 0, 1, 0\n4, 0, 0, 1\n"
         << "*ELEMENT, TYPE=C3D4, ELSET=EALL\n1, 1, 2, 3, 4\n*MATERIAL, NAME=M\n*ELASTIC\n1000, 0.3\n"
         << "*SOLID SECTION, ELSET=EALL, MATERIAL=M\n*BOUNDARY\nNOPE, 1, 3\n*STEP\n*STATIC\n*END STEP\n";
  }
  try {
    kerf::run_calculix(ccx, folder, "broken");
    FAIL("run_calculix accepted a deck with an undefined node set");
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    MESSAGE(message);
    CHECK(message.find("broken.ccx.log") != std::string::npos);
    CHECK(message.find("*ERROR reading *BOUNDARY: node set NOPE has not yet been defined.") != std::string::npos);
    CHECK(message.find('\n') == std::string::npos);
  }
}
