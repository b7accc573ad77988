/// @file input_error.hpp
/// @brief The one exception type for bad input: it names the file, the field and what was expected.
#pragma once

#include <stdexcept>
#include <string>

namespace kerf {

/// Thrown for anything a user can get wrong in a file or on the command line.
///
/// The message is always one line of the form `FILE: FIELD: PROBLEM`, so that the
/// command line (app/run_guarded.hpp) can print it as it is and exit with a non-zero status.
/// We never let bad input reach the numerics: a NaN coordinate or a zero-volume tet is
/// rejected here, with its index, before it can turn into a silent NaN in a solution.
class InputError : public std::runtime_error {
public:
  /// @param file  the file (or "command line", or "scene") the problem was found in
  /// @param field the field, section or line that is wrong, e.g. "material.young" or "line 17"
  /// @param problem what was expected and what was found instead
  InputError(const std::string& file, const std::string& field, const std::string& problem)
      : std::runtime_error(file + ": " + field + ": " + problem) {}
};

} // namespace kerf
