/// @file solve_linear_static.hpp
/// @brief The whole static linear solve in one call: assemble K_ff, lift, factorise, solve.
#pragma once

#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/linear_material.hpp"
#include "kerf/mesh/tet_mesh.hpp"
#include "kerf/solve/linear_solver.hpp"

#include <Eigen/Core>

namespace kerf {

/// Solves K u = f with the Dirichlet conditions of `dofs` eliminated, as chapter 1 does step
/// by step; tests, benchmarks and studies call this instead of repeating the steps.
/// @param f nodal loads, 3#V (node-major)
/// @return all nodal displacements, 3#V
Eigen::VectorXd solve_linear_static(const TetMesh& mesh, const LinearMaterial& material, const DofMap& dofs,
                                    const Eigen::VectorXd& f, const SolverSettings& solver_settings);

} // namespace kerf
