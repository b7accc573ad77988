/// @file probes_csv.hpp
/// @brief The probe contract: read points from `x,y,z` CSV, write `x,y,z,ux,uy,uz` CSV.
#pragma once

#include <Eigen/Core>
#include <filesystem>

namespace kerf {

/// Reads a probe file: a header line `x,y,z`, then one point per line (three numbers separated
/// by commas). Blank lines are skipped. Anything else is an InputError naming the file and line.
/// @return #P by 3 points
Eigen::MatrixXd read_probes_csv(const std::filesystem::path& file);

/// Writes `x,y,z,ux,uy,uz`, one row per point, with 17 significant digits so that the values
/// read back are the doubles Kerf computed; NaN (points outside the mesh) is written as `nan`.
void write_probes_csv(const std::filesystem::path& file, const Eigen::MatrixXd& points, const Eigen::MatrixXd& displacements);

} // namespace kerf
