/* Kerf measurement helpers shared by the benchmarks (bench/) and the chapter studies (examples/).

   They live in one header so that every program times its work the same way and stamps its
   report with the same machine description; a fix to one of them then reaches all of them.
   Header-only on purpose: these are a few small functions, and a library target for them
   would cost more to read than they do. */

#pragma once

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace kerf_measure {

/// The clock every measurement uses: steady, because the wall clock may jump while we time.
using clock = std::chrono::steady_clock;

/// How often best_time repeats a piece of work. Each program states its own rule, because the
/// rule is part of what its report says ("best of >= 3 runs and >= 0.5 s").
struct Repeats {
  int min_repeats;          ///< run at least this many times ...
  double min_total_seconds; ///< ... and for at least this long in total ...
  double max_total_seconds; ///< ... but stop once this much time has gone by.
};

/// The shortest of repeated runs of `work`: at least `repeats.min_repeats` runs and at least
/// `repeats.min_total_seconds` of them, unless one run alone is so long (over
/// `repeats.max_total_seconds` spent) that more would only cost time. The minimum, not the
/// mean: it is what the work costs, the rest is noise from the machine.
template <class Work>
double best_time(Work&& work, const Repeats& repeats) {
  double best = 1e300, total = 0.0;
  for (int r = 0; r < repeats.min_repeats || total < repeats.min_total_seconds; ++r) {
    const auto start = clock::now();
    work();
    const double t = std::chrono::duration<double>(clock::now() - start).count();
    best = std::min(best, t);
    total += t;
    if (total > repeats.max_total_seconds) break;
  }
  return best;
}

/// The CPU's name from /proc/cpuinfo, or "unknown". Reports carry it because a time means
/// nothing without the machine that took it.
inline std::string cpu_model() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);)
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown";
}

/// Today's date and time, YYYY-MM-DD HH:MM, to tell one report from the next.
inline std::string now_text() {
  const std::time_t t = std::time(nullptr);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%d %H:%M", std::localtime(&t));
  return text;
}

/// The value of an environment variable, or "unset". Reports print the BLAS thread counts
/// with it, since a second thread would change the numbers.
inline std::string environment(const char* name) {
  const char* value = std::getenv(name);
  return value ? value : "unset";
}

/// A report's lines about the machine and its threads: the CPU, the date, and the BLAS and OpenMP
/// thread counts (a second thread would change the numbers).
inline std::string machine_lines() {
  return "- CPU: " + cpu_model() + "\n- date: " + now_text() + "\n- threads: OPENBLAS_NUM_THREADS=" +
         environment("OPENBLAS_NUM_THREADS") + ", OMP_NUM_THREADS=" + environment("OMP_NUM_THREADS") + "\n";
}

/// Writes a report to `out` (FILE.md) and its rows to FILE.csv beside it; nothing if `out` is empty.
inline void write_report(const std::filesystem::path& out, const std::string& report, const std::string& csv) {
  if (out.empty()) return;
  std::ofstream(out) << report;
  std::filesystem::path csv_path = out;
  std::ofstream(csv_path.replace_extension(".csv")) << csv;
}

/// What every benchmark and study takes on its command line.
struct RunOptions {
  bool quick = false;        ///< --quick: tiny sizes, every code path, a few seconds
  std::filesystem::path out; ///< --out PATH: where the program writes its results
  std::string only;          ///< --only A,B: the parts to run (comma-separated); all by default

  /// Whether part `name` runs: it is listed in --only, or --only was not given.
  bool runs(const std::string& name) const {
    return only.empty() || ("," + only + ",").find("," + name + ",") != std::string::npos;
  }
};

/// Reads `[--quick] [--out PATH] [--only PARTS]` from the command line. `out` starts as
/// `default_out` (empty means "no file"); `--only` is accepted only if `parts` (the program's
/// part names) is not empty, and every name it lists must be one of them. On anything else it
/// prints "usage: <usage>" to stderr and returns nothing: the caller then exits with code 2, the
/// usual code for a bad command line.
inline std::optional<RunOptions> parse_run_options(int argc, char** argv, const std::string& usage,
                                                   const std::filesystem::path& default_out,
                                                   const std::vector<std::string>& parts = {}) {
  RunOptions options;
  options.out = default_out;
  const auto known_parts = [&](const std::string& list) {
    std::istringstream names(list);
    std::string name;
    bool any = false;
    while (std::getline(names, name, ',')) {
      if (std::find(parts.begin(), parts.end(), name) == parts.end()) return false;
      any = true;
    }
    return any;
  };
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--quick")
      options.quick = true;
    else if (arg == "--out" && i + 1 < argc)
      options.out = argv[++i];
    else if (arg == "--only" && i + 1 < argc && known_parts(argv[i + 1]))
      options.only = argv[++i];
    else {
      std::cerr << "usage: " << usage << '\n';
      return std::nullopt;
    }
  }
  return options;
}

} // namespace kerf_measure
