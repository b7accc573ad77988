/// @file newton_matrix_conditioning.hpp
/// @brief The 2-norm condition number of the implicit step's matrix A = M + dt^2 K of a cut body, bare, Jacobi-scaled, with Koschier's preconditioner, with his constraining too (Koschier et al. section 6, Fig. 14), and in the part basis.
#pragma once

#include "kerf/xfem/cut_xfem_model.hpp"
#include "kerf/xfem/enrichment_volumes.hpp"

#include <Eigen/Core>

namespace kerf {

/// kappa_2(A) = lambda_max / lambda_min of a symmetric positive definite dense matrix, from its
/// eigenvalues (Eigen's SelfAdjointEigenSolver). The eigenvalues carry an absolute error of
/// about 1e-16 lambda_max, so numbers beyond about 1e15 only say "numerically singular".
/// @return +infinity when the smallest computed eigenvalue is not positive
double spectral_condition_number(const Eigen::MatrixXd& A);

/// The condition numbers of Koschier's Fig. 14 experiment for one cut body (dense: for small
/// bodies such as the five-tet cube). A = M + dt^2 K on the free DOFs is the Newton matrix of a
/// backward Euler step without damping (Koschier et al. section 7); K is the linear XFEM stiffness,
/// M the consistent XFEM mass. The body is free (no Dirichlet condition), as Koschier's cube.
struct NewtonMatrixConditioning {
  double plain = 0.0;               ///< kappa(A), enrichments with v <= 0 constrained only
  double jacobi = 0.0;              ///< kappa(T A T), T = diag(A)^(-1/2)
  double koschier = 0.0;            ///< kappa(T A T), T of eqs. 26-27
  double plain_constrained = 0.0;   ///< kappa(A) after eq. 22 constrains v < epsilon
  double jacobi_constrained = 0.0;  ///< kappa(T A T), Jacobi's T, after eq. 22 (on every part, home parts too)
  double koschier_constrained = 0.0; ///< eq. 22 and eqs. 26-27 together, Koschier's three steps (but the perturbation)
  double part_jacobi = 0.0;         ///< kappa(S^T A S), S = P T: the part basis (part_basis.hpp), then Jacobi;
                                    ///< infinity when a part is below round-off of P^T A P's diagonal
  double part_jacobi_constrained = 0.0; ///< the same after eq. 22
  double smallest_fraction = 0.0;   ///< the smallest v = V_enr / V_supp of any enrichment (1 if none)
  int enrichments = 0;              ///< enrichments of the body
  int constrained = 0;              ///< enrichments eq. 22 constrains
};

/// Assembles A = M + dt^2 K of `model` and measures the eight condition numbers.
/// @param density   rho (kg/m^3) for the mass
/// @param dt        the time step (s)
/// @param mass_rule a piece rule exact for degree 2 (Tet4) or 4 (Tet10), for the mass
/// @param epsilon   eq. 22's threshold (Koschier's 1e-9 by default)
NewtonMatrixConditioning newton_matrix_conditioning(const CutXfemModel& model, double density, double dt,
                                                    const PieceRuleFunction& mass_rule,
                                                    double epsilon = koschier_sliver_fraction);

} // namespace kerf
