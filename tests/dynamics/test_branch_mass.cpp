// Chapter 6's masses with rows for chapter 5's crack-tip (branch) DOFs, on a slab whose cut ends
// in the middle of a row of elements (cut_xfem_mass.hpp, lumped_mass.hpp):
// - the consistent mass weighs the body rho V, is symmetric positive semi-definite, its branch
//   block is positive definite, and a rigid translation of the u's has kinetic energy
//   1/2 rho V |v|^2; its phantom block, integrated by the tets' front and blending rules, is the
//   exact rule's in the blending tets and off by 8e-4 (Tet4) in the front tets;
// - the per-piece lumped masses (a tet with branch functions keeps its consistent mass) keep
//   rho V and the translation's energy, have a positive branch diagonal (the consistent one)
//   and are positive definite; their body force is M "u'' = g";
// - a body with nothing held falls at g with either mass, its branch DOFs staying zero;
// - chapter 6's program steps a beam with a partial cut and "crack_tip" to the end.
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/dynamics/linear_dynamic_system.hpp"
#include "kerf/dynamics/lumped_mass.hpp"
#include "kerf/dynamics/newmark.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/fem/tet_mass.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"
#include "kerf/quadrature/gauss_piece_rules.hpp"
#include "kerf/xfem/cut_xfem_mass.hpp"

#include "dynamics/cut_body.hpp"
#include "support/cut_body.hpp"
#include "support/run_program.hpp"

#include <doctest/doctest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace {

const double rho = 1000.0;
const kerf::LinearMaterial material{1.0e6, 0.3, rho};
const double slab_volume = 0.6 * 0.6 * 0.2; // m^3

// The slab [-0.3, 0.3]^2 x [0, 0.2], 3 x 3 x 1 cells, cut by y = 0, x < 0: the front x = y = 0
// runs through the middle of the central column of cells (as in tests/chapter_05).
support::TipBody slab_body(int order, int front_points = 0) {
  const kerf::TetMesh tet4 = kerf::make_box_mesh({-0.3, -0.3, 0.0}, {0.3, 0.3, 0.2}, {3, 3, 1});
  const kerf::TriangleSurface crack =
      kerf::rectangle_surface(kerf::RectangleCut({-1.0, 0.0, -1.0}, {0.0, 0.0, 2.0}, {1.0, 0.0, 0.0}));
  // The model's default front and blending rules: the ones whose fitness for the mass is checked.
  return support::TipBody(order == 1 ? tet4 : kerf::tet10_from_tet4(tet4), {crack}, material, kerf::TipEnrichmentRule::topological, 0.0,
                          kerf::FrontRule::collapsed, front_points);
}

// The first row of the branch DOFs: after the u's and the a's.
Eigen::Index first_branch_row(const kerf::CutXfemModel& model) {
  return 3 * (model.mesh().num_nodes() + model.enrichment().num_enrichments());
}

// The rigid translation v of the mesh's nodes, every enrichment coefficient (a and b) at 0.
Eigen::VectorXd translation(const kerf::CutXfemModel& model, const Eigen::Vector3d& v) {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * model.num_dof_nodes());
  for (Eigen::Index i = 0; i < model.mesh().num_nodes(); ++i) u.segment<3>(3 * i) = v;
  return u;
}

double smallest_eigenvalue(const Eigen::MatrixXd& A) {
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A, Eigen::EigenvaluesOnly).eigenvalues().minCoeff();
}


// What every lumped mass M with branch rows must do on the slab, whatever the scheme: a rigid
// translation has the kinetic energy of rho V (each piece's diagonal sums to rho V_p, round-off
// as for the consistent mass), M is symmetric, its branch rows and columns are the consistent
// mass M_c's (the design of lumped_mass.hpp), and its body force is M times "every phantom node
// at g" (b'' = 0), with branch rows those of the model's gravity_load, rho int phi_j g.
void check_lumped_branch_mass(const kerf::CutXfemModel& model, const Eigen::MatrixXd& M, const Eigen::MatrixXd& M_c,
                              kerf::LumpingScheme scheme) {
  const Eigen::Index b = first_branch_row(model);
  const Eigen::Vector3d v(0.3, -0.2, 0.5);
  const Eigen::VectorXd u = translation(model, v);
  const double expected = 0.5 * rho * slab_volume * v.squaredNorm();
  CHECK(std::abs(0.5 * u.dot(M * u) - expected) <= 1e-12 * expected);
  CHECK((M - M.transpose()).norm() <= 1e-14 * M.norm());
  CHECK((M.bottomRows(M.rows() - b) - M_c.bottomRows(M.rows() - b)).norm() <= 1e-14 * M_c.norm());
  const Eigen::Vector3d g(0.0, 0.0, -9.81);
  const Eigen::VectorXd f = kerf::lumped_gravity_load(model, rho, g, scheme, support::subtets);
  CHECK((M * translation(model, g) - f).norm() <= 1e-12 * f.norm());
  const Eigen::VectorXd consistent = model.gravity_load(rho, g);
  CHECK((f.tail(f.size() - b) - consistent.tail(f.size() - b)).norm() <= 1e-12 * consistent.norm());
  CHECK(consistent.tail(f.size() - b).norm() > 1e-3 * consistent.norm()); // the branch rows do pull
}

} // namespace

TEST_CASE("the consistent mass with branch rows weighs rho V, is positive semi-definite with a definite branch block") {
  for (const int order : {1, 2}) {
    CAPTURE(order);
    const support::TipBody body = slab_body(order);
    const kerf::CutXfemModel& model = body.model;
    REQUIRE(model.num_branch_nodes() > 0);
    const Eigen::MatrixXd M = Eigen::MatrixXd(kerf::assemble_cut_xfem_mass(model, rho, support::subtets));
    const double mass = rho * slab_volume;
    const Eigen::Vector3d v(0.3, -0.2, 0.5);
    const Eigen::VectorXd u = translation(model, v);
    // The rules' weights sum to the volumes to round-off, and sum_a N_a = 1 at every point: the
    // kinetic energy of the translation is the body's, 1/2 rho V |v|^2 (1e-12 is round-off over
    // thousands of points; the measured error is printed).
    const double kinetic = 0.5 * u.dot(M * u);
    MESSAGE("order " << order << ": kinetic energy of the translation off by " << std::abs(kinetic / (0.5 * mass * v.squaredNorm()) - 1.0));
    CHECK(std::abs(kinetic - 0.5 * mass * v.squaredNorm()) <= 1e-12 * 0.5 * mass * v.squaredNorm());
    // Symmetric by construction (g g^T at every point).
    CHECK((M - M.transpose()).norm() <= 1e-14 * M.norm());
    // Positive semi-definite; the branch block definite: its smallest eigenvalue against its
    // largest (measured 5.2e-4 Tet4, 1.3e-4 Tet10; the whole M's 2.2e-5 and 5.0e-6).
    const double largest = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff();
    const double smallest = smallest_eigenvalue(M);
    const Eigen::Index b = first_branch_row(model);
    const Eigen::MatrixXd M_bb = M.bottomRightCorner(M.rows() - b, M.cols() - b);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> branch(M_bb, Eigen::EigenvaluesOnly);
    MESSAGE("order " << order << ": smallest eigenvalue of M / largest " << smallest / largest << ", of the branch block "
                     << branch.eigenvalues().minCoeff() / branch.eigenvalues().maxCoeff());
    CHECK(smallest >= -1e-12 * largest);
    CHECK(branch.eigenvalues().minCoeff() > 0.0);
    CHECK(M_bb.diagonal().minCoeff() > 0.0);
  }
}

// The largest error of the phantom masses sum_p rho int_p N N^T of the tets with branch
// functions, at the points of the model's rules, against the exact rules, relative to the
// whole tet's mass: over the pieces of the split tets, over the whole blending tets and over the
// whole front tets.
struct PhantomMassError {
  double piece = 0.0, blending = 0.0, front = 0.0;
  int tets = 0;
};
PhantomMassError phantom_mass_error(const support::TipBody& body, int order) {
  const kerf::CutXfemModel& model = body.model;
  const kerf::TetMesh& mesh = body.mesh;
  const int n = mesh.nodes_per_tet();
  PhantomMassError worst;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    if (!model.has_branch_functions(t)) continue;
    ++worst.tets;
    const std::vector<Eigen::MatrixXd> masses = kerf::cut_xfem_piece_masses(model, t, 1.0, support::subtets);
    Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(n, n);
    for (const Eigen::MatrixXd& m : masses) sum += m;
    Eigen::MatrixXd whole;
    if (order == 1) {
      whole = kerf::tet4_mass(kerf::tet_corners(mesh, t), 1.0);
    } else {
      Eigen::Matrix<double, 10, 3> X;
      for (int a = 0; a < 10; ++a) X.row(a) = mesh.nodes.row(mesh.tets(t, a));
      whole = kerf::tet10_mass(X, 1.0);
    }
    const double error = (sum - whole).norm() / whole.norm();
    double& bucket = body.branch.front_tet[static_cast<std::size_t>(t)] != 0 ? worst.front : worst.blending;
    bucket = std::max(bucket, error);
    // Piece by piece where chapter 4 split the tet: against the exact sub-tet rule.
    const int e = body.pieces.entry[static_cast<std::size_t>(t)];
    if (e < 0 || masses.size() < 2) continue;
    for (std::size_t p = 0; p < masses.size(); ++p) {
      const kerf::PieceQuadratureRule r = kerf::subtet_rule(body.pieces.tets[static_cast<std::size_t>(e)], static_cast<int>(p), 2 * order);
      Eigen::MatrixXd exact = Eigen::MatrixXd::Zero(n, n);
      for (std::size_t q = 0; q < r.points.size(); ++q) {
        const Eigen::VectorXd N = model.shape_values(t, r.points[q]);
        exact += r.weights[q] * N * N.transpose();
      }
      worst.piece = std::max(worst.piece, (masses[p] - exact).norm() / whole.norm());
    }
  }
  return worst;
}

TEST_CASE("the front and blending rules integrate the phantom masses of the tets with branch functions") {
  // N_a N_b has degree 2 (Tet4) or 4 (Tet10). The graded Gauss rules of degree 6 of the blending
  // tets are exact for it (measured 2e-14 and 9e-15 relative; 1e-12 is round-off). The front
  // tets' rules, sub-tets collapsed onto the front (exact in r for the stiffness's 1 / r), are
  // not exact for polynomials: measured 7.7e-4 (Tet4, 4 points per direction) and 2.2e-5
  // (Tet10, 6) of the element mass, the split pieces 8.0e-4 and 2.2e-5, a quadrature error that
  // goes with more points (Tet4 with 8 per direction: 1.6e-14, round-off). The body's mass and a
  // translation's energy stay exact (the weights sum to the volumes, sum_a N_a = 1: the
  // consistent-mass test). The bounds are twice to four times the measured errors.
  for (const int order : {1, 2}) {
    CAPTURE(order);
    const PhantomMassError worst = phantom_mass_error(slab_body(order), order);
    MESSAGE("order " << order << ": " << worst.tets << " tets with branch functions; phantom mass against the exact rule: pieces "
                     << worst.piece << ", whole blending tets " << worst.blending << ", whole front tets " << worst.front);
    REQUIRE(worst.tets > 0);
    CHECK(worst.blending <= 1e-12);
    CHECK(worst.front <= (order == 1 ? 2e-3 : 1e-4));
    CHECK(worst.piece <= (order == 1 ? 2e-3 : 1e-4));
  }
  const PhantomMassError finer = phantom_mass_error(slab_body(1, 8), 1);
  MESSAGE("order 1, 8 points per direction: whole front tets " << finer.front << ", pieces " << finer.piece);
  CHECK(finer.front <= 1e-12);
  CHECK(finer.piece <= 1e-12);
}

TEST_CASE("the per-piece lumped masses with branch rows keep rho V, a positive branch diagonal and free fall") {
  struct Case {
    int order;
    kerf::LumpingScheme scheme;
    const char* name;
  };
  // Row sums only on Tet4: a Tet10's corner rows sum to a negative number (lumped_mass.hpp).
  const std::vector<Case> cases{{1, kerf::LumpingScheme::row_sum, "row_sum"},
                                {1, kerf::LumpingScheme::hrz, "hrz"},
                                {1, kerf::LumpingScheme::virtual_tet, "virtual_tet"},
                                {2, kerf::LumpingScheme::hrz, "hrz"},
                                {2, kerf::LumpingScheme::virtual_tet, "virtual_tet"}};
  for (const int order : {1, 2}) {
    const support::TipBody body = slab_body(order);
    const kerf::CutXfemModel& model = body.model;
    const Eigen::MatrixXd M_c = Eigen::MatrixXd(kerf::assemble_cut_xfem_mass(model, rho, support::subtets));
    const Eigen::Index b = first_branch_row(model);
    for (const Case& c : cases) {
      if (c.order != order) continue;
      CAPTURE(order);
      CAPTURE(std::string(c.name));
      const Eigen::MatrixXd M = Eigen::MatrixXd(kerf::lump_cut_xfem_mass(model, rho, c.scheme, support::subtets));
      check_lumped_branch_mass(model, M, M_c, c.scheme);
      // The branch diagonal is the consistent one, positive.
      CHECK(M.diagonal().tail(M.rows() - b).minCoeff() > 0.0);
      // Positive semi-definite by construction (consistent tets with branch functions, lumped
      // others); definite, measured: smallest eigenvalue 2.2e-5 (Tet4) and 5.1e-6 (Tet10) of the
      // largest. Lumping the phantom part of those tets too was indefinite on Tet10 (-0.023 hrz,
      // -0.033 virtual_tet: lumped_mass.hpp).
      const double smallest = smallest_eigenvalue(M);
      const double largest = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff();
      MESSAGE("order " << order << ", " << std::string(c.name) << ": smallest eigenvalue / largest " << smallest / largest);
      CHECK(smallest > 0.0);
    }
  }
}

TEST_CASE("on a Tet4 slab with a crack tip and cheap rules the virtual-tet lumped mass keeps rho V, the consistent branch rows and free fall's load") {
  // The case above on Tet4 with the virtual_tet scheme alone and cheap blending rules (degree 2,
  // depth 1; the front's default rule): what it checks holds for any rules whose weights sum to
  // the volumes, and it runs in 0.03 s instead of 20, so that chapter 6's assignment can grade
  // the tets with branch functions (assignments/06_newmark/grading.txt).
  const kerf::TetMesh tet4 = kerf::make_box_mesh({-0.3, -0.3, 0.0}, {0.3, 0.3, 0.2}, {3, 3, 1});
  const kerf::TriangleSurface crack =
      kerf::rectangle_surface(kerf::RectangleCut({-1.0, 0.0, -1.0}, {0.0, 0.0, 2.0}, {1.0, 0.0, 0.0}));
  const support::TipBody body(tet4, {crack}, material, kerf::TipEnrichmentRule::topological, 0.0, kerf::FrontRule::collapsed, 0, 2, 1);
  const kerf::CutXfemModel& model = body.model;
  const Eigen::Index b = first_branch_row(model);
  REQUIRE(b < 3 * model.num_dof_nodes());
  const Eigen::MatrixXd M_c = Eigen::MatrixXd(kerf::assemble_cut_xfem_mass(model, rho, support::subtets));
  const Eigen::MatrixXd M = Eigen::MatrixXd(kerf::lump_cut_xfem_mass(model, rho, kerf::LumpingScheme::virtual_tet, support::subtets));
  check_lumped_branch_mass(model, M, M_c, kerf::LumpingScheme::virtual_tet);
  // The phantom block is lumped elsewhere: the lumped mass is not the consistent one.
  CHECK((M.topRows(b) - M_c.topRows(b)).norm() > 1e-3 * M_c.norm());
}

TEST_CASE("a slab with a crack tip and nothing held falls at g with Newmark, its enrichment DOFs staying zero") {
  // Gravity and no clamp: the exact solution is u = g t^2 / 2 at every node, a = b = 0, in
  // the discrete equations too (the translation is in K's null space, and M "u'' = g" = f for
  // the consistent mass and the lumped one with branch rows). What is left is the solves'
  // round-off: measured 2.4e-14 (consistent) and 2.2e-14 (virtual_tet) of the drop on the u's,
  // 2.7e-14 and 1.8e-14 on the a's and b's; 1e-9 leaves a wide margin for other orderings.
  const support::TipBody body = slab_body(1);
  const kerf::CutXfemModel& model = body.model;
  const Eigen::Vector3d g(0.0, 0.0, -9.81);
  const double dt = 0.01;
  const int steps = 20;
  for (const bool lumped : {false, true}) {
    CAPTURE(lumped);
    const kerf::DynamicState state = cut_body::newmark_from_rest(
        lumped ? kerf::lump_cut_xfem_mass(model, rho, kerf::LumpingScheme::virtual_tet, support::subtets)
               : kerf::assemble_cut_xfem_mass(model, rho, support::subtets),
        support::full_linear_stiffness(model), kerf::make_cut_xfem_dof_map(model, {}),
        lumped ? kerf::lumped_gravity_load(model, rho, g, kerf::LumpingScheme::virtual_tet, support::subtets) : model.gravity_load(rho, g), dt,
        steps);
    const double drop = 0.5 * g.z() * state.t * state.t;
    const Eigen::VectorXd exact = translation(model, Eigen::Vector3d(0.0, 0.0, drop));
    const Eigen::Index N3 = 3 * model.mesh().num_nodes();
    const double u_error = (state.u.head(N3) - exact.head(N3)).lpNorm<Eigen::Infinity>() / std::abs(drop);
    const double enrichment_error = state.u.tail(state.u.size() - N3).lpNorm<Eigen::Infinity>() / std::abs(drop);
    const Eigen::Index b = first_branch_row(model);
    const double branch_error = state.u.tail(state.u.size() - b).lpNorm<Eigen::Infinity>() / std::abs(drop);
    MESSAGE(std::string(lumped ? "virtual_tet" : "consistent") << ": after " << steps << " steps, nodes off g t^2 / 2 by " << u_error
                                                    << " of the drop, a and b " << enrichment_error << ", b alone " << branch_error);
    CHECK(u_error <= 1e-9);
    CHECK(enrichment_error <= 1e-9);
  }
}

TEST_CASE("chapter 6's program steps a beam with a partial cut and crack-tip functions to the end, its energy balanced") {
  // examples/05_beam_partial_cut_gravity_tet4.json (the cut across half the width, ending inside
  // the beam) on 3 x 3 x 9 cells, topological branch enrichment, 20 undamped steps of the
  // average acceleration rule from rest under gravity. Newmark's energy identity makes
  // kinetic + elastic - work constant for the discrete solution; what is left is the solves'
  // round-off (measured 2.4e-13 and 1.4e-13 of the largest energy, 0.085 and 0.087 J, for
  // lumped and consistent): 1e-9 as in tests/chapter_06/test_answers.cpp.
  const std::string program = std::string(KERF_BINARY_DIR) + "/bin/06_newmark";
  for (const std::string mass : {"lumped", "consistent"}) {
    CAPTURE(mass);
    const auto dir = kerf_test::fresh_dir("dynamics_crack_tip_" + mass);
    kerf_test::write_text(dir / "scene.json", R"({
  "name": "beam_partial_cut_dynamics",
  "mesh": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0.2], "cells": [3, 3, 9]}, "order": 1},
  "material": {"young": 300e3, "poisson": 0.35, "density": 1070},
  "model": "linear",
  "dirichlet": [{"region": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0]}}, "displacement": [0, 0, 0]}],
  "gravity": [9.81, 0, 0],
  "cuts": [{"rectangle": {"origin": [0, 0, 0.1], "edge1": [0.015, 0, 0], "edge2": [0, 0.06, 0]}}],
  "crack_tip": {"enrichment": "branch", "radius": 0},
  "time": {"integrator": "newmark", "dt": 0.005, "steps": 20, "mass": ")" + mass + R"("}
})");
    const auto run = kerf_test::run_program(program + " --scene '" + (dir / "scene.json").string() + "' --out '" + (dir / "out").string() + "'", dir);
    INFO(run.out, run.err);
    REQUIRE(run.exit_status == 0);
    CHECK(run.out.find("crack tip: 0 branch nodes") == std::string::npos);
    CHECK(run.out.find("crack tip: ") != std::string::npos);
    std::string header;
    const auto rows = kerf_test::read_csv_rows(dir / "out" / "energy.csv", header);
    REQUIRE(rows.size() == 21);
    double largest = 0.0, drift = 0.0;
    const auto balance = [](const std::vector<double>& row) { return row[2] + row[3] + row[5] - row[4]; };
    for (const auto& row : rows) {
      for (const double x : row) REQUIRE(std::isfinite(x));
      largest = std::max(largest, row[2] + row[3]);
      drift = std::max(drift, std::abs(balance(row) - balance(rows[0])));
    }
    MESSAGE(mass << ": largest kinetic + elastic " << largest << " J, balance drift " << drift / largest << " of it");
    CHECK(largest > 0.0);
    CHECK(drift <= 1e-9 * largest);
  }
  // Eqs. 81-82 have no branch rows: the program refuses them in one line naming the field.
  const auto dir = kerf_test::fresh_dir("dynamics_crack_tip_schoch");
  kerf_test::write_text(dir / "scene.json", R"({
  "mesh": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0.2], "cells": [3, 3, 9]}, "order": 1},
  "material": {"young": 300e3, "poisson": 0.35, "density": 1070},
  "dirichlet": [{"region": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0]}}, "displacement": [0, 0, 0]}],
  "cuts": [{"rectangle": {"origin": [0, 0, 0.1], "edge1": [0.015, 0, 0], "edge2": [0, 0.06, 0]}}],
  "crack_tip": {"enrichment": "branch", "radius": 0},
  "time": {"integrator": "newmark", "dt": 0.005, "steps": 2, "mass": "schoch_eq_81_82"}
})");
  const auto refused = kerf_test::run_program(program + " --quiet --scene '" + (dir / "scene.json").string() + "' --out '" + (dir / "out").string() + "'", dir);
  CHECK(refused.exit_status != 0);
  CHECK(refused.err.find("time.mass") != std::string::npos);
  CHECK(refused.err.find("crack-tip") != std::string::npos);
}
