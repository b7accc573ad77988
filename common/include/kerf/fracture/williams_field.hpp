/// @file williams_field.hpp
/// @brief Williams's near-front field of a straight crack front in closed form: displacement, its gradient and the stress.
///
/// Chapter 5's validation field (not in the papers): the leading term of the elastic field near a
/// straight crack front, plane strain for modes I and II and antiplane shear for mode III, with
/// stress intensity factors K_I, K_II, K_III (Pa sqrt(m)). It is written in the front frame of
/// crack_front.hpp: `a` points ahead of the front into uncut material, `b` is the unit normal of the cut
/// (theta > 0 on its + side), `c = a x b` runs along the front, and
///     r = sqrt(x_a^2 + x_b^2),  theta = atan2(x_b, x_a) in (-pi, pi],
/// so the cut faces are theta = +-pi. With mu the shear modulus, kappa = 3 - 4 nu (plane
/// strain) and C = K / (2 mu sqrt(2 pi)), every displacement component is C sqrt(r) f(theta):
///     mode I:   u_a = C_I  sqrt(r) cos(theta/2) (kappa - cos theta)
///               u_b = C_I  sqrt(r) sin(theta/2) (kappa - cos theta)
///     mode II:  u_a = C_II sqrt(r) sin(theta/2) (kappa + 2 + cos theta)
///               u_b = -C_II sqrt(r) cos(theta/2) (kappa - 2 + cos theta)
///     mode III: u_c = C_III sqrt(r) 4 sin(theta/2)   (= 2 K_III / mu sqrt(r / 2 pi) sin(theta/2))
/// (the textbook forms, e.g. Anderson, Fracture Mechanics, Tables 2.1-2.2, with
/// 2 sin^2(theta/2) = 1 - cos theta). The field does not depend on x_c.
#pragma once

#include "kerf/fem/linear_material.hpp"

#include <Eigen/Core>
#include <array>
#include <filesystem>

namespace kerf {

/// A straight crack front: a point on it and the right-handed frame R = [a | b | c] (columns).
struct StraightFrontFrame {
  Eigen::Vector3d origin{0, 0, 0};                    ///< a point of the front (m)
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();    ///< columns a (ahead), b (cut normal), c (along the front)

  /// x in the frame: (x_a, x_b, x_c) = R^T (x - origin).
  Eigen::Vector3d local(const Eigen::Vector3d& x) const { return R.transpose() * (x - origin); }
};

/// The frame with a = `ahead` and b = `normal` (both normalised) and c = a x b. Throws
/// std::invalid_argument when either is zero or they are not perpendicular (|a . b| > 1e-12).
StraightFrontFrame make_straight_front_frame(const Eigen::Vector3d& origin, const Eigen::Vector3d& ahead, const Eigen::Vector3d& normal);

/// Stress intensity factors of the three modes, Pa sqrt(m).
struct StressIntensityFactors {
  double K_I = 0.0;   ///< opening
  double K_II = 0.0;  ///< in-plane sliding (along a)
  double K_III = 0.0; ///< tearing (along c)
};

/// Polar coordinates about the front: r = sqrt(x_a^2 + x_b^2) and theta = atan2(x_b, x_a), except
/// that a point on the cut faces behind the front (x_b = 0, x_a < 0), where the field has two
/// values, takes the + side's theta = pi whatever the sign of the zero.
/// (Its own name: cut/crack_front.hpp has kerf::FrontPolar, the polar coordinates about a
/// polyline front, and one name for two types breaks the one-definition rule.)
struct StraightFrontPolar {
  double r = 0.0;
  double theta = 0.0;
};
StraightFrontPolar front_polar(const StraightFrontFrame& front, const Eigen::Vector3d& x);

/// The Williams displacement at x (m), in global coordinates: R (u_a, u_b, u_c).
Eigen::Vector3d williams_displacement(const StraightFrontFrame& front, const StressIntensityFactors& K, const LinearMaterial& material,
                                      const Eigen::Vector3d& x);

/// Its gradient H_ij = du_i/dx_j (3x3, global), in closed form: with u = C sqrt(r) f(theta),
///     du/dx_a = C / sqrt(r) (cos(theta) f / 2 - sin(theta) f'),
///     du/dx_b = C / sqrt(r) (sin(theta) f / 2 + cos(theta) f'),   du/dx_c = 0,
/// then H = R H_local R^T. Singular on the front: x with r = 0 throws std::invalid_argument.
Eigen::Matrix3d williams_displacement_gradient(const StraightFrontFrame& front, const StressIntensityFactors& K,
                                               const LinearMaterial& material, const Eigen::Vector3d& x);

/// The Williams stress at x (3x3, global, Pa), from the textbook's closed forms (not from the
/// gradient), with s = K / sqrt(2 pi r):
///     mode I:   s_aa = s cos(t/2) (1 - sin(t/2) sin(3t/2)),  s_bb = s cos(t/2) (1 + sin(t/2) sin(3t/2)),
///               s_ab = s cos(t/2) sin(t/2) cos(3t/2)
///     mode II:  s_aa = -s sin(t/2) (2 + cos(t/2) cos(3t/2)), s_bb = s sin(t/2) cos(t/2) cos(3t/2),
///               s_ab = s cos(t/2) (1 - sin(t/2) sin(3t/2))
///     mode III: s_ac = -s sin(t/2),  s_bc = s cos(t/2)
/// and s_cc = nu (s_aa + s_bb) (plane strain). Throws std::invalid_argument on the front.
Eigen::Matrix3d williams_stress(const StraightFrontFrame& front, const StressIntensityFactors& K, const LinearMaterial& material,
                                const Eigen::Vector3d& x);

/// The gradients and stresses of the three unit fields (K_I = 1, then K_II = 1, then K_III = 1)
/// at x, from one evaluation of the angles: the auxiliary fields of the interaction integral.
struct WilliamsUnitFields {
  std::array<Eigen::Matrix3d, 3> gradient; ///< williams_displacement_gradient of each unit mode
  std::array<Eigen::Matrix3d, 3> stress;   ///< williams_stress of each unit mode
};
WilliamsUnitFields williams_unit_fields(const StraightFrontFrame& front, const LinearMaterial& material, const Eigen::Vector3d& x);

/// The displacement at each point (rows of `points`, #P by 3): #P by 3.
Eigen::MatrixXd williams_displacements_at(const StraightFrontFrame& front, const StressIntensityFactors& K, const LinearMaterial& material,
                                          const Eigen::MatrixXd& points);

/// Writes the field at `points` as a displacement file (`x,y,z,ux,uy,uz`, 17 digits), the format a
/// scene's `"displacement_file"` reads: give it the mesh's nodes and a region around the whole
/// boundary, and the scene prescribes Williams's field there.
void write_williams_displacement_file(const std::filesystem::path& file, const StraightFrontFrame& front, const StressIntensityFactors& K,
                                      const LinearMaterial& material, const Eigen::MatrixXd& points);

} // namespace kerf
