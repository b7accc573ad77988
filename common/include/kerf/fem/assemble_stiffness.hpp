/// @file assemble_stiffness.hpp
/// @brief The element loop of linear elasticity: every Tet4 or Tet10 stiffness into K_ff.
#pragma once

#include "kerf/fem/linear_material.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/mesh/tet_mesh.hpp"

#include <Eigen/Core>

namespace kerf {

/// Computes every element stiffness (tet4_stiffness or tet10_stiffness, eq. 30) and adds it
/// through the assembler: the free-free entries into K_ff, the prescribed columns into rhs_free
/// (f_f -= K_fc u_c). The assembler's values are not zeroed first: call set_zero() for a fresh K.
/// Every tet must be positively oriented: std::invalid_argument names the first one whose
/// corner volume is not positive (see positive_jacobian.hpp).
void assemble_linear_stiffness(const TetMesh& mesh, const LinearMaterial& material, SparseAssembler& assembler,
                               Eigen::VectorXd& rhs_free);

} // namespace kerf
