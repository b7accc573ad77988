/// @file quasi_static_model.hpp
/// @brief What the quasi-static solver needs from an elastic body: its DOF layout, its internal forces and their tangent.
#pragma once

#include "kerf/corotation/corotated_element.hpp"
#include "kerf/corotation/corotation_statistics.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/mesh/tet_mesh.hpp"

#include <Eigen/Core>

namespace kerf {

/// A body whose equilibrium solve_quasi_static() can find: chapter 2's corotated mesh
/// (CorotationalModel) and chapter 3's cut one (XfemCorotationalModel).
///
/// The solver only ever asks for the residual and the tangent at a state u, so one interface of
/// three questions lets the same Newton iteration, load stepping and fallback serve both; the
/// XFEM body differs only in its unknowns, [u; a] instead of u (Schoch et al. eq. 74).
class QuasiStaticModel {
public:
  virtual ~QuasiStaticModel() = default;

  /// The number of "DOF nodes", three DOFs each: #V for plain FEM, #V + #enriched nodes for
  /// XFEM. Displacement vectors have 3 num_dof_nodes() entries.
  virtual Eigen::Index num_dof_nodes() const = 0;

  /// One row of DOF nodes per element, for the SparseAssembler (-1 marks an empty slot).
  virtual const TetMatrix& assembly_slots() const = 0;

  /// Internal forces f_int(u) (3 num_dof_nodes()) and, when `assembler` is given, the tangent
  /// added into it (its lifting moves -K_fc u_c into rhs_free, with the u_c of its DofMap).
  virtual CorotationStatistics assemble(const Eigen::VectorXd& u, RotationMethod rotation, CorotationalTangent tangent,
                                        Eigen::VectorXd& f_int, SparseAssembler* assembler, Eigen::VectorXd* rhs_free) const = 0;

  /// sqrt(sum_e |K_e X_e|^2): the size of the element forces that cancel in f_int = R K (R^T x - X).
  /// f_int carries a round-off error of about machine epsilon times this, whatever u is; the
  /// quasi-static solver uses it as a floor for its tolerance.
  virtual double position_force_norm() const = 0;
};

} // namespace kerf
