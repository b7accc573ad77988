#include "kerf/scene/displacement_file.hpp"

#include "kerf/app/input_error.hpp"
#include "kerf/mesh/node_region.hpp"
#include "kerf/mesh/number_table_csv.hpp"

#include <algorithm>
#include <numeric>
#include <sstream>

namespace kerf {

DisplacementFile read_displacement_file(const std::filesystem::path& file) {
  const Eigen::MatrixXd rows = read_number_table_csv(file, "x,y,z,ux,uy,uz", "displacement file");
  return {file, rows.leftCols<3>(), rows.rightCols<3>()};
}

std::vector<Eigen::Vector3d> displacements_from_file(const DisplacementFile& table, const TetMesh& mesh, const std::vector<int>& nodes,
                                                     const std::string& entry) {
  const double tolerance = region_tolerance(mesh);
  // The rows sorted by x: the candidates for a node are the rows with |x_row - x_node| <= tol,
  // one binary search away, so matching V nodes to R rows costs O((V + R) log R), not O(V R).
  std::vector<Eigen::Index> by_x(static_cast<std::size_t>(table.positions.rows()));
  std::iota(by_x.begin(), by_x.end(), Eigen::Index{0});
  std::sort(by_x.begin(), by_x.end(), [&](Eigen::Index i, Eigen::Index j) { return table.positions(i, 0) < table.positions(j, 0); });
  std::vector<Eigen::Vector3d> values;
  values.reserve(nodes.size());
  for (const int v : nodes) {
    const Eigen::Vector3d X = mesh.nodes.row(v).transpose();
    auto candidate = std::lower_bound(by_x.begin(), by_x.end(), X.x() - tolerance,
                                      [&](Eigen::Index i, double x) { return table.positions(i, 0) < x; });
    Eigen::Index best = -1;
    double best_distance = tolerance;
    for (; candidate != by_x.end() && table.positions(*candidate, 0) <= X.x() + tolerance; ++candidate) {
      const double distance = (table.positions.row(*candidate).transpose() - X).lpNorm<Eigen::Infinity>();
      if (distance <= best_distance) {
        best = *candidate;
        best_distance = distance;
      }
    }
    if (best < 0) {
      std::ostringstream problem;
      problem.precision(17);
      problem << "no row at the node's position (" << X.x() << ", " << X.y() << ", " << X.z() << ") within " << tolerance
              << " m (1e-9 of the mesh's diagonal); " << entry << " needs a row for every node of its region";
      throw InputError(table.file.string(), "node " + std::to_string(v), problem.str());
    }
    values.push_back(table.displacements.row(best).transpose());
  }
  return values;
}

} // namespace kerf
