/// @file header_shapes.hpp
/// @brief A test input for the header filter: shapes written as in libigl.
#pragma once

#include <string>

namespace kerf_test {

/// Positions of the nodes, \#V by 3, and the tets, \#T by 4; a vector of 3\#V DOFs.
/// Left alone: `#V by 3` in a code span, \#V already escaped, and &#35; an entity.
///
/// @code
/// #include <iostream> // in a code block, # stays
/// @endcode
///
/// @param name a name, quoted in a comment: "#V"; the default argument below keeps its #
/// @return the number of \#V
int count_nodes(const std::string& name = "#V"); ///< trailing: \#V rows

/* A block comment with \#T, on
   two lines: \#T again. */
inline int count_tets() { return 0; } // \#T in a plain comment

} // namespace kerf_test
