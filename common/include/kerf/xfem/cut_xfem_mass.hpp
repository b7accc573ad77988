/// @file cut_xfem_mass.hpp
/// @brief The consistent XFEM mass of a body cut by triangle meshes, integrated on the pieces (Schoch et al. eqs. 76-80, degree 4 for Tet10).
#pragma once

#include "kerf/xfem/cut_xfem_model.hpp"
#include "kerf/xfem/split_tet_masses.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace kerf {

/// Throws std::invalid_argument naming `who` if `model` has crack-tip functions. Since the masses
/// have rows for the branch DOFs (below), only eqs. 81-82 of dynamics/lumped_mass.hpp call it:
/// Schoch et al. give them no branch rows.
void require_no_crack_tip_functions(const CutXfemModel& model, const char* who);

/// The scalar consistent mass of tet t on its slots (row t of model.assembly_slots()), S x S:
///
///   m_e = rho sum_q w_q g_q g_q^T,
///
/// g_q the value at point q of every slot's function (CutXfemModel::for_each_slot_value: the
/// phantom element's N_a on the node and sign slots, the branch functions N_v (F_l - F_l(x_v))
/// on the branch slots), over the points the model integrates the tet's stiffness at. For a tet
/// with branch functions these are its front or blending rules (chapter 5): the branch
/// functions are bounded (|F_l| <= sqrt(r)), so the products are bounded where the stiffness's
/// gradients are singular, and those rules serve them, with the stiffness's and the body
/// force's points (so that free fall stays exact). Measured on the phantom block against an
/// exact rule (tests/dynamics/test_branch_mass.cpp): the blending tets' graded Gauss rules are
/// exact (1e-14); the front tets' collapsed sub-tets, exact in r but not for polynomials, are off
/// by 7.7e-4 of the element mass on Tet4 (4 points per direction, the default) and 2.2e-5 on Tet10
/// (6), and exact with 8 (CrackTipFunctions::front_points). The weights sum to the volumes: the
/// body's mass and a translation's kinetic energy are exact whatever the points.
Eigen::MatrixXd cut_xfem_slot_mass(const CutXfemModel& model, Eigen::Index t, double density);

/// The consistent mass on all 3 num_dof_nodes() DOFs, no Dirichlet elimination:
///
///   M_e = sum_p T_p^T (rho int_p N^T N dV, times I_3) T_p,
///
/// the phantom elements' masses over their pieces (eqs. 77-80 with Psi in {0, 1} on each piece);
/// a tet with branch functions adds their rows and columns, cut_xfem_slot_mass() scattered.
/// N_a N_b has degree 2 on a Tet4 piece and 4 on a Tet10 piece: `rule` is asked for
/// that degree on every piece of a split tet, and must be exact for it (the "exact" and
/// "subtets" rules are; volume ratios are not, even for a Tet4; Koschier's "moment_fitting" is
/// built for degrees 1 and 2 only and refuses 4). Tets integrated whole use chapter 1's
/// element masses.
Eigen::SparseMatrix<double> assemble_cut_xfem_mass(const CutXfemModel& model, double density, const PieceRuleFunction& rule);

/// The scalar masses rho int_p N_a N_b dV (n x n) of every piece tet t integrates, in piece
/// order: its split pieces (each with `rule` of degree 2 order), or the whole tet as one
/// (chapter 1's element mass). What assemble_cut_xfem_mass() scatters, and what the lumped
/// masses of chapter 6 (dynamics/lumped_mass.hpp) lump piece by piece. In a tet with branch
/// functions: the phantom block of each of the model's pieces over its front or blending rule
/// (for_each_slot_value; `rule` is not used there), the points cut_xfem_slot_mass() sums over
/// (the lumped masses do not lump such a tet: lumped_mass.hpp).
std::vector<Eigen::MatrixXd> cut_xfem_piece_masses(const CutXfemModel& model, Eigen::Index t, double density,
                                                   const PieceRuleFunction& rule);

/// assemble_cut_xfem_mass() with the piece masses from `masses` (of this model; scaled by `density`).
Eigen::SparseMatrix<double> assemble_cut_xfem_mass(const CutXfemModel& model, double density, const SplitTetMasses& masses);

/// The body's mass as a mass matrix sees it: e^T M e for e a unit translation of the mesh's
/// nodes along x (the enrichments at 0); rho V for every scheme of lumped_mass.hpp and for the
/// consistent mass, so a change of the cut must leave it unchanged.
double translation_mass(const Eigen::SparseMatrix<double>& M, Eigen::Index num_mesh_nodes);

} // namespace kerf
