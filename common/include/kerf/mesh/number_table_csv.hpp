/// @file number_table_csv.hpp
/// @brief The small CSV files of numbers Kerf reads: a fixed header, then rows of finite numbers.
///
/// The probe points (`x,y,z`, io/probes_csv.hpp) and the prescribed displacement fields of a
/// scene (`x,y,z,ux,uy,uz`, scene/displacement_file.hpp) are both such a table. The reader lives
/// on the ground floor, next to the mesh readers, because the scene (below io) needs it too.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <string>

namespace kerf {

/// Reads a CSV file whose first non-blank line is `header` (spaces around the commas allowed)
/// and whose other non-blank lines hold one finite number per column of the header.
/// Anything else - a missing file, another header, a row with too few or too many cells, a cell
/// that is not a number, `nan` or `inf` - is an InputError naming the file and the line.
/// @param header comma-separated column names, e.g. "x,y,z"
/// @param what   what the file is, for the message when it cannot be opened ("probe file")
/// @return #rows by #columns
Eigen::MatrixXd read_number_table_csv(const std::filesystem::path& file, const std::string& header, const std::string& what);

} // namespace kerf
