/// @file probes_csv.hpp
/// @brief The probe contract: read points from `x,y,z` CSV, write `x,y,z,ux,uy,uz` CSV.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <ostream>

#include "kerf/mesh/tet_mesh.hpp"

namespace kerf {

/// Reads a probe file: a header line `x,y,z`, then one point per line (three numbers separated
/// by commas). Blank lines are skipped. Anything else is an InputError naming the file and line.
/// @return #P by 3 points
Eigen::MatrixXd read_probes_csv(const std::filesystem::path& file);

/// Writes `x,y,z,ux,uy,uz`, one row per point, with 17 significant digits so that the values
/// read back are the doubles Kerf computed; NaN (points outside the mesh) is written as `nan`.
void write_probes_csv(const std::filesystem::path& file, const Eigen::MatrixXd& points, const Eigen::MatrixXd& displacements);

/// The probe contract in one call: reads the points of `probes_in`, evaluates the displacement
/// field of `mesh` and `u` there (eq. 14; NaN outside the mesh) and writes `probes_out`. Points
/// outside the mesh are counted in one warning line.
void sample_probes(const std::filesystem::path& probes_in, const std::filesystem::path& probes_out, const TetMesh& mesh,
                   const Eigen::VectorXd& u, std::ostream* warnings);

} // namespace kerf
