/// @file newton_history_csv.hpp
/// @brief Write the quasi-static solver's convergence history as CSV: how we know what Newton's method reached.
#pragma once

#include "kerf/corotation/quasi_static_solver.hpp"

#include <filesystem>
#include <vector>

namespace kerf {

/// Writes `step,iteration,relative_residual,warped_fallback`, one row per Newton iteration.
/// @throws InputError `FILE: file: cannot write the convergence history` when it cannot
void write_newton_history_csv(const std::filesystem::path& file, const std::vector<NewtonIteration>& history);

} // namespace kerf
