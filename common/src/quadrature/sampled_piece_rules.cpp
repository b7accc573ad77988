#include "kerf/quadrature/sampled_piece_rules.hpp"

#include "kerf/cut/convex_cell.hpp"
#include "kerf/quadrature/polyhedron_moments.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace kerf {

namespace {

// The cells' face planes with unit normals, so that a plane's value is a distance.
struct CellPlanes {
  std::vector<std::vector<Plane>> planes; ///< per cell
  std::vector<int> piece;                 ///< per cell
  std::vector<Eigen::Vector3d> lo, hi;    ///< per cell, its bounding box widened by the tolerance: most cells
                                          ///< of a finely cut tet are small, and the box rejects them cheaply
  double tolerance = 0.0;                 ///< a distance below which a point counts as on a plane (m)
};

CellPlanes cell_planes(const TetPieces& pieces) {
  CellPlanes result;
  double diameter = 0.0;
  for (std::size_t c = 0; c < pieces.cells.size(); ++c) {
    std::vector<Plane> planes;
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = Eigen::Vector3d::Constant(-1e300);
    for (const CellFace& face : pieces.cells[c].faces)
      for (const Eigen::Vector3d& x : face.polygon) {
        lo = lo.cwiseMin(x);
        hi = hi.cwiseMax(x);
      }
    result.lo.push_back(lo);
    result.hi.push_back(hi);
    for (const CellFace& face : pieces.cells[c].faces) {
      const Eigen::Vector3d a = polygon_area_vector(face.polygon);
      const double norm = a.norm();
      if (norm == 0.0) continue;
      planes.push_back({a / norm, a.dot(face.polygon.front()) / norm});
      for (const Eigen::Vector3d& x : face.polygon) diameter = std::max(diameter, (x - face.polygon.front()).norm());
    }
    result.planes.push_back(std::move(planes));
    result.piece.push_back(pieces.cell_piece[c]);
  }
  // Round-off in a plane's value is some epsilon times the cell's size: 1e-12 of it is far
  // above that and far below any sampling spacing.
  result.tolerance = 1e-12 * diameter;
  for (std::size_t c = 0; c < result.lo.size(); ++c) {
    result.lo[c].array() -= result.tolerance;
    result.hi[c].array() += result.tolerance;
  }
  return result;
}

// The piece of the first cell that holds x; failing that, of the cell x is least outside of, if
// by no more than the tolerance (a point on a face that round-off puts outside both cells).
int piece_of_point(const CellPlanes& cells, const Eigen::Vector3d& x) {
  double least = 1e300;
  int best = -1;
  for (std::size_t c = 0; c < cells.planes.size(); ++c) {
    if ((x.array() < cells.lo[c].array()).any() || (x.array() > cells.hi[c].array()).any()) continue;
    double outside = -1e300;
    for (const Plane& plane : cells.planes[c]) outside = std::max(outside, plane.evaluate(x));
    if (outside <= 0.0) return cells.piece[c];
    if (outside < least) {
      least = outside;
      best = cells.piece[c];
    }
  }
  return least <= cells.tolerance ? best : -1;
}

} // namespace

int piece_of_point(const TetPieces& pieces, const Eigen::Vector3d& x) { return piece_of_point(cell_planes(pieces), x); }

PieceQuadratureRule lattice_rule(const Eigen::Matrix<double, 4, 3>& X, const TetPieces& pieces, int piece, int n) {
  if (n < 1) throw std::invalid_argument("lattice_rule: n must be >= 1");
  const CellPlanes cells = cell_planes(pieces);
  const ReferenceMap map(X);
  const double weight = pieces.volume / (static_cast<double>(n) * n * n);
  PieceQuadratureRule rule;
  // The reference tet is the image of the Kuhn simplex 1 >= y1 >= y2 >= y3 >= 0 under
  // xi = (y1 - y2, y2 - y3, y3). Scaled by n, that simplex is the union of the Kuhn simplices
  // t_s1 >= t_s2 >= t_s3 (s a permutation, t in [0, 1]^3 the local coordinates of lattice cube
  // (i, j, k)) that satisfy i + t1 >= j + t2 >= k + t3: all six when i > j > k, the three with
  // t1 >= t2 (or t2 >= t3) when i = j > k (or i > j = k), one when i = j = k. That is n^3
  // simplices, all of one volume; the centroid of simplex s is (3 e_s1 + 2 e_s2 + e_s3) / 4.
  static const int permutations[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int i = 0; i < n; ++i)
    for (int j = 0; j <= i; ++j)
      for (int k = 0; k <= j; ++k)
        for (const auto& s : permutations) {
          Eigen::Vector3d t = Eigen::Vector3d::Zero();
          t[s[0]] += 0.75;
          t[s[1]] += 0.5;
          t[s[2]] += 0.25;
          const Eigen::Vector3d y = (Eigen::Vector3d(i, j, k) + t) / n;
          if (!(y[0] >= y[1] && y[1] >= y[2])) continue; // this simplex lies outside the scaled Kuhn simplex
          const Eigen::Vector3d x = map.to_physical(Eigen::Vector3d(y[0] - y[1], y[1] - y[2], y[2]));
          if (piece_of_point(cells, x) != piece) continue;
          rule.points.push_back(x);
          rule.weights.push_back(weight);
        }
  return rule;
}

PieceQuadratureRule regular_rule(const Eigen::Matrix<double, 4, 3>& X, const TetPieces& pieces, int piece, int n) {
  if (n < 1) throw std::invalid_argument("regular_rule: n must be >= 1");
  const CellPlanes cells = cell_planes(pieces);
  const Eigen::Vector3d lo = X.colwise().minCoeff().transpose(), hi = X.colwise().maxCoeff().transpose();
  const Eigen::Vector3d h = (hi - lo) / n;
  const double weight = h.prod();
  PieceQuadratureRule rule;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const Eigen::Vector3d x = lo + Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5).cwiseProduct(h);
        if (piece_of_point(cells, x) != piece) continue;
        rule.points.push_back(x);
        rule.weights.push_back(weight);
      }
  return rule;
}

} // namespace kerf
