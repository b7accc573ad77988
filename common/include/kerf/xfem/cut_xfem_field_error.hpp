/// @file cut_xfem_field_error.hpp
/// @brief How far a cut body's field is from a field known in closed form: the L2 and energy norms of the difference, integrated piece by piece.
///
/// The convergence of chapter 5 is measured against Williams's field (williams_field.hpp): with
/// e = u_h - u,
///   ||e||_L2 = sqrt(int |e|^2 dV),   ||e||_E = sqrt(int eps(e) : C : eps(e) dV),
///   eps(e) : C : eps(e) = lambda tr(eps)^2 + 2 mu eps : eps,
/// each divided by the same norm of u for a relative error. The integrals run over every piece of
/// every tet, so that no rule straddles the cut where u_h and u jump: sub-tets with the Gauss
/// rule of degree 4, refined twice in the tets a front passes through and once in the tets
/// whose centre lies within two of their longest edges of a front, where the gradient of a field
/// without branch functions grows like 1 / sqrt(r) (examples/williams_slab.hpp measures the
/// same way, with the cell size for the tet's edge).
#pragma once

#include "kerf/cut/crack_front.hpp"
#include "kerf/fem/linear_material.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"

#include <Eigen/Core>
#include <functional>

namespace kerf {

/// The norms of the error and of the exact field.
struct FieldError {
  double L2 = 0.0, L2_exact = 0.0;         ///< ||u_h - u||_L2, ||u||_L2 (m^(5/2))
  double energy = 0.0, energy_exact = 0.0; ///< ||u_h - u||_E, ||u||_E (sqrt(J))
  double relative_L2() const { return L2 / L2_exact; }
  double relative_energy() const { return energy / energy_exact; }
};

/// The exact field's displacement (m) and gradient du_i/dx_j at a point x (m).
using ExactDisplacement = std::function<Eigen::Vector3d(const Eigen::Vector3d& x)>;
using ExactGradient = std::function<Eigen::Matrix3d(const Eigen::Vector3d& x)>;

/// The error of the field u (all DOFs [u; a; b] of `model`) against the exact one.
/// @param model    the cut body
/// @param material its material (lambda and mu of the energy norm)
/// @param u        3 model.num_dof_nodes() values
/// @param fronts   the fronts of its cuts (where the rules are refined; empty: nowhere)
FieldError cut_xfem_field_error(const CutXfemModel& model, const LinearMaterial& material, const Eigen::VectorXd& u,
                                const CrackFronts& fronts, const ExactDisplacement& exact,
                                const ExactGradient& exact_gradient);

} // namespace kerf
