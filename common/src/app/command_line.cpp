#include "kerf/app/command_line.hpp"

#include "kerf/app/input_error.hpp"

#include <exception>
#include <iostream>
#include <string>
#include <string_view>

namespace kerf {

CommandLine parse_command_line(int argc, const char* const* argv) {
  CommandLine options;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw InputError("command line", std::string(arg), "expected a value after it");
      return argv[++i];
    };
    if (arg == "--scene") options.scene = value();
    else if (arg == "--probes") options.probes_in = value();
    else if (arg == "--probes-out") options.probes_out = value();
    else if (arg == "--moments-out") options.moments_out = value();
    else if (arg == "--probes-history") options.probes_history = value();
    else if (arg == "--out") options.out_dir = value();
    else if (arg == "--tets") {
      const std::string text = value();
      std::size_t used = 0;
      long long n = -1;
      try {
        n = std::stoll(text, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != text.size() || n < 1 || n > 100'000'000)
        throw InputError("command line", "--tets", "expected a positive whole number of tets, got \"" + text + "\"");
      options.tets = static_cast<int>(n);
    } else if (arg == "--interactive") options.interactive = true;
    else if (arg == "--events") options.events = value();
    else if (arg == "--quiet") options.quiet = true;
    else if (arg == "--help" || arg == "-h") options.help = true;
    else throw InputError("command line", std::string(arg), "unknown option (see --help)");
  }
  if (options.probes_in.has_value() != (options.probes_out || options.probes_history))
    throw InputError("command line", "--probes", "--probes and --probes-out (or --probes-history) go together");
  return options;
}

int run_reporting_errors(const std::string& program, const std::function<void()>& body) {
  try {
    body();
    return 0;
  } catch (const InputError& error) {
    std::cerr << program << ": error: " << error.what() << '\n';
    return 2;
  } catch (const std::exception& error) {
    std::cerr << program << ": failed: " << error.what() << '\n';
    return 3;
  }
}

int run_guarded(int argc, const char* const* argv, const std::string& program, const std::string& usage,
                const std::function<void(const CommandLine&)>& body, const CommandLineFeatures& taught) {
  return run_reporting_errors(program, [&] {
    const CommandLine options = parse_command_line(argc, argv);
    if (options.moments_out && !taught.moments_out)
      throw InputError("command line", "--moments-out", "the moments of cut pieces are taught from chapter 4 on (04_cut_quadrature)");
    if (options.probes_history && !taught.probes_history)
      throw InputError("command line", "--probes-history", "the probes over time are taught from chapter 6 on (06_newmark)");
    if ((options.tets || options.interactive || options.events) && !taught.organ)
      throw InputError("command line", options.tets ? "--tets" : options.events ? "--events" : "--interactive",
                       "the liver and its blade come with chapter 7 (07_liver)");
    if (options.events && !options.interactive)
      throw InputError("command line", "--events", "plays mouse events into the --interactive window: give --interactive too");
    if (options.help) {
      std::cout << usage;
      return;
    }
    body(options);
  });
}

} // namespace kerf
