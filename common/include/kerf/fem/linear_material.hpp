/// @file linear_material.hpp
/// @brief Isotropic linear elastic material: Young's modulus and Poisson's ratio to Lame constants and Voigt C.
#pragma once

#include <Eigen/Core>

namespace kerf {

/// A homogeneous, isotropic, linear elastic material (Schoch et al., section 2.1).
struct LinearMaterial {
  double young = 300e3;    ///< Young's modulus E in Pa
  double poisson = 0.35;   ///< Poisson's ratio nu, in (-1, 0.5)
  double density = 1070.0; ///< mass density rho in kg/m^3

  /// First Lame constant lambda = E nu / ((1 + nu)(1 - 2 nu)), in Pa.
  double lambda() const { return young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson)); }
  /// Shear modulus mu = E / (2 (1 + nu)), in Pa.
  double mu() const { return young / (2.0 * (1.0 + poisson)); }
};

/// The 6x6 material matrix C of eq. (6), sigma = C epsilon, in the paper's Voigt order
/// (xx, yy, zz, xy, xz, yz) with engineering shear strains gamma_xy = 2 epsilon_xy.
Eigen::Matrix<double, 6, 6> voigt_elasticity_matrix(const LinearMaterial& material);

} // namespace kerf
