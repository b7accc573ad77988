// Assignment 01: the element stiffness matrices of Tet4 and Tet10 in linear elasticity.
// This file stands in for common/src/fem/tet_stiffness.cpp when assignment 01 is graded
// (./kerf.sh assignment 01); what to compute is in assignments/01_linear_fem/README.md.
#include "kerf/fem/tet_stiffness.hpp"

#include "kerf/fem/positive_jacobian.hpp"   // require_positive_jacobian: refuse det J <= 0
#include "kerf/fem/tet_quadrature.hpp"      // tet_quadrature_rule: points and weights on the reference tet
#include "kerf/fem/tet_shape_functions.hpp" // the shape gradients, physical_shape_gradients

#include <stdexcept>

namespace kerf {

/// Tet4 element stiffness (eq. 30 with constant gradients, times the volume), 12x12, node-major
/// DOFs 3a + p.
/// @param X 4x3 corner positions, positively oriented: det[x1-x0, x2-x0, x3-x0] > 0, or
///          std::invalid_argument (see positive_jacobian.hpp)
Eigen::Matrix<double, 12, 12> tet4_stiffness([[maybe_unused]] const Eigen::Matrix<double, 4, 3>& X,
                                             [[maybe_unused]] const LinearMaterial& material) {
  throw std::logic_error("assignment 01: implement tet4_stiffness (assignments/01_linear_fem/README.md)");
}

/// Tet10 element stiffness, 30x30: eq. (30) integrated with the 4-point degree-2 rule, which
/// is exact for straight-edged Tet10 (their gradients are linear, the integrand quadratic).
/// @param X 10x3 node positions (Kerf's Tet10 order) with det J > 0 at the four points, or
///          std::invalid_argument (see positive_jacobian.hpp)
Eigen::Matrix<double, 30, 30> tet10_stiffness([[maybe_unused]] const Eigen::Matrix<double, 10, 3>& X,
                                              [[maybe_unused]] const LinearMaterial& material) {
  throw std::logic_error("assignment 01: implement tet10_stiffness (assignments/01_linear_fem/README.md)");
}

} // namespace kerf
