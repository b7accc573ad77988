/// @file command_line.hpp
/// @brief The command line every chapter shares, and the one place that turns errors into exit codes.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>

namespace kerf {

/// What the user asked for on the command line (DESIGN.md's contract).
struct CommandLine {
  std::optional<std::filesystem::path> scene;       ///< --scene FILE.json; none: the chapter's demo
  std::optional<std::filesystem::path> probes_in;   ///< --probes IN.csv
  std::optional<std::filesystem::path> probes_out;  ///< --probes-out OUT.csv
  std::optional<std::filesystem::path> moments_out; ///< --moments-out FILE (chapter 4 on): the moments of every cut piece
  std::optional<std::filesystem::path> probes_history; ///< --probes-history FILE (chapter 6 on): the probes at every step
  std::filesystem::path out_dir = "output";         ///< --out DIR: where VTK files and CSV go
  std::optional<int> tets;                          ///< --tets N (chapter 7): the liver's size, overriding the scene's
  bool interactive = false;                         ///< --interactive (chapter 7): cut with the mouse in a window
  std::optional<std::filesystem::path> events;      ///< --events FILE.csv (chapter 7): play these mouse events into the window, then close it
  bool quiet = false;                               ///< --quiet: no progress lines
  bool help = false;                                ///< --help
};

/// Parses argv. Unknown options, missing values, --probes without --probes-out or
/// --probes-history, and either of those without --probes are InputErrors with the file name
/// "command line".
CommandLine parse_command_line(int argc, const char* const* argv);

/// The options that arrive with later chapters; a program that has not taught one refuses it.
struct CommandLineFeatures {
  bool moments_out = false; ///< --moments-out (chapter 4 on)
  bool probes_history = false; ///< --probes-history (chapter 6 on)
  bool organ = false;          ///< --tets and --interactive (chapter 7)
};

/// Runs `body` and turns every exception into one line on stderr and a non-zero exit status:
/// `PROGRAM: error: MESSAGE` and 2 for bad input (InputError), `PROGRAM: failed: MESSAGE` and 3
/// for a numerical failure or anything else; 0 when `body` returns. It is the one try/catch of
/// every program in Kerf, the tools with command lines of their own included
/// (examples/render_pieces.cpp).
int run_reporting_errors(const std::string& program, const std::function<void()>& body);

/// Parses the chapter command line and runs `body` on it through run_reporting_errors.
/// `--help` prints `usage` and returns 0. Every chapter's main() is a single call to this, so
/// the try/catch is written once. An option of a later chapter than `taught` allows is an
/// InputError.
int run_guarded(int argc, const char* const* argv, const std::string& program, const std::string& usage,
                const std::function<void(const CommandLine&)>& body, const CommandLineFeatures& taught = {});

} // namespace kerf
