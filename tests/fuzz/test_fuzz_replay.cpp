// Replays the fuzzers' inputs through the readers in the normal test suite (g++, no clang).
//
// tests/fuzz/corpus/<reader>/ holds the seeds the fuzzers start from: small valid files and
// slightly malformed ones, written by hand. tests/fuzz/regressions/<reader>/ holds every input
// a fuzzer found that crashed, hung or broke a promise, kept after the bug was fixed. Each one
// must now be either read into a valid mesh (or scene) or refused with an InputError; nothing
// else may escape (see feed_to_reader()).

#include "fuzz_inputs.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace {

/// The bytes of `file`, as they are.
std::string read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

/// How many of the inputs in `folder` were accepted and rejected (a missing folder holds none).
struct Tally {
  int accepted = 0;
  int rejected = 0;
};

/// Feeds every file of `folder` to `reader`, checking that each gets a verdict.
Tally replay_folder(const kerf::fuzz::FuzzedReader& reader, const fs::path& folder) {
  Tally tally;
  if (!fs::is_directory(folder)) return tally;
  for (const auto& entry : fs::directory_iterator(folder)) {
    if (!entry.is_regular_file()) continue;
    CAPTURE(entry.path());
    kerf::fuzz::Verdict verdict = kerf::fuzz::Verdict::rejected;
    REQUIRE_NOTHROW(verdict = kerf::fuzz::feed_to_reader(reader, read_bytes(entry.path())));
    ++(verdict == kerf::fuzz::Verdict::accepted ? tally.accepted : tally.rejected);
  }
  return tally;
}

const fs::path fuzz_folder = fs::path(KERF_SOURCE_DIR) / "tests" / "fuzz";

} // namespace

TEST_CASE("every seed and regression input is read into a valid result or refused with an InputError") {
  for (const kerf::fuzz::FuzzedReader& reader : kerf::fuzz::fuzzed_readers()) {
    CAPTURE(reader.name);
    const Tally seeds = replay_folder(reader, fuzz_folder / "corpus" / reader.name);
    replay_folder(reader, fuzz_folder / "regressions" / reader.name);
    // The seeds must reach both ends of the reader, or the fuzzer starts half blind.
    CHECK(seeds.accepted > 0);
    CHECK(seeds.rejected > 0);
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
  CHECK_THROWS_AS(kerf::fuzz::fuzzed_reader("stl"), std::invalid_argument);
}
