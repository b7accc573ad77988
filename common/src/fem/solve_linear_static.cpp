#include "kerf/fem/solve_linear_static.hpp"

#include "kerf/fem/assemble_stiffness.hpp"
#include "kerf/fem/rigid_motion_check.hpp"
#include "kerf/fem/sparse_assembler.hpp"

#include <stdexcept>
#include <string>

namespace kerf {

Eigen::VectorXd solve_linear_static(const TetMesh& mesh, const LinearMaterial& material, const DofMap& dofs,
                                    const Eigen::VectorXd& f, const SolverSettings& solver_settings) {
  if (const int free_motions = count_free_rigid_motions(mesh, dofs); free_motions > 0)
    throw std::runtime_error("the Dirichlet conditions leave " + std::to_string(free_motions) +
                             " rigid motions free: the stiffness matrix is singular");
  SparseAssembler assembler(mesh.tets, dofs);
  Eigen::VectorXd rhs = dofs.restrict_to_free(f);
  assemble_linear_stiffness(mesh, material, assembler, rhs);
  return dofs.expand(solve_once(assembler.matrix(), rhs, solver_settings));
}

} // namespace kerf
