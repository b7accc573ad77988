/// @file cut_xfem_mass.hpp
/// @brief The consistent XFEM mass of a body cut by triangle meshes, integrated on the pieces (Paper 000 eqs. 76-80, degree 4 for Tet10).
#pragma once

#include "kerf/xfem/cut_xfem_model.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace kerf {

/// Throws std::invalid_argument naming `who` if `model` has crack-tip functions: the masses of
/// this file and of dynamics/lumped_mass.hpp are the phantom elements', with no rows for the
/// branch DOFs (rho int N_a F_l N_b F_m would need the front rules of the stiffness), so chapter
/// 6's dynamics refuses chapter 5's functions rather than give them no inertia.
void require_no_crack_tip_functions(const CutXfemModel& model, const char* who);

/// The consistent mass on all 3 num_dof_nodes() DOFs, no Dirichlet elimination:
///
///   M_e = sum_p T_p^T (rho int_p N^T N dV, times I_3) T_p,
///
/// the phantom elements' masses over their pieces (eqs. 77-80 with Psi in {0, 1} on each piece).
/// N_a N_b has degree 2 on a Tet4 piece and 4 on a Tet10 piece (notes 4.4): `rule` is asked for
/// that degree on every piece of a split tet, and must be exact for it (the "exact" and
/// "subtets" rules are; volume ratios are not, even for a Tet4; Koschier's "moment_fitting" is
/// built for degrees 1 and 2 only and refuses 4). Tets integrated whole use chapter 1's
/// element masses.
Eigen::SparseMatrix<double> assemble_cut_xfem_mass(const CutXfemModel& model, double density, const PieceRuleFunction& rule);

/// The scalar masses rho int_p N_a N_b dV (n x n) of every piece tet t integrates, in piece
/// order: its split pieces (each with `rule` of degree 2 order), or the whole tet as one
/// (chapter 1's element mass). What assemble_cut_xfem_mass() scatters, and what the lumped
/// masses of chapter 6 (dynamics/lumped_mass.hpp) lump piece by piece.
std::vector<Eigen::MatrixXd> cut_xfem_piece_masses(const CutXfemModel& model, Eigen::Index t, double density,
                                                   const PieceRuleFunction& rule);

} // namespace kerf
