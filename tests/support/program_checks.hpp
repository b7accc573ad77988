// What the tests of a chapter's program share: running it (under xvfb-run where it draws),
// reading what it printed and wrote, and checking a refusal.
#pragma once

#include "support/run_program.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace kerf_test {

// A path in single quotes for the shell. (Built by appending: g++ 12 warns, wrongly, about
// "'" + path.string() with -Wrestrict.)
inline std::string quoted(const std::filesystem::path& path) {
  std::string text = "'";
  text += path.string();
  text += '\'';
  return text;
}

// The program under xvfb-run (a display for its window and its frames). The suite itself runs
// without one; tests/CMakeLists.txt passes the path it found. Without it the case fails, saying
// so: a window test that skipped itself would let a broken window through.
inline std::string with_display(const std::string& command) {
  const std::string xvfb_run = KERF_XVFB_RUN; // "KERF_XVFB_RUN-NOTFOUND" when CMake found none
  REQUIRE_MESSAGE(std::filesystem::exists(xvfb_run), "xvfb-run not found: install xvfb, then reconfigure");
  return xvfb_run + " -a " + command;
}

// The number written after `key` in the program's output (e.g. "cut: " -> the tets crossed).
inline double number_after(const std::string& text, const std::string& key) {
  const std::size_t at = text.find(key);
  REQUIRE_MESSAGE(at != std::string::npos, "no \"" << key << "\" in the output");
  return std::stod(text.substr(at + key.size()));
}

// stderr without the one warning VTK 9.1 writes whenever a window's interactor is made without its
// InteractionStyle module ("vtkInteractorStyleSwitchBase ... Link to vtkInteractionStyle"), which
// chapters 7 and 8 leave out on purpose (render/cutting_window.hpp): every --interactive run has it.
inline std::string without_style_warning(const std::string& err) {
  std::istringstream lines(err);
  std::string line, kept;
  while (std::getline(lines, line))
    if (line.find("vtkInteractorStyleSwitchBase") == std::string::npos) kept += line + "\n";
  return kept;
}

// A failed run's report: exit status 2 (an InputError) and one line on stderr naming `field`.
inline void check_refused(const ProgramResult& result, const std::string& field) {
  INFO("field ", field, "; stderr: ", result.err);
  CHECK(result.exit_status == 2);
  CHECK(result.err.find(field) != std::string::npos);
  CHECK(std::count(result.err.begin(), result.err.end(), '\n') == 1);
}

// The chunks of a PNG file by type, in order (the 8-byte signature checked).
inline std::vector<std::pair<std::string, std::string>> png_chunks(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  REQUIRE(bytes.size() >= 8);
  REQUIRE(bytes.substr(0, 8) == std::string("\x89PNG\r\n\x1a\n", 8));
  const auto big_endian = [&](std::size_t at) {
    std::uint32_t value = 0;
    for (std::size_t k = 0; k < 4; ++k) value = (value << 8) | static_cast<unsigned char>(bytes[at + k]);
    return value;
  };
  std::vector<std::pair<std::string, std::string>> chunks;
  for (std::size_t at = 8; at + 12 <= bytes.size();) {
    const std::uint32_t length = big_endian(at);
    REQUIRE(at + 12 + length <= bytes.size());
    chunks.emplace_back(bytes.substr(at + 4, 4), bytes.substr(at + 8, length));
    at += 12 + length;
  }
  return chunks;
}

inline std::uint32_t big_endian_32(const std::string& data, std::size_t at) {
  std::uint32_t value = 0;
  for (std::size_t k = 0; k < 4; ++k) value = (value << 8) | static_cast<unsigned char>(data.at(at + k));
  return value;
}

} // namespace kerf_test
