// The lowest natural frequencies of chapter 1's clamped Tet10 beam (0.03 x 0.06 x 0.2 m,
// E = 300 kPa, nu = 0.35, rho = 1070 kg/m^3, clamped at z = 0; coarse: 1 x 2 x 6 cells) by
// Kerf's shift-invert subspace iteration (dynamics/eigen_modes.hpp), against CalculiX's own
// *FREQUENCY (ARPACK) on the same mesh.
//
// What we found on the way, and what the test therefore asserts: CalculiX's K is Kerf's (the
// matrix route's 14 digits agree), but its C3D10 mass is integrated with the 4-point rule of
// the stiffness (degree 2; N_a N_b has degree 4), while Kerf's is exact. So (1) Kerf's solver on
// CalculiX's own K and M gives CalculiX's eigenvalues to the 7 digits ccx prints; (2) Kerf's K
// with the 4-point mass gives them too; (3) with Kerf's exact mass the eigenvalues are lower,
// by 1.5e-5 (mode 1) to 7e-3 (mode 10) relative: a difference of the mass rule, not of the solver.
#include "dynamics/cut_body.hpp"
#include "kerf/dynamics/eigen_modes.hpp"
#include "kerf/dynamics/linear_dynamic_system.hpp"
#include "kerf/fem/tet_quadrature.hpp"
#include "kerf/fem/tet_shape_functions.hpp"
#include "kerf/io/calculix_deck.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"
#include "kerf/xfem/cut_xfem_mass.hpp"

#include "support/calculix_path.hpp"

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace {

const kerf::LinearMaterial beam_material{300e3, 0.35, 1070.0};
const int count = 10;

std::vector<int> clamped_nodes(const kerf::TetMesh& mesh) {
  std::vector<int> nodes;
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v)
    if (mesh.nodes(v, 2) == 0.0) nodes.push_back(static_cast<int>(v));
  return nodes;
}

// The free-free block of a matrix over all 3#V DOFs, given as (row DOF, column DOF, value).
template <class Entries>
Eigen::SparseMatrix<double> free_block(const kerf::DofMap& dofs, const Entries& entries_of) {
  std::vector<Eigen::Triplet<double>> entries;
  entries_of([&](Eigen::Index row_dof, Eigen::Index col_dof, double value) {
    const int i = dofs.free_index[static_cast<std::size_t>(row_dof)], j = dofs.free_index[static_cast<std::size_t>(col_dof)];
    if (i >= 0 && j >= 0) entries.emplace_back(i, j, value);
  });
  Eigen::SparseMatrix<double> A(dofs.num_free, dofs.num_free);
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

// The Tet10 mass integrated with the reference rule of degree `degree` (straight edges: det J = 6 V).
Eigen::SparseMatrix<double> tet10_mass_with_rule(const kerf::TetMesh& mesh, double rho, int degree, const kerf::DofMap& dofs) {
  const kerf::TetQuadratureRule rule = kerf::tet_quadrature_rule(degree);
  return free_block(dofs, [&](const auto& add) {
    for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
      const Eigen::Matrix<double, 4, 3> X = kerf::tet_corners(mesh, t);
      Eigen::Matrix3d J;
      for (int a = 0; a < 3; ++a) J.col(a) = (X.row(a + 1) - X.row(0)).transpose();
      Eigen::Matrix<double, 10, 10> m = Eigen::Matrix<double, 10, 10>::Zero();
      for (std::size_t q = 0; q < rule.points.size(); ++q) {
        const Eigen::Matrix<double, 10, 1> N = kerf::tet10_shape(rule.points[q]);
        m += rule.weights[q] * J.determinant() * rho * N * N.transpose();
      }
      for (int a = 0; a < 10; ++a)
        for (int b = 0; b < 10; ++b)
          for (int p = 0; p < 3; ++p) add(3 * mesh.tets(t, a) + p, 3 * mesh.tets(t, b) + p, m(a, b));
    }
  });
}

double relative_difference(const Eigen::SparseMatrix<double>& A, const Eigen::SparseMatrix<double>& B) {
  return (Eigen::MatrixXd(A) - Eigen::MatrixXd(B)).norm() / Eigen::MatrixXd(B).norm();
}

} // namespace

TEST_CASE("the clamped Tet10 beam's ten lowest eigenvalues: Kerf's subspace iteration against CalculiX *FREQUENCY") {
  const std::string ccx = support::ccx_path();
  const kerf::TetMesh mesh = kerf::tet10_from_tet4(kerf::make_box_mesh({0, 0, 0}, {0.03, 0.06, 0.2}, {1, 2, 6}));
  const cut_body::CutBody body(mesh, {}, beam_material);
  kerf::LinearDynamicSystem system;
  system.M = kerf::assemble_cut_xfem_mass(body.model, beam_material.density, cut_body::subtets);
  system.K = body.stiffness();
  system.C = Eigen::SparseMatrix<double>(system.M.rows(), system.M.cols());
  system.dofs = kerf::make_dof_map(mesh.num_nodes(), {{clamped_nodes(mesh), Eigen::Vector3d::Zero()}});
  const kerf::ReducedDynamicSystem reduced(system);

  // CalculiX: its eigenvalues (*FREQUENCY, 7 digits) and its K and M (matrix route, 14 digits).
  const std::filesystem::path folder = std::filesystem::path(KERF_BINARY_DIR) / "tests" / "calculix" / "eigen_modes";
  std::filesystem::create_directories(folder);
  kerf::CalculixJob job;
  job.material = beam_material;
  job.dirichlet = {{clamped_nodes(mesh), Eigen::Vector3d::Zero()}};
  job.procedure = kerf::CalculixProcedure::frequency;
  job.frequencies = count;
  kerf::write_calculix_deck(folder / "beam_frequency.inp", mesh, job);
  kerf::run_calculix(ccx, folder, "beam_frequency");
  const std::vector<double> ccx_lambda = kerf::read_calculix_eigenvalues(folder / "beam_frequency.dat");
  REQUIRE(ccx_lambda.size() == static_cast<std::size_t>(count));
  job.procedure = kerf::CalculixProcedure::matrix_storage;
  kerf::write_calculix_deck(folder / "beam_matrices.inp", mesh, job);
  kerf::run_calculix(ccx, folder, "beam_matrices");
  const kerf::CalculixMatrices ccx_matrices = kerf::read_calculix_matrices(folder / "beam_matrices", mesh.num_nodes());
  const auto ccx_free = [&](const Eigen::SparseMatrix<double>& A) {
    return free_block(system.dofs, [&](const auto& add) {
      for (Eigen::Index c = 0; c < A.outerSize(); ++c)
        for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it)
          add(ccx_matrices.dof[static_cast<std::size_t>(it.row())], ccx_matrices.dof[static_cast<std::size_t>(it.col())], it.value());
    });
  };
  const Eigen::SparseMatrix<double> K_ccx = ccx_free(ccx_matrices.stiffness), M_ccx = ccx_free(ccx_matrices.mass);

  // ccx prints 1p,e13.6-style 7 significant digits (0.1234567E+03): half a unit of the 7th digit
  // is at most 5e-7 relative; ARPACK's converged Ritz values are closer than that (measured
  // 3.7e-7 at most), so 1e-6 is the print precision with a factor 2 of margin.
  const double printed = 1e-6;
  SUBCASE("Kerf's solver on CalculiX's K and M: CalculiX's eigenvalues to the printed digits") {
    const kerf::EigenModes modes = kerf::lowest_eigenmodes(K_ccx, M_ccx, count);
    REQUIRE(modes.converged);
    for (int k = 0; k < count; ++k) CHECK(std::abs(modes.lambda[k] - ccx_lambda[k]) <= printed * ccx_lambda[k]);
  }
  SUBCASE("CalculiX's K is Kerf's, its M the 4-point-rule mass; with that mass Kerf's K gives CalculiX's eigenvalues") {
    // The .sti and .mas hold 14 significant digits: 1e-12 relative in the Frobenius norm.
    CHECK(relative_difference(K_ccx, reduced.K_ff()) < 1e-12);
    const Eigen::SparseMatrix<double> M_4point = tet10_mass_with_rule(mesh, beam_material.density, 2, system.dofs);
    CHECK(relative_difference(M_ccx, M_4point) < 1e-12);
    // Kerf's exact mass is the degree-4 rule's, and it is not the 4-point one (25 % in the norm).
    CHECK(relative_difference(reduced.M_ff(), tet10_mass_with_rule(mesh, beam_material.density, 4, system.dofs)) < 1e-12);
    CHECK(relative_difference(reduced.M_ff(), M_4point) > 0.1);
    const kerf::EigenModes modes = kerf::lowest_eigenmodes(reduced.K_ff(), M_4point, count);
    REQUIRE(modes.converged);
    for (int k = 0; k < count; ++k) CHECK(std::abs(modes.lambda[k] - ccx_lambda[k]) <= printed * ccx_lambda[k]);
  }
  SUBCASE("with Kerf's exact mass: M-orthonormal eigenpairs, lower than CalculiX's, mode 1 within 2e-5") {
    const kerf::EigenModes modes = kerf::lowest_eigenmodes(reduced.K_ff(), reduced.M_ff(), count);
    REQUIRE(modes.converged);
    const Eigen::MatrixXd MtM = modes.phi.transpose() * (reduced.M_ff() * modes.phi);
    // Rayleigh-Ritz makes the block M-orthonormal to round-off of a 10 x 10 Cholesky.
    CHECK((MtM - Eigen::MatrixXd::Identity(count, count)).cwiseAbs().maxCoeff() < 1e-10);
    for (int k = 0; k < count; ++k) {
      INFO("mode " << k + 1 << ": Kerf " << modes.lambda[k] << " 1/s^2, CalculiX " << ccx_lambda[k] << ", relative "
                      << (ccx_lambda[k] - modes.lambda[k]) / ccx_lambda[k]);
      // An eigenvalue converged to 1e-12 has an eigenvector error of about sqrt(1e-12) = 1e-6
      // (the residual goes with the vector's error, the value with its square): 1e-5 relative.
      const Eigen::VectorXd Kphi = reduced.K_ff() * modes.phi.col(k);
      CHECK((Kphi - modes.lambda[k] * (reduced.M_ff() * modes.phi.col(k))).norm() < 1e-5 * Kphi.norm());
      // The 4-point mass misses part of the mass's high-degree content; here it raises every
      // eigenvalue (measured: 1.5e-5 for mode 1 up to 6.8e-3 for mode 10).
      CHECK(modes.lambda[k] < ccx_lambda[k]);
    }
    CHECK((ccx_lambda[0] - modes.lambda[0]) / ccx_lambda[0] < 2e-5);
  }
}

TEST_CASE("the frequency deck refuses loads and a missing density; a .dat without eigenvalues is an error naming the file") {
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {1, 1, 1});
  const std::filesystem::path folder = std::filesystem::path(KERF_BINARY_DIR) / "tests" / "calculix" / "eigen_modes_input";
  std::filesystem::create_directories(folder);
  kerf::CalculixJob job;
  job.material = beam_material;
  job.procedure = kerf::CalculixProcedure::frequency;
  job.gravity = Eigen::Vector3d(0, 0, -9.81);
  CHECK_THROWS_AS(kerf::write_calculix_deck(folder / "loaded.inp", mesh, job), std::invalid_argument);
  job.gravity.setZero();
  job.material.density = 0.0;
  CHECK_THROWS_AS(kerf::write_calculix_deck(folder / "massless.inp", mesh, job), std::invalid_argument);
  const std::filesystem::path dat = folder / "no_eigenvalues.dat";
  std::ofstream(dat) << " displacements (vx,vy,vz) for set NALL and time  0.1000000E+01\n\n  1  0.0  0.0  0.0\n";
  try {
    kerf::read_calculix_eigenvalues(dat);
    FAIL("read_calculix_eigenvalues accepted a file without an eigenvalue block");
  } catch (const std::runtime_error& error) {
    CHECK(std::string(error.what()).find(dat.string()) != std::string::npos);
  }
}
