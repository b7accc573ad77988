/// @file positive_jacobian.hpp
/// @brief The precondition of every element integral: det J > 0 at each point it is evaluated.
///
/// The element integrals of eqs. (26) and (30) are sums of w_q det J(xi_q) times an integrand.
/// For a tet whose corners are listed in the negative orientation det J < 0, and the element
/// matrices come out negative definite without any other sign of trouble; for a flat tet they
/// vanish. A mesh read from a file is reoriented by check_tet_mesh(), but a mesh built in code
/// (a test, a study, later a remesher) never passes through it. So the integrals check for
/// themselves: one comparison per element or quadrature point, which costs nothing next to the
/// integrand.
#pragma once

#include <Eigen/Core>

namespace kerf {

/// Throws std::invalid_argument saying which function refused which element and why.
/// Out of line and [[noreturn]], so that the check below stays one branch in the loops.
[[noreturn]] void throw_non_positive_jacobian(double det_J, const char* function, Eigen::Index element);

/// Throws std::invalid_argument unless det_J > 0 (a NaN fails too).
/// @param det_J    the Jacobian determinant det(dx/dxi), 6 times the volume for a straight tet
/// @param function the function that integrates, named in the message
/// @param element  the element's row in the mesh, named in the message; -1 when the caller
///                 has only the node positions (the element functions tet4_stiffness etc.)
inline void require_positive_jacobian(double det_J, const char* function, Eigen::Index element = -1) {
  if (!(det_J > 0.0)) [[unlikely]]
    throw_non_positive_jacobian(det_J, function, element);
}

} // namespace kerf
