#include "kerf/dynamics/newton_matrix_conditioning.hpp"

#include "kerf/dynamics/bilateral_preconditioner.hpp"
#include "kerf/dynamics/linear_dynamic_system.hpp"
#include "kerf/dynamics/part_basis.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/xfem/cut_xfem_mass.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <limits>
#include <vector>

namespace kerf {

double spectral_condition_number(const Eigen::MatrixXd& A) {
  const Eigen::VectorXd lambda = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A, Eigen::EigenvaluesOnly).eigenvalues();
  if (!(lambda.minCoeff() > 0.0)) return std::numeric_limits<double>::infinity();
  return lambda.maxCoeff() / lambda.minCoeff();
}

namespace {

// A = M + dt^2 K restricted to the free DOFs of `dofs`, and T and P restricted alike.
struct FreeNewtonMatrix {
  Eigen::SparseMatrix<double> A;
  Eigen::VectorXd koschier_t;
  Eigen::SparseMatrix<double> part_basis; // P_ff: a constrained enrichment's w_k is its node's w_i
};

FreeNewtonMatrix free_newton_matrix(const LinearDynamicSystem& full, const DofMap& dofs, double dt,
                                    const Eigen::VectorXd& koschier_t, const CutXfemModel& model) {
  LinearDynamicSystem system = full;
  system.dofs = dofs;
  const ReducedDynamicSystem reduced(system);
  return {reduced.M_ff() + dt * dt * reduced.K_ff(), dofs.restrict_to_free(koschier_t),
          free_part_basis(model.enrichment(), model.mesh().num_nodes(), dofs)};
}

// kappa of S^T A S with S = P T, T the Jacobi scaling of P^T A P. P^T A P is formed from A, so
// the diagonal of a part much thinner than round-off of A's entries (relative volume below
// ~1e-16) is a difference of O(1) numbers and may come out non-positive: infinity then, as for
// any numerically singular matrix (assembling on the parts directly would avoid it).
double part_jacobi_condition(const FreeNewtonMatrix& m) {
  const Eigen::SparseMatrix<double> B = m.part_basis.transpose() * m.A * m.part_basis;
  if (!(B.diagonal().minCoeff() > 0.0)) return std::numeric_limits<double>::infinity();
  return spectral_condition_number(Eigen::MatrixXd(scale_bilaterally(B, jacobi_preconditioner(B))));
}

double condition(const Eigen::SparseMatrix<double>& A) { return spectral_condition_number(Eigen::MatrixXd(A)); }

} // namespace

NewtonMatrixConditioning newton_matrix_conditioning(const CutXfemModel& model, double density, double dt,
                                                    const PieceRuleFunction& mass_rule, double epsilon) {
  LinearDynamicSystem full;
  full.M = assemble_cut_xfem_mass(model, density, mass_rule);
  const DofMap all_free = make_dof_map(model.num_dof_nodes(), {});
  SparseAssembler assembler(model.assembly_slots(), all_free);
  Eigen::VectorXd unused_rhs = Eigen::VectorXd::Zero(all_free.num_free);
  model.assemble_linear_stiffness(assembler, unused_rhs);
  full.K = assembler.matrix();
  full.C = Eigen::SparseMatrix<double>(full.M.rows(), full.M.cols());

  const EnrichmentVolumes volumes = model.enrichment_volumes();
  NewtonMatrixConditioning result;
  result.enrichments = static_cast<int>(volumes.enriched.size());
  result.smallest_fraction = 1.0;
  for (Eigen::Index k = 0; k < result.enrichments; ++k) result.smallest_fraction = std::min(result.smallest_fraction, volumes.fraction(k));
  result.constrained = static_cast<int>(sliver_enrichments(volumes, epsilon).size());

  // T from eqs. 26-27 on the enrichments that have volume; the others are constrained in
  // every variant (epsilon 0), so their entry never enters.
  EnrichmentVolumes with_volume = volumes;
  for (double& v : with_volume.enriched) v = std::max(v, std::numeric_limits<double>::min());
  const Eigen::VectorXd koschier_t = koschier_preconditioner(with_volume, model.mesh().num_nodes());

  const FreeNewtonMatrix bare = free_newton_matrix(full, make_cut_xfem_dof_map(model, {}, 0.0), dt, koschier_t, model);
  result.plain = condition(bare.A);
  result.jacobi = condition(scale_bilaterally(bare.A, jacobi_preconditioner(bare.A)));
  result.koschier = condition(scale_bilaterally(bare.A, bare.koschier_t));
  result.part_jacobi = part_jacobi_condition(bare);
  const FreeNewtonMatrix constrained = free_newton_matrix(full, make_cut_xfem_dof_map(model, {}, epsilon), dt, koschier_t, model);
  result.plain_constrained = condition(constrained.A);
  result.jacobi_constrained = condition(scale_bilaterally(constrained.A, jacobi_preconditioner(constrained.A)));
  result.koschier_constrained = condition(scale_bilaterally(constrained.A, constrained.koschier_t));
  result.part_jacobi_constrained = part_jacobi_condition(constrained);
  return result;
}

} // namespace kerf
