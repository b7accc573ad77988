// CG preconditioned by an earlier CHOLMOD factor: right answers for matrices that drift away
// from the factored one, a factorisation only when the old one stops paying, and an
// indefinite matrix reported.
#include "kerf/fem/assemble_loads.hpp"
#include "kerf/fem/assemble_stiffness.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/node_region.hpp"
#include "kerf/solve/reused_factorisation_cg.hpp"

#include <doctest/doctest.h>

#include <Eigen/SparseCholesky>

namespace {

/// The clamped Tet4 beam's K_ff for Young's modulus E, and its gravity load.
struct Beam {
  Eigen::SparseMatrix<double> K;
  Eigen::VectorXd f;
};

Beam beam(double young) {
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {0.03, 0.06, 0.2}, {3, 4, 12});
  kerf::NodeRegion bottom;
  bottom.box_max = {0.03, 0.06, 0.0};
  const kerf::DofMap dofs = kerf::make_dof_map(mesh.num_nodes(), {{kerf::nodes_in_region(mesh, bottom), {0, 0, 0}}});
  kerf::SparseAssembler assembler(mesh.tets, dofs);
  Beam b;
  b.f = dofs.restrict_to_free(kerf::assemble_gravity(mesh, 1070, {9.81, 0, 0}));
  kerf::assemble_linear_stiffness(mesh, kerf::LinearMaterial{young, 0.35, 1070}, assembler, b.f);
  b.K = assembler.matrix();
  return b;
}

/// K + s K_half, with K_half the stiffness of the beam's lower half (z < 0.1): a matrix that
/// moves away from K as s grows, the way a tangent changes where a body deforms, and stays
/// positive definite. The eigenvalues of K^{-1} A lie in [1, 1 + s].
Eigen::SparseMatrix<double> perturbed(double s) {
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {0.03, 0.06, 0.2}, {3, 4, 12});
  kerf::NodeRegion bottom;
  bottom.box_max = {0.03, 0.06, 0.0};
  const kerf::DofMap dofs = kerf::make_dof_map(mesh.num_nodes(), {{kerf::nodes_in_region(mesh, bottom), {0, 0, 0}}});
  kerf::TetMesh lower = mesh;
  std::vector<Eigen::Index> kept;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    if (mesh.nodes(mesh.tets(t, 0), 2) + mesh.nodes(mesh.tets(t, 1), 2) + mesh.nodes(mesh.tets(t, 2), 2) +
            mesh.nodes(mesh.tets(t, 3), 2) < 0.4)
      kept.push_back(t);
  lower.tets = mesh.tets(kept, Eigen::all);
  kerf::SparseAssembler whole(mesh.tets, dofs), half(lower.tets, dofs);
  Eigen::VectorXd unused = Eigen::VectorXd::Zero(dofs.num_free);
  kerf::assemble_linear_stiffness(mesh, kerf::LinearMaterial{300e3, 0.35, 1070}, whole, unused);
  kerf::assemble_linear_stiffness(lower, kerf::LinearMaterial{300e3, 0.35, 1070}, half, unused);
  return whole.matrix() + s * half.matrix();
}

} // namespace

TEST_CASE("cg-cholmod solves a drifting sequence to its tolerance and refactorises only when needed") {
  const Beam b = beam(300e3);
  kerf::ReusedFactorisationCg solver(1e-10, 10);
  solver.analyze_pattern(b.K);
  Eigen::VectorXd x;

  // The first matrix is factorised and solved directly: one "iteration".
  solver.factorize(b.K);
  solver.solve(b.f, x);
  CHECK(solver.factorisations() == 1);
  CHECK(solver.iterations() == 1);
  CHECK((b.K * x - b.f).norm() <= 1e-10 * b.f.norm());

  // A nearby matrix reuses the factor: a few PCG iterations, no new factorisation, and the
  // residual of the new system below the tolerance.
  const Eigen::SparseMatrix<double> near = perturbed(0.01);
  solver.factorize(near);
  solver.solve(b.f, x);
  CHECK(solver.factorisations() == 1);
  CHECK(solver.iterations() >= 2);
  CHECK(solver.iterations() <= 10);
  CHECK((near * x - b.f).norm() <= 1e-10 * b.f.norm());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(near);
  const Eigen::VectorXd exact = ldlt.solve(b.f);
  // |x - exact| <= cond(A) |r| / |A|-ish; with cond ~ 1e5 and the 1e-10 residual, 1e-5 is safe.
  CHECK((x - exact).norm() <= 1e-5 * exact.norm());

  // A matrix far from the factored one: CG needs more than 10 iterations, so it either
  // refactorises at once (20 iterations spent) or asks for a fresh factor at the next call.
  const Eigen::SparseMatrix<double> far = perturbed(100.0);
  solver.factorize(far);
  x.setZero();
  solver.solve(b.f, x);
  CHECK(solver.iterations() > 10);
  CHECK((far * x - b.f).norm() <= 1e-10 * b.f.norm());
  const int after_far = solver.factorisations();
  CHECK(after_far <= 2);
  // Whatever happened, the next factorize() works from a fresh factor of the matrix it gets.
  solver.factorize(far);
  solver.solve(b.f, x);
  CHECK(solver.factorisations() == 2);
  CHECK(solver.iterations() <= 2);
  CHECK((far * x - b.f).norm() <= 1e-10 * b.f.norm());
}

TEST_CASE("cg-cholmod reports an indefinite matrix and refuses misuse") {
  const Beam b = beam(300e3);
  kerf::ReusedFactorisationCg solver(1e-10, 10);
  solver.analyze_pattern(b.K);
  Eigen::VectorXd x;
  CHECK_THROWS_AS(solver.solve(b.f, x), std::logic_error); // nothing factorised yet
  solver.factorize(b.K);
  // -K with the factor of K: the first search direction has p^T A p < 0.
  const Eigen::SparseMatrix<double> negative = -b.K;
  solver.factorize(negative);
  x.setZero();
  CHECK_THROWS_AS(solver.solve(b.f, x), kerf::NotPositiveDefinite);
  CHECK_THROWS_AS(solver.solve(Eigen::VectorXd::Constant(b.f.size(), std::nan("")), x), std::invalid_argument);
  CHECK_THROWS_AS(solver.solve(Eigen::VectorXd::Ones(3), x), std::invalid_argument);
  CHECK_THROWS_AS(kerf::ReusedFactorisationCg(0.0), std::invalid_argument);
  CHECK_THROWS_AS(kerf::ReusedFactorisationCg(1e-8, 0), std::invalid_argument);
}
