/// @file cholmod_ordering.hpp
/// @brief The names of CholmodSolver's fill-reducing orderings, which the scene checks its field against.
#pragma once

#include <string>

namespace kerf {

/// Whether `name` is one of CholmodSolver's orderings: "nested-dissection", "metis", "amd" or
/// "cholmod" (cholmod_solver.hpp says what each does). A header of its own, so that checking
/// a scene needs no CHOLMOD: the scene parser's fuzz target is built without it.
bool is_cholmod_ordering(const std::string& name);

} // namespace kerf
