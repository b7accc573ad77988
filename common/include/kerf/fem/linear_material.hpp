/// @file linear_material.hpp
/// @brief Isotropic linear elastic material: Young's modulus and Poisson's ratio to Lame constants and Voigt C.
#pragma once

#include <Eigen/Core>

namespace kerf {

/// A homogeneous, isotropic, linear elastic material (Schoch et al., section 2.1).
///
/// The Lame constants are computed from E and nu where they are asked for, and checked there:
/// a Poisson ratio at 0.5 makes lambda infinite (incompressible), and every number must be
/// finite, so a library caller with a wrong material gets std::invalid_argument naming the
/// field, not a stiffness full of inf. The scene reader checks the same with a message naming
/// the file.
struct LinearMaterial {
  /// The largest Poisson ratio accepted: 0.5 - 1e-6 (lambda = E / (6e-6 (1 + nu)) there, about
  /// 1.1e5 E, already far past where Tet4 locks; see chapter 1's locking study).
  static constexpr double max_poisson = 0.5 - 1e-6;

  double young = 300e3;    ///< Young's modulus E in Pa, positive
  double poisson = 0.35;   ///< Poisson's ratio nu, in (-1, max_poisson]
  double density = 1070.0; ///< mass density rho in kg/m^3, non-negative

  /// Throws std::invalid_argument naming the first field out of range.
  void check() const;
  /// First Lame constant lambda = E nu / ((1 + nu)(1 - 2 nu)), in Pa (checks the material).
  double lambda() const {
    check();
    return young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
  }
  /// Shear modulus mu = E / (2 (1 + nu)), in Pa (checks the material).
  double mu() const {
    check();
    return young / (2.0 * (1.0 + poisson));
  }
};

/// The Poisson ratio above which a scene with Tet4 elements gets a warning that they lock.
inline constexpr double near_incompressible_poisson = 0.45;

/// The 6x6 material matrix C of eq. (6), sigma = C epsilon, in the paper's Voigt order
/// (xx, yy, zz, xy, xz, yz) with engineering shear strains gamma_xy = 2 epsilon_xy.
Eigen::Matrix<double, 6, 6> voigt_elasticity_matrix(const LinearMaterial& material);

} // namespace kerf
