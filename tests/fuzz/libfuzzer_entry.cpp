// The libFuzzer entry point of one fuzz target (built only with KERF_FUZZ=ON and clang).
//
// The build compiles this file once per reader, with KERF_FUZZED_READER naming it ("gmsh",
// "vtk", ...). libFuzzer calls LLVMFuzzerTestOneInput with each input it makes up; an exception
// that escapes feed_to_reader() (a BrokenPromise, a std::bad_alloc, ...) ends in std::terminate,
// which libFuzzer reports as a crash and saves the input that caused it.

#include "fuzz_inputs.hpp"

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // Looked up on every call rather than kept in a static: it costs nothing next to a file read.
  const kerf::fuzz::FuzzedReader reader = kerf::fuzz::fuzzed_reader(KERF_FUZZED_READER);
  kerf::fuzz::feed_to_reader(reader, std::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}
