// Runs a program from a test and captures its exit status, stdout and stderr.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <vector>

namespace kerf_test {

struct ProgramResult {
  int exit_status = -1;
  std::string out, err;
};

inline std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Runs `command` through the shell with stdout and stderr sent to files in `work_dir`.
inline ProgramResult run_program(const std::string& command, const std::filesystem::path& work_dir) {
  std::filesystem::create_directories(work_dir);
  const auto out = work_dir / "stdout.txt", err = work_dir / "stderr.txt";
  const std::string full = command + " > '" + out.string() + "' 2> '" + err.string() + "' < /dev/null";
  const int raw = std::system(full.c_str());
  ProgramResult result;
  result.exit_status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  result.out = read_text(out);
  result.err = read_text(err);
  return result;
}

/// The rows of a CSV file of numbers, its header line in `header`.
inline std::vector<std::vector<double>> read_csv_rows(const std::filesystem::path& file, std::string& header) {
  std::stringstream in(read_text(file));
  std::string line;
  std::getline(in, header);
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::stringstream cells(line);
    std::string cell;
    std::vector<double> row;
    while (std::getline(cells, cell, ',')) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

/// Writes `text` to `file`, creating its folder.
inline void write_text(const std::filesystem::path& file, const std::string& text) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream(file) << text;
}

/// A fresh, empty folder for one test under the current working directory (the build tree).
inline std::filesystem::path fresh_dir(const std::string& name) {
  const auto dir = std::filesystem::current_path() / "work" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

} // namespace kerf_test
