/// @file probes_csv.hpp
/// @brief The probe contract: read points from `x,y,z` CSV, write `x,y,z,ux,uy,uz` CSV.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <functional>
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

/// A displacement field known tet by tet: its value at x (m) in tet t. Cut bodies (chapters 3
/// and 4) evaluate it on the piece of t that holds x.
using TetField = std::function<Eigen::Vector3d(Eigen::Index t, const Eigen::Vector3d& x)>;

/// `field` at each point (rows of `points`), in the tet of `mesh` that holds it; NaN rows for
/// points outside the mesh, counted in num_outside.
Eigen::MatrixXd evaluate_tet_field_at(const TetMesh& mesh, const TetField& field, const Eigen::MatrixXd& points,
                                      Eigen::Index& num_outside);

/// The probe contract for a field known tet by tet (a cut body): reads `probes_in`, writes
/// `field` there to `probes_out`, and counts the points outside the mesh in one warning line.
void sample_tet_field_probes(const std::filesystem::path& probes_in, const std::filesystem::path& probes_out,
                             const TetMesh& mesh, const TetField& field, std::ostream* warnings);

/// --probes-history's rows for one step: `step,t,probe,ux,uy,uz`, one per row of `values` (the
/// displacements at the probes, evaluate_tet_field_at), probe 0-based, full precision.
void write_probe_history_rows(std::ostream& out, int step, double t, const Eigen::MatrixXd& values);

} // namespace kerf
