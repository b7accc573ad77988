// Where the corotational solve used to depend on luck: which solver noticed an indefinite
// tangent, where the mesh sits, whether a Higham failure rescued by the SVD was counted, a
// singular tr(S) I - S in the consistent tangent, and what the Newton history says at the start
// of a step driven by a moving support. And the material and load checks that keep inf out.
#include "kerf/app/input_error.hpp"
#include "kerf/corotation/corotational_model.hpp"
#include "kerf/corotation/quasi_static_solver.hpp"
#include "kerf/fem/assemble_loads.hpp"
#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/node_region.hpp"
#include "kerf/scene/scene.hpp"
#include "kerf/scene/scene_mesh.hpp"
#include "kerf/solve/linear_solver.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <Eigen/SparseCore>
#include <sstream>
#include <string>

namespace {

// A small symmetric indefinite matrix with a positive diagonal: [[2, 3], [3, 2]] has the
// eigenvalues 5 and -1. A solver for SPD matrices must refuse it.
Eigen::SparseMatrix<double> indefinite_2x2() {
  Eigen::SparseMatrix<double> A(2, 2);
  A.insert(0, 0) = 2.0;
  A.insert(0, 1) = 3.0;
  A.insert(1, 0) = 3.0;
  A.insert(1, 1) = 2.0;
  A.makeCompressed();
  return A;
}

int fallbacks(const kerf::QuasiStaticResult& result) {
  int count = 0;
  for (const kerf::NewtonIteration& it : result.history) count += it.warped_fallback;
  return count;
}

} // namespace

TEST_CASE("every solver refuses an indefinite matrix: LDLT by its pivots, CG by the curvature b . x") {
  const Eigen::SparseMatrix<double> A = indefinite_2x2();
  // b along the eigenvector (1, -1) of the eigenvalue -1: x = -b, so b . x = -|b|^2 < 0.
  const Eigen::VectorXd b = Eigen::Vector2d(1.0, -1.0);
  for (const std::string type : {"cholmod", "ldlt", "cg-jacobi", "cg-ichol"}) {
    CAPTURE(type);
    auto solver = kerf::make_linear_solver({type});
    solver->analyze_pattern(A);
    bool refused = false;
    try {
      solver->factorize(A);
      Eigen::VectorXd x = Eigen::VectorXd::Zero(2);
      solver->solve(b, x);
    } catch (const kerf::NotPositiveDefinite&) {
      refused = true;
    } catch (const std::runtime_error&) {
      refused = true; // CG may also fail to converge; the fallback treats both alike
    }
    CHECK(refused);
  }
  // An infinite right-hand side is named as such, not as an indefinite matrix.
  Eigen::SparseMatrix<double> I(2, 2);
  I.setIdentity();
  auto solver = kerf::make_linear_solver({"ldlt"});
  solver->analyze_pattern(I);
  solver->factorize(I);
  Eigen::VectorXd x;
  CHECK_THROWS_AS(solver->solve(Eigen::Vector2d(1.0, std::numeric_limits<double>::infinity()), x), std::invalid_argument);
}

// A body of one DOF node whose internal force is f_int = K_w u (so the warped tangent K_w is
// exact) but whose "consistent" tangent is indefinite: what a strongly compressed corotated mesh
// does to Newton, reduced to three numbers. The quasi-static solver must notice with every
// solver and take the warped tangent; if it does not (Eigen's LDLT factorises the indefinite
// matrix happily), Newton walks uphill along the third component and never converges.
class IndefiniteTangentModel final : public kerf::QuasiStaticModel {
public:
  IndefiniteTangentModel() : slots_(1, 1) { slots_(0, 0) = 0; }
  Eigen::Index num_dof_nodes() const override { return 1; }
  const kerf::TetMatrix& assembly_slots() const override { return slots_; }
  double position_force_norm() const override { return 0.0; }
  kerf::CorotationStatistics assemble(const Eigen::VectorXd& u, kerf::RotationMethod, kerf::CorotationalTangent tangent,
                                      Eigen::VectorXd& f_int, kerf::SparseAssembler* assembler, Eigen::VectorXd* rhs_free) const override {
    const Eigen::Matrix3d K_w = Eigen::Vector3d(1.0, 2.0, 3.0).asDiagonal();
    const Eigen::Matrix3d K_c = Eigen::Vector3d(1.0, 2.0, -3.0).asDiagonal();
    f_int = K_w * u;
    if (assembler) assembler->add_element<3>(0, tangent == kerf::CorotationalTangent::warped ? K_w : K_c, *rhs_free);
    return {};
  }

private:
  kerf::TetMatrix slots_;
};

TEST_CASE("the warped-tangent fallback works with every solver when the consistent tangent is indefinite") {
  const IndefiniteTangentModel model;
  const Eigen::Vector3d f_ext(1.0, 1.0, 1.0);
  for (const std::string type : {"cholmod", "ldlt", "cg-jacobi", "cg-ichol"}) {
    CAPTURE(type);
    kerf::QuasiStaticSettings settings;
    settings.load_steps = 2;
    settings.solver.type = type;
    kerf::QuasiStaticResult result;
    REQUIRE_NOTHROW(result = kerf::solve_quasi_static(model, kerf::make_dof_map(1, {}), f_ext, settings));
    CHECK(result.converged);
    CHECK(fallbacks(result) == result.total_iterations); // every solve needed the warped tangent
    // K_w u = f_ext: u = (1, 1/2, 1/3), to the solver's precision (CG: 1e-10 relative).
    CHECK((result.u - Eigen::Vector3d(1.0, 0.5, 1.0 / 3.0)).cwiseAbs().maxCoeff() <= 1e-9);
  }
}

TEST_CASE("a beam 1000 m from the origin converges in as many Newton iterations as at the origin") {
  const auto solve_at = [](const Eigen::Vector3d& offset) {
    const kerf::TetMesh mesh = kerf::make_box_mesh(offset, offset + Eigen::Vector3d(0.03, 0.06, 0.2), {2, 3, 10});
    kerf::NodeRegion clamp;
    clamp.box_min = offset;
    clamp.box_max = offset + Eigen::Vector3d(0.03, 0.06, 0.0);
    const kerf::DofMap dofs = kerf::make_dof_map(mesh.num_nodes(), {{kerf::nodes_in_region(mesh, clamp), {0, 0, 0}}});
    const kerf::LinearMaterial material;
    const kerf::CorotationalModel model(mesh, material);
    kerf::QuasiStaticSettings settings;
    settings.load_steps = 2;
    return kerf::solve_quasi_static(model, dofs, kerf::assemble_gravity(mesh, material.density, {9.81, 0, 0}), settings);
  };
  const kerf::QuasiStaticResult here = solve_at(Eigen::Vector3d::Zero());
  const kerf::QuasiStaticResult far = solve_at(Eigen::Vector3d::Constant(1000.0));
  MESSAGE("Newton iterations: " << here.total_iterations << " at the origin, " << far.total_iterations << " at 1000 m");
  CHECK(here.converged);
  CHECK(far.converged); // before: the residual stalled at 1.2e-9 and it took 48 iterations
  CHECK(far.total_iterations == here.total_iterations);
  // The answer is the same displacement field: the shift costs only eps |X| in the positions.
  CHECK((far.u - here.u).cwiseAbs().maxCoeff() <= 1e-9 * here.u.cwiseAbs().maxCoeff());
}

TEST_CASE("corotation statistics: the automatic mode counts the Higham failures the SVD rescued") {
  const Eigen::Matrix3d inverted = Eigen::Vector3d(1.0, 1.0, -0.5).asDiagonal();
  const kerf::PolarDecomposition automatic = kerf::element_rotation(inverted, kerf::RotationMethod::automatic);
  CHECK(automatic.R.determinant() == kerf_test::relative(1.0)); // the SVD's rotation stands in
  kerf::CorotationStatistics stats;
  stats.record(automatic, inverted, 2.0);
  stats.record(kerf::element_rotation(Eigen::Matrix3d::Identity(), kerf::RotationMethod::automatic), Eigen::Matrix3d::Identity(), 1.0);
  stats.record(kerf::element_rotation(inverted, kerf::RotationMethod::svd), inverted, 0.5);
  CHECK(stats.higham_failures == 1); // before: 0, the SVD's result hid the failure
  CHECK(stats.inverted_points == 2);
  CHECK(stats.inverted_volume == kerf_test::relative(2.5));
}

TEST_CASE("the consistent tangent drops dR/dx where tr(S) I - S is singular, and stays finite") {
  // F = diag(1, 1, -1): the SVD rotation leaves the stretch diag(1, 1, -1), and tr(S) I - S =
  // diag(0, 0, 2) is singular (the pair 1 + (-1) cancels).
  Eigen::Matrix<double, 4, 3> X;
  X << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  Eigen::Matrix<double, 4, 3> u = Eigen::Matrix<double, 4, 3>::Zero();
  u(3, 2) = -2.0; // the top corner pushed through the base: z -> -z
  kerf::TetMesh tet;
  tet.nodes = X;
  tet.tets.resize(1, 4);
  tet.tets << 0, 1, 2, 3;
  const kerf::LinearMaterial material;
  const kerf::CorotationalModel model(tet, material);
  Eigen::VectorXd u_flat(12);
  for (int a = 0; a < 4; ++a) u_flat.segment<3>(3 * a) = u.row(a).transpose();
  const kerf::DofMap dofs = kerf::make_dof_map(4, {});
  kerf::SparseAssembler assembler(tet.tets, dofs);
  Eigen::VectorXd f_int, rhs = Eigen::VectorXd::Zero(12);
  const kerf::CorotationStatistics stats =
      model.assemble(u_flat, kerf::RotationMethod::svd, kerf::CorotationalTangent::consistent, f_int, &assembler, &rhs);
  CHECK(stats.dropped_rotation_terms == 1);
  CHECK(stats.inverted_points == 1);
  CHECK(f_int.allFinite());
  CHECK(Eigen::MatrixXd(assembler.matrix()).allFinite()); // before: inf and NaN from the inverse
}

TEST_CASE("the Newton history's iteration 0 shows how far a step driven by a support starts from equilibrium") {
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {0.03, 0.06, 0.2}, {2, 3, 8});
  kerf::NodeRegion clamp, top;
  clamp.box_max = Eigen::Vector3d(0.03, 0.06, 0.0);
  top.box_min = Eigen::Vector3d(0, 0, 0.2);
  top.box_max = Eigen::Vector3d(0.03, 0.06, 0.2);
  const kerf::DofMap dofs = kerf::make_dof_map(
      mesh.num_nodes(), {{kerf::nodes_in_region(mesh, clamp), {0, 0, 0}}, {kerf::nodes_in_region(mesh, top), {0.02, 0, 0}}});
  const kerf::CorotationalModel model(mesh, kerf::LinearMaterial{});
  kerf::QuasiStaticSettings settings;
  settings.load_steps = 2;
  const kerf::QuasiStaticResult result = kerf::solve_quasi_static(model, dofs, Eigen::VectorXd::Zero(3 * mesh.num_nodes()), settings);
  CHECK(result.converged);
  for (const kerf::NewtonIteration& it : result.history) {
    CAPTURE(it.step);
    CAPTURE(it.iteration);
    // No load but the moving face: the step starts out of equilibrium by K_fc du_c, which
    // is the whole force scale of that step (before: recorded as 0).
    if (it.iteration == 0) CHECK(it.relative_residual > 0.1);
  }
  CHECK(result.history.back().relative_residual <= settings.tolerance);
}

TEST_CASE("materials and loads that would put inf into the system are refused by name") {
  CHECK_THROWS_AS(kerf::LinearMaterial({300e3, 0.5, 1000}).lambda(), std::invalid_argument);
  CHECK_THROWS_AS(kerf::LinearMaterial({-1.0, 0.3, 1000}).mu(), std::invalid_argument);
  CHECK_THROWS_AS(kerf::LinearMaterial({300e3, 0.3, std::numeric_limits<double>::infinity()}).check(), std::invalid_argument);
  CHECK_NOTHROW(kerf::LinearMaterial({300e3, 0.4999, 1000}).lambda());

  const auto scene_with = [](const std::string& material, const std::string& gravity) {
    return R"({"mesh": {"box": {"min": [0,0,0], "max": [0.03,0.06,0.2], "cells": [1,1,2]}, "order": 1},
               "material": )" + material + R"(, "gravity": )" + gravity + R"(,
               "dirichlet": [{"region": {"box": {"min": [0,0,0], "max": [0.03,0.06,0]}}}]})";
  };
  const auto error_of = [](const std::function<void()>& run) {
    try {
      run();
    } catch (const kerf::InputError& error) {
      return std::string(error.what());
    }
    return std::string();
  };
  // Within 1e-6 of 0.5: refused, naming the field.
  const std::string near_half = error_of([&] { kerf::parse_scene(scene_with(R"({"poisson": 0.4999999999})", "[0,0,0]"), "s.json", "."); });
  CHECK(near_half.find("s.json") != std::string::npos);
  CHECK(near_half.find("material.poisson") != std::string::npos);
  // Above 0.45 with Tet4: accepted, with a warning that points at chapter 1's locking study.
  const kerf::Scene locking = kerf::parse_scene(scene_with(R"({"poisson": 0.46})", "[0,0,0]"), "s.json", ".");
  std::ostringstream warnings;
  kerf::make_scene_mesh(locking, &warnings);
  CHECK(warnings.str().find("material.poisson") != std::string::npos);
  CHECK(warnings.str().find("locking study") != std::string::npos);
  // Finite numbers whose product is not: the body force names "gravity".
  const kerf::Scene huge = kerf::parse_scene(scene_with(R"({"density": 1e10})", "[1e307, 1e307, 0]"), "s.json", ".");
  const kerf::TetMesh mesh = kerf::make_scene_mesh(huge, nullptr);
  const std::string overflow = error_of([&] { kerf::scene_external_loads(huge, mesh, kerf::boundary_faces(mesh)); });
  CHECK(overflow.find("gravity") != std::string::npos);
  CHECK(overflow.find("not finite") != std::string::npos);
}
