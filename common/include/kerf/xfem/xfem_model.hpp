/// @file xfem_model.hpp
/// @brief The cut body: the [u; a] unknowns (Paper 000 eq. 74), its linear stiffness by volume ratios (eqs. 60-63)
///        and its corotated forces and tangent with one rotation per piece (eqs. 64-71).
#pragma once

#include "kerf/corotation/quasi_static_model.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/linear_material.hpp"
#include "kerf/solve/linear_solver.hpp"
#include "kerf/xfem/enrichment.hpp"

#include <Eigen/Core>
#include <array>
#include <vector>

namespace kerf {

/// A Tet4 mesh with one cut, enriched by shifted Heaviside functions.
///
/// The unknowns are [u_1 .. u_N, a_1 .. a_Nenr] (eq. 74): three displacements per node, then
/// three enriched DOFs per enriched node. We number them as "DOF nodes" 0 .. N + N_enr - 1,
/// three DOFs each, so that the DofMap and the SparseAssembler of chapter 1 serve unchanged:
/// node i's u is DOF node i, its a is DOF node N + enriched_index[i]. Each tet has a row of 8
/// slots, its 4 nodes and then the 4 enriched DOF nodes of its corners, -1 where a corner is
/// not enriched. Dirichlet conditions fix u_i alone: with the shifted enrichment u_i is the
/// node's displacement (section 5.2), so no condition is needed on a_i.
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

/// The DofMap of the [u; a] unknowns: the Dirichlet conditions on the mesh's nodes, and every
/// enriched DOF free.
DofMap make_xfem_dof_map(const XfemModel& model, const std::vector<DirichletNodes>& conditions);

/// Linear XFEM in one call: assembles K^X (eqs. 60-63), lifts, factorises and solves.
/// @param f_ext loads on all 3 (N + N_enr) DOFs (see xfem_loads.hpp)
/// @return all DOFs [u; a]
/// @throws std::runtime_error naming the likely cause when K^X_ff is singular (a piece the cut
///         separates has no Dirichlet condition)
Eigen::VectorXd solve_linear_xfem(const XfemModel& model, const DofMap& dofs, const Eigen::VectorXd& f_ext,
                                  const SolverSettings& solver_settings);

} // namespace kerf
