/// @file fuzz_inputs.hpp
/// @brief Feed arbitrary bytes to one of Kerf's file readers, as a fuzzer and the replay test do.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace kerf::fuzz {

/// One reader of user files that is fuzzed: its name (also the folder of its corpus under
/// tests/fuzz/corpus/ and tests/fuzz/regressions/) and the extension that selects it.
struct FuzzedReader {
  std::string name;      ///< "gmsh", "vtk", "vtu", "medit", "scene" or "surface_obj", "surface_stl", ...
  std::string extension; ///< ".msh", ".vtk", ".vtu", ".mesh", ".json" or ".obj", ".stl", ...
};

/// Every fuzzed reader: the four mesh formats of read_mesh(), the scene parser, and the cut
/// surface formats of read_surface() that Kerf parses itself (OBJ, STL, OFF) or checks before
/// VTK does (legacy .vtk polydata).
std::vector<FuzzedReader> fuzzed_readers();

/// The reader called `name`; std::invalid_argument if there is none.
FuzzedReader fuzzed_reader(std::string_view name);

/// Thrown when a reader accepted an input but what it returned breaks the reader's promise
/// (a non-finite coordinate, a node index out of range, ...): a bug in the reader.
class BrokenPromise : public std::logic_error {
public:
  using std::logic_error::logic_error;
};

/// What a reader made of one input.
enum class Verdict {
  accepted, ///< read, and the result passed our own checks
  rejected, ///< refused with an InputError, which is what bad input must get
};

/// Hands `bytes` to `reader` the way a user's file would reach it and checks the outcome.
///
/// The mesh readers read files by path, so the bytes go to a scratch file with the reader's
/// extension (named after the process, so that parallel runs do not collide) which is removed
/// afterwards; the scene parser takes the text directly. An InputError is the expected answer
/// to bad input and gives Verdict::rejected. An accepted mesh must have at least one tet, 4 or
/// 10 nodes per tet, finite coordinates and indices in [0, #V); an accepted surface a triangle,
/// finite coordinates, indices in [0, #V), and be left unchanged by a second check; an accepted
/// scene finite numbers and the ranges its reference promises. Otherwise BrokenPromise is thrown, and any
/// other exception (std::bad_alloc, nlohmann's, ...) escapes: both are bugs to fix.
Verdict feed_to_reader(const FuzzedReader& reader, std::string_view bytes);

} // namespace kerf::fuzz
