/// @file write_vtu.hpp
/// @brief Write a mesh with point and cell fields to a ParaView .vtu file, and a time series to a .pvd file.
#pragma once

#include "kerf/mesh/tet_mesh.hpp"

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace kerf {

/// A field with one row per mesh node, e.g. the displacement (k = 3).
struct PointField {
  std::string name;       ///< the name ParaView shows
  Eigen::MatrixXd values; ///< #V by k, k components per node (1 for a scalar, 3 for a vector)
};

/// A field with one row per tetrahedron, e.g. the material id or whether the tet is cut.
struct CellField {
  std::string name;       ///< the name ParaView shows
  Eigen::MatrixXd values; ///< #T by k, k components per tet
};

/// Writes the mesh and its fields as a VTK XML unstructured grid that ParaView opens as it is:
/// Tet4 as VTK_TETRA, Tet10 as VTK_QUADRATIC_TETRA (Kerf's node order is VTK's), data in
/// binary appended, zlib-compressed form. The parent folder is created when missing.
///
/// @param file         the .vtu file to write
/// @param mesh         the mesh: #V by 3 nodes, #T by 4 or 10 tets
/// @param point_fields fields with #V rows each
/// @param cell_fields  fields with #T rows each
/// @throws std::invalid_argument when a field has the wrong number of rows, no columns or no
///         name (a bug in the calling program, not bad input)
/// @throws InputError `FILE: write: PROBLEM` when the file cannot be written
void write_vtu(const std::filesystem::path& file, const TetMesh& mesh,
               const std::vector<PointField>& point_fields,
               const std::vector<CellField>& cell_fields);

/// Writes a ParaView collection (.pvd) that plays a list of .vtu files as a time series.
///
/// The .vtu paths are given as the program opens them (absolute, or relative to the current
/// folder) and are written relative to the .pvd's folder, so that the output folder can be
/// moved or copied as a whole. The parent folder is created when missing.
///
/// @param file               the .pvd file to write
/// @param time_and_vtu_file  (time in seconds, .vtu file) for each frame, in playing order
/// @throws InputError `FILE: write: PROBLEM` when the file cannot be written
void write_pvd(const std::filesystem::path& file,
               const std::vector<std::pair<double, std::filesystem::path>>& time_and_vtu_file);

} // namespace kerf
