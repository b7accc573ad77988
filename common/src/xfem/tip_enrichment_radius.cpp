/// @file tip_enrichment_radius.cpp
/// @brief The default geometric enrichment radius: twice the mean edge of the tets the front crosses.
#include "kerf/xfem/tip_enrichment_radius.hpp"

namespace kerf {

double default_tip_enrichment_radius(const TetMesh& mesh, const CrackFronts& fronts) {
  if (fronts.empty() || mesh.tets.rows() == 0) return 0.0;
  // The mean edge length of the tets for which `take` says yes (0 if none).
  const auto mean_edge = [&mesh](auto take) {
    double edge_sum = 0.0;
    int edges = 0;
    for (Eigen::Index t = 0; t < mesh.tets.rows(); ++t) {
      const Eigen::Matrix<double, 4, 3> X = tet_corners(mesh, t);
      if (!take(X)) continue;
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j, ++edges) edge_sum += (X.row(i) - X.row(j)).norm();
    }
    return edges == 0 ? 0.0 : edge_sum / edges;
  };
  double h = mean_edge([&fronts](const Eigen::Matrix<double, 4, 3>& X) { return !front_in_tet(fronts, X).empty(); });
  // A front that crosses no tet (it lies on faces only) still gets a radius: the mean edge of the
  // whole mesh stands in for the local one.
  if (h == 0.0) h = mean_edge([](const Eigen::Matrix<double, 4, 3>&) { return true; });
  // Two rings of elements around the front: the first choice, to be replaced by what the
  // convergence study measures.
  return 2.0 * h;
}

} // namespace kerf
