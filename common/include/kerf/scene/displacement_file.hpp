/// @file displacement_file.hpp
/// @brief A prescribed displacement field read from a file: the `"displacement_file"` of a Dirichlet entry.
///
/// Chapter 5 validates its crack-tip model against a field known in closed form (Williams's
/// near-front field): the field is written at the boundary nodes of a slab into a CSV file, and
/// the scene prescribes it there. Each node of the entry's region takes the row at its position.
#pragma once

#include "kerf/mesh/tet_mesh.hpp"

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

namespace kerf {

/// The rows of a displacement file (header `x,y,z,ux,uy,uz`, every number finite).
struct DisplacementFile {
  std::filesystem::path file;    ///< where it was read from (for messages)
  Eigen::MatrixXd positions;     ///< #R by 3: x, y, z of each row (m)
  Eigen::MatrixXd displacements; ///< #R by 3: ux, uy, uz of each row (m)
};

/// Reads a displacement file. A malformed file (another header, a row without six finite
/// numbers) is an InputError naming the file and the line.
DisplacementFile read_displacement_file(const std::filesystem::path& file);

/// The displacement `table` gives each of `nodes` of `mesh`: the row nearest to the node among
/// those within region_tolerance(mesh) of it in every coordinate (the tolerance of a region's
/// box). A node with no such row is an InputError naming the file and the node; `entry` names
/// the scene and the Dirichlet entry that asked, e.g. "dirichlet[1] of slab.json".
/// @return one displacement per node, in the order of `nodes`
std::vector<Eigen::Vector3d> displacements_from_file(const DisplacementFile& table, const TetMesh& mesh, const std::vector<int>& nodes,
                                                     const std::string& entry);

} // namespace kerf
