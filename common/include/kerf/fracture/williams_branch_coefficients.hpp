/// @file williams_branch_coefficients.hpp
/// @brief Williams's near-front field written in the four branch functions: u = sum_l F_l c_l with constant vectors c_l.
///
/// The branch functions of chapter 5 (branch_functions.hpp),
///   F = sqrt(r) ( sin(theta/2), cos(theta/2), sin(theta/2) sin(theta), cos(theta/2) sin(theta) ),
/// span the first term of the field at a straight front for every mode (Fleming et al. 1997), so
/// Williams's displacement (williams_field.hpp) is exactly sum_l F_l(x) c_l. With
/// A = K / (2 mu sqrt(2 pi)) per mode, kappa = 3 - 4 nu (plane strain) and the front's frame a, b, c:
///   mode I:   c_1 = A_I (kappa + 1) b,   c_2 = A_I (kappa - 1) a,   c_3 = A_I a,   c_4 = -A_I b
///   mode II:  c_1 = A_II (kappa + 1) a,  c_2 = -A_II (kappa - 1) b, c_3 = A_II b,  c_4 = A_II a
///   mode III: c_1 = 4 A_III c
/// (u_a = A_I sqrt(r) cos(theta/2) (kappa - cos theta) = A_I ((kappa - 1) F_2 + F_3), since
/// 2 sin^2(theta/2) = 1 - cos theta; the others the same way). A branch node whose four DOFs take
/// these values carries the exact field: what a program prescribes on a branch node of a
/// boundary where Williams's field is given.
#pragma once

#include "kerf/fem/linear_material.hpp"
#include "kerf/fracture/williams_field.hpp"

#include <Eigen/Core>
#include <array>

namespace kerf {

/// c_1 .. c_4 of Williams's field (m^1/2, in global coordinates) for the front `front`, the
/// factors K (Pa sqrt(m)) and the material's mu and nu (plane strain).
std::array<Eigen::Vector3d, 4> williams_branch_coefficients(const StraightFrontFrame& front,
                                                            const StressIntensityFactors& K,
                                                            const LinearMaterial& material);

} // namespace kerf
