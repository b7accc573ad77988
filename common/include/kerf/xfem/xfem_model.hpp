/// @file xfem_model.hpp
/// @brief The cut body: the [u; a] unknowns (Schoch et al. eq. 74), its linear stiffness by volume ratios (eqs. 60-63)
///        and its corotated forces and tangent with one rotation per piece (eqs. 64-71).
#pragma once

#include "kerf/corotation/quasi_static_model.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/rigid_motion_check.hpp"
#include "kerf/fem/linear_material.hpp"
#include "kerf/solve/linear_solver.hpp"
#include "kerf/xfem/enrichment.hpp"

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

namespace kerf {

/// A Tet4 mesh with one cut, enriched by shifted Heaviside functions.
///
/// The unknowns are [u_1 .. u_N, a_1 .. a_Nenr] (eq. 74): three displacements per node, then
/// three enriched DOFs per enriched node. We number them as "DOF nodes" 0 .. N + N_enr - 1,
/// three DOFs each, so that the DofMap and the SparseAssembler of chapter 1 serve unchanged:
/// node i's u is DOF node i, its a is DOF node N + enriched_index[i]. Each tet has a row of 8
/// slots, its 4 nodes and then the 4 enriched DOF nodes of its corners, -1 where a corner is
/// not enriched. Dirichlet conditions fix u_i and, for an enriched node, a_i = 0 as well (see
/// make_xfem_dof_map for why u_i alone is not enough).
///
/// Everything that does not change with the deformation is computed here once: for every tet
/// its stiffness K (eq. 47), its shape gradients, its volume and the Psi values of its corners.
class XfemModel : public QuasiStaticModel {
public:
  /// @param mesh       the Tet4 mesh (kept by reference)
  /// @param material   the material
  /// @param enrichment make_enrichment(mesh, cut) (kept by reference)
  XfemModel(const TetMesh& mesh, const LinearMaterial& material, const Enrichment& enrichment);

  /// N + N_enr.
  Eigen::Index num_dof_nodes() const override { return mesh_.num_nodes() + enrichment_.num_enriched(); }

  /// #T by 8: [4 nodes, 4 enriched DOF nodes or -1].
  const TetMatrix& assembly_slots() const override { return slots_; }

  /// Corotational XFEM (section 4.3.2): every piece of a cut tet turns with its own rotation,
  /// R_a from the deformation gradient of the above side's corner values u_a and R_b from u_b
  /// (eqs. 64-71); tets without enriched corners are chapter 2's corotated Tet4.
  CorotationStatistics assemble(const Eigen::VectorXd& u, RotationMethod rotation, CorotationalTangent tangent,
                                Eigen::VectorXd& f_int, SparseAssembler* assembler, Eigen::VectorXd* rhs_free) const override;

  double position_force_norm() const override { return position_force_norm_; }

  /// The linear XFEM stiffness K^X (eqs. 60-63) added into `assembler`, lifting into rhs_free.
  void assemble_linear_stiffness(SparseAssembler& assembler, Eigen::VectorXd& rhs_free) const;

  /// The strain energy 1/2 sum over pieces (V_side / V) d^T K d with d = R^T x_side - X, the
  /// corotated energy of every piece; with `corotated` false R = I (linear XFEM).
  double energy(const Eigen::VectorXd& u, bool corotated, RotationMethod rotation = RotationMethod::automatic) const;

  /// The displacement of corner `corner` of tet t as the piece on side `side` (+1 above,
  /// -1 below) sees it: u_i + Psi_side,i a_i (eq. 66). For a tet on one side, `side` should be
  /// that side.
  Eigen::Vector3d side_displacement(const Eigen::VectorXd& u, Eigen::Index t, int corner, int side) const;

  /// Psi_side,i of the four corners of tet t (0 for a corner without enriched DOFs).
  Eigen::Vector4d psi(Eigen::Index t, int side) const;

  /// The four shape functions Phi_i of tet t at the point x (m): Phi_i(X_0) + grad Phi_i . (x - X_0).
  Eigen::Vector4d shape_values(Eigen::Index t, const Eigen::Vector3d& x) const;

  /// Whether tet t has a corner with enriched DOFs (and so needs the 24 x 24 form).
  bool has_enriched_corner(Eigen::Index t) const { return slots_used_[static_cast<std::size_t>(t)] > 4; }

  const TetMesh& mesh() const { return mesh_; }
  const LinearMaterial& material() const { return material_; }
  const Enrichment& enrichment() const { return enrichment_; }
  const Eigen::Matrix<double, 12, 12>& element_stiffness(Eigen::Index t) const { return stiffness_[static_cast<std::size_t>(t)]; }
  double element_volume(Eigen::Index t) const { return volumes_[static_cast<std::size_t>(t)]; }

private:
  const TetMesh& mesh_;
  LinearMaterial material_;
  const Enrichment& enrichment_;
  TetMatrix slots_;
  std::vector<int> slots_used_;
  std::vector<Eigen::Matrix<double, 12, 12>> stiffness_;
  std::vector<Eigen::Matrix<double, 4, 3>> gradients_;
  std::vector<double> volumes_;
  double position_force_norm_ = 0.0;
};

/// The DofMap of the [u; a] unknowns: the Dirichlet conditions on the mesh's nodes, and for
/// every enriched node among them also a_i = 0.
///
/// Why a_i too. With the shifted enrichment the field at node i is u_i on both sides, so
/// fixing u_i holds the node (Schoch et al. section 4.2: a node "can be fixed to a specific value by
/// constraining a single DOF"). It does not hold the field between nodes: on a Dirichlet face
/// inside a cut tet, the side that node j is not on sees sum_j Phi_j (u_j + Psi_j a_j), and
/// with u_j prescribed and a_j free the two flaps can slide along the clamp. With a_j = 0 on
/// every node of the face, both sides see the interpolant of the prescribed values: the
/// condition holds on the whole face, on both sides of the cut. In general the side s field at
/// a gripped node is g_s(x_i) = u_i + Psi_s,i a_i, so a_i = (g_other - g_own) / Psi_other,i; every
/// prescribed field a scene can give (a translation, a rotation) is continuous across the cut,
/// which makes a_i = 0. So a gripped node holds both flaps: the clamp grips the tissue on both
/// sides of the cut, whichever side the node itself is on. A condition in `conditions` on an
/// enriched DOF node N + k (a field that jumps across the cut) overrides that a_k = 0.
DofMap make_xfem_dof_map(const XfemModel& model, const std::vector<DirichletNodes>& conditions);

/// The cut body as a plain Tet4 mesh with phantom nodes, for questions about its pieces.
///
/// On each side of a cut tet the field is an ordinary linear field with corner values u_i on
/// the corners of that side and u_i + Psi_i a_i on the others (xfem_element.hpp's side
/// operator T); (u_i, a_i) and the two sides' values at node i determine each other. So K^X is
/// singular exactly when the mesh in which every such piece is a tet of its own, with "phantom"
/// nodes N + k at the positions of the enriched nodes for the other side's values, has a piece
/// no Dirichlet condition holds.
struct PhantomMesh {
  TetMesh mesh;                              ///< N + N_enr nodes; one tet per uncut tet, one per side of every tet with an enriched corner
  std::vector<double> piece_volume;          ///< per tet: the volume of the material it stands for (fraction V for a piece)
  std::vector<Eigen::Vector3d> piece_point;  ///< per tet: a point of that material (the centroid of its largest sub-tet)
};
PhantomMesh xfem_phantom_mesh(const XfemModel& model);

/// The pieces of the cut body that `dofs` leaves free to move rigidly (see unheld_pieces), from
/// its phantom mesh: a DOF node there is held when every unknown behind its value is prescribed.
std::vector<UnheldPiece> xfem_unheld_pieces(const XfemModel& model, const DofMap& dofs);

/// One line naming the first unheld piece, for error messages: its volume, a point in it and
/// the number of its free rigid motions.
std::string describe_unheld_pieces(const std::vector<UnheldPiece>& pieces);

/// Linear XFEM in one call: assembles K^X (eqs. 60-63), lifts, factorises and solves.
/// @param f_ext loads on all 3 (N + N_enr) DOFs (see xfem_loads.hpp)
/// @return all DOFs [u; a]
/// @throws std::runtime_error naming the piece, before any factorisation, when a piece the cut
///         leaves (or any piece of the body) is held by no Dirichlet condition: K^X_ff is then
///         singular, and a solver cannot be trusted to notice (LDLT returns 3e10 m)
Eigen::VectorXd solve_linear_xfem(const XfemModel& model, const DofMap& dofs, const Eigen::VectorXd& f_ext,
                                  const SolverSettings& solver_settings);

} // namespace kerf
