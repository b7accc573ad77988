/// @file scene_quasi_static.hpp
/// @brief The quasi-static solver's settings as a scene file gives them (its "quasi_static" and "solver" fields).
#pragma once

#include "kerf/corotation/quasi_static_solver.hpp"
#include "kerf/scene/scene.hpp"

namespace kerf {

/// Load steps, Newton iterations, tolerance, tangent ("consistent" or "warped"), rotation
/// ("automatic", "higham" or "svd") and linear solver from `scene`; every chapter that solves
/// a nonlinear problem reads them the same way.
QuasiStaticSettings scene_quasi_static_settings(const Scene& scene);

} // namespace kerf
