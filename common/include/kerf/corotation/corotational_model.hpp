/// @file corotational_model.hpp
/// @brief The corotational elastic body: precomputed element data, internal forces, tangent, energy.
#pragma once

#include "kerf/corotation/corotated_element.hpp"
#include "kerf/corotation/quasi_static_model.hpp"
#include "kerf/fem/linear_material.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/mesh/tet_mesh.hpp"

#include <Eigen/Core>
#include <vector>

namespace kerf {

/// A Tet4 or Tet10 body with corotated linear elasticity (Schoch et al., section 3.7).
///
/// Everything that does not change is computed once: for a Tet4 the 12x12 stiffness of
/// chapter 1 and the shape gradients; for a Tet10 the gradients and weights at the four
/// quadrature points, each of which gets its own rotation (the paper's remark after eq. 31: one
/// R cannot turn a quadratic tet back, so a separate polar decomposition per cubature point).
class CorotationalModel : public QuasiStaticModel {
public:
  /// The volumes and w_q det J are the integration weights, so every tet must have det J > 0
  /// (at each quadrature point for a Tet10): std::invalid_argument names the first that has
  /// not (see positive_jacobian.hpp).
  CorotationalModel(const TetMesh& mesh, const LinearMaterial& material);

  /// Internal forces f_int(u) (3#V) and, when `assembler` is given, the tangent added into it
  /// (its lifting moves -K_fc u_c into rhs_free, with the u_c of the assembler's DofMap).
  CorotationStatistics assemble(const Eigen::VectorXd& u, RotationMethod rotation, CorotationalTangent tangent,
                                Eigen::VectorXd& f_int, SparseAssembler* assembler, Eigen::VectorXd* rhs_free) const override;

  /// #V: one DOF node per mesh node.
  Eigen::Index num_dof_nodes() const override { return mesh_.num_nodes(); }

  /// The mesh's own connectivity.
  const TetMatrix& assembly_slots() const override { return mesh_.tets; }

  /// The corotated strain energy sum 1/2 (R^T x - X)^T K (R^T x - X): zero for any rigid motion.
  double energy(const Eigen::VectorXd& u, RotationMethod rotation) const;

  /// sqrt(sum_e |K_e X_e|^2): the size of the element forces that cancel in f_int = R K (R^T x - X).
  /// f_int carries a round-off error of about machine epsilon times this, whatever u is; the
  /// quasi-static solver uses it as a floor for its tolerance.
  double position_force_norm() const override { return position_force_norm_; }

  const TetMesh& mesh() const { return mesh_; }
  const LinearMaterial& material() const { return material_; }

private:
  const TetMesh& mesh_;
  LinearMaterial material_;
  std::vector<Eigen::Matrix<double, 12, 12>> tet4_stiffness_;  ///< Tet4: K per element
  std::vector<Eigen::Matrix<double, 4, 3>> tet4_gradients_;    ///< Tet4: grad N per element
  std::vector<double> tet4_volumes_;                           ///< Tet4: V per element
  std::vector<Eigen::Matrix<double, 10, 3>> tet10_gradients_;  ///< Tet10: grad N per element and point (4 per element)
  std::vector<double> tet10_weights_;                          ///< Tet10: w_q |det J| per element and point
  double position_force_norm_ = 0.0;
};

} // namespace kerf
