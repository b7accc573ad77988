/// @file solver_checks.hpp
/// @brief What every linear solver checks and says, in one place (private to the library).
#pragma once

#include "kerf/solve/linear_solver.hpp"

#include <Eigen/Core>
#include <stdexcept>

namespace kerf::solver_checks {

/// The message of NotPositiveDefinite, whichever solver found it.
inline const char* not_positive_definite =
    "the stiffness matrix is not positive definite: is the body held by enough Dirichlet conditions?";

/// A NaN or infinite load would come back as a NaN solution: refuse it before solving.
inline void require_finite_right_hand_side(const Eigen::MatrixXd& b) {
  if (!b.allFinite())
    throw std::invalid_argument("the right-hand side is not finite: an infinite or NaN load or prescribed displacement");
}

} // namespace kerf::solver_checks
