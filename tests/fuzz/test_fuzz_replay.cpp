// Replays the fuzzers' inputs through the readers in the normal test suite (g++, no clang).
//
// tests/fuzz/corpus/<reader>/ holds the seeds the fuzzers start from: small valid files (named
// valid_*, written by hand or, for .vtk, by VTK's own writer) and slightly malformed ones. tests/fuzz/regressions/<reader>/ holds every input
// a fuzzer found that crashed, hung or broke a promise, kept after the bug was fixed. Each one
// must now be either read into a valid mesh (or scene) or refused with an InputError; nothing
// else may escape (see feed_to_reader()).

#include "fuzz_inputs.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace fs = std::filesystem;

namespace {

/// The bytes of `file`, as they are.
std::string read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

/// Feeds every file of `folder` to `reader` and returns the files with their verdicts; each
/// file must get one (a missing folder holds none).
std::vector<std::pair<fs::path, kerf::fuzz::Verdict>> replay_folder(const kerf::fuzz::FuzzedReader& reader,
                                                                   const fs::path& folder) {
  std::vector<std::pair<fs::path, kerf::fuzz::Verdict>> verdicts;
  if (!fs::is_directory(folder)) return verdicts;
  for (const auto& entry : fs::directory_iterator(folder)) {
    if (!entry.is_regular_file()) continue;
    CAPTURE(entry.path());
    kerf::fuzz::Verdict verdict = kerf::fuzz::Verdict::rejected;
    REQUIRE_NOTHROW(verdict = kerf::fuzz::feed_to_reader(reader, read_bytes(entry.path())));
    verdicts.emplace_back(entry.path(), verdict);
  }
  return verdicts;
}

const fs::path fuzz_folder = fs::path(KERF_SOURCE_DIR) / "tests" / "fuzz";

} // namespace

TEST_CASE("every seed and regression input is read into a valid result or refused with an InputError") {
  for (const kerf::fuzz::FuzzedReader& reader : kerf::fuzz::fuzzed_readers()) {
    CAPTURE(reader.name);
    replay_folder(reader, fuzz_folder / "regressions" / reader.name);
    // A seed named valid_* is a good file and must be read; every other seed is broken on
    // purpose and must be refused. Both kinds are needed, or the fuzzer starts half blind.
    int valid = 0;
    int broken = 0;
    for (const auto& [file, verdict] : replay_folder(reader, fuzz_folder / "corpus" / reader.name)) {
      CAPTURE(file);
      const bool is_valid = file.filename().string().rfind("valid_", 0) == 0;
      ++(is_valid ? valid : broken);
      CHECK(verdict == (is_valid ? kerf::fuzz::Verdict::accepted : kerf::fuzz::Verdict::rejected));
    }
    CHECK(valid > 0);
    CHECK(broken > 0);
  }
}

TEST_CASE("the inputs that used to be read wrongly without a word are now refused") {
  // Crashes show up on their own; these were accepted with a value wrapped round to a valid
  // one, so only their verdict tells that the fix holds.
  for (const char* name : {"negative_steps_wrap_to_one.json", "node_index_wraps_to_zero.json"}) {
    CAPTURE(name);
    const std::string bytes = read_bytes(fuzz_folder / "regressions" / "scene" / name);
    CHECK(kerf::fuzz::feed_to_reader(kerf::fuzz::fuzzed_reader("scene"), bytes) ==
          kerf::fuzz::Verdict::rejected);
  }
  const std::string seed = read_bytes(fuzz_folder / "corpus" / "scene" / "big_integer.json");
  CHECK(kerf::fuzz::feed_to_reader(kerf::fuzz::fuzzed_reader("scene"), seed) ==
        kerf::fuzz::Verdict::rejected);
}

TEST_CASE("fuzzed_reader knows every reader by its corpus folder's name, and no other") {
  for (const auto& entry : fs::directory_iterator(fuzz_folder / "corpus"))
    CHECK_NOTHROW(kerf::fuzz::fuzzed_reader(entry.path().filename().string()));
  CHECK_THROWS_AS(kerf::fuzz::fuzzed_reader("ply"), std::invalid_argument);
}
