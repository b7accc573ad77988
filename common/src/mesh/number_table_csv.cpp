#include "kerf/mesh/number_table_csv.hpp"

#include "kerf/app/input_error.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

namespace kerf {

namespace {

std::string trim(const std::string& s) {
  const auto begin = s.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return "";
  const auto end = s.find_last_not_of(" \t\r");
  return s.substr(begin, end - begin + 1);
}

} // namespace

Eigen::MatrixXd read_number_table_csv(const std::filesystem::path& file, const std::string& header, const std::string& what) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string(), "file", "cannot open the " + what);
  const auto columns = static_cast<int>(std::count(header.begin(), header.end(), ',')) + 1;
  const std::string expected_row = "expected " + std::to_string(columns) + " finite numbers " + header;
  std::string line;
  int line_number = 0;
  std::string first;
  while (first.empty() && std::getline(in, line)) {
    ++line_number;
    first = trim(line);
  }
  std::string compact;
  for (char c : first)
    if (c != ' ' && c != '\t') compact += c;
  if (compact != header) throw InputError(file.string(), "line " + std::to_string(line_number), "expected the header " + header);
  std::vector<double> values;
  while (std::getline(in, line)) {
    ++line_number;
    if (trim(line).empty()) continue;
    std::stringstream row(line);
    std::string cell;
    int count = 0;
    while (std::getline(row, cell, ',')) {
      cell = trim(cell);
      std::size_t used = 0;
      double value = 0.0;
      try {
        value = std::stod(cell, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || used != cell.size() || !std::isfinite(value) || count >= columns)
        throw InputError(file.string(), "line " + std::to_string(line_number), expected_row);
      values.push_back(value);
      ++count;
    }
    // A trailing comma leaves an empty last cell that getline does not return: count it too.
    if (count != columns || trim(line).back() == ',') throw InputError(file.string(), "line " + std::to_string(line_number), expected_row);
  }
  const auto rows = static_cast<Eigen::Index>(values.size()) / columns;
  return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(values.data(), rows, columns);
}

} // namespace kerf
