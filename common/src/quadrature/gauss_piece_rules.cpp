#include "kerf/quadrature/gauss_piece_rules.hpp"

#include "kerf/cut/convex_cell.hpp"
#include "kerf/fem/tet_quadrature.hpp"
#include "kerf/quadrature/polyhedron_moments.hpp"

#include <Eigen/LU>
#include <array>
#include <cmath>
#include <stdexcept>

namespace kerf {

namespace {
// The reference rule mapped onto the tet T: x = T0 + J xi, w = w_ref |det J| (the reference
// tet's weights sum to 1/6, its volume).
void append_mapped_rule(const TetQuadratureRule& reference, const Eigen::Matrix<double, 4, 3>& T, double scale,
                        PieceQuadratureRule& rule) {
  // A fan over a face with collinear corners has tets of no volume: they hold no integral.
  Eigen::Matrix3d J;
  for (int i = 0; i < 3; ++i) J.col(i) = (T.row(i + 1) - T.row(0)).transpose();
  if (J.determinant() == 0.0) return;
  const ReferenceMap map(T);
  for (std::size_t q = 0; q < reference.points.size(); ++q) {
    rule.points.push_back(map.to_physical(reference.points[q]));
    rule.weights.push_back(reference.weights[q] * std::abs(map.det) * scale);
  }
}

} // namespace

std::vector<Eigen::Matrix<double, 4, 3>> refine_tet(const Eigen::Matrix<double, 4, 3>& T) {
  const auto mid = [&T](int i, int j) { return Eigen::RowVector3d(0.5 * (T.row(i) + T.row(j))); };
  const Eigen::RowVector3d x0 = T.row(0), x1 = T.row(1), x2 = T.row(2), x3 = T.row(3);
  const Eigen::RowVector3d m01 = mid(0, 1), m02 = mid(0, 2), m03 = mid(0, 3), m12 = mid(1, 2), m13 = mid(1, 3), m23 = mid(2, 3);
  const std::array<std::array<Eigen::RowVector3d, 4>, 8> children{{{x0, m01, m02, m03},
                                                                   {m01, x1, m12, m13},
                                                                   {m02, m12, x2, m23},
                                                                   {m03, m13, m23, x3},
                                                                   {m01, m02, m03, m13},
                                                                   {m01, m02, m12, m13},
                                                                   {m02, m03, m13, m23},
                                                                   {m02, m12, m13, m23}}};
  std::vector<Eigen::Matrix<double, 4, 3>> result;
  for (const auto& c : children) {
    Eigen::Matrix<double, 4, 3> C;
    for (int k = 0; k < 4; ++k) C.row(k) = c[static_cast<std::size_t>(k)];
    result.push_back(C);
  }
  return result;
}

PieceQuadratureRule volume_ratio_rule(const Eigen::Matrix<double, 4, 3>& X, const TetPieces& pieces, int piece, int degree) {
  PieceQuadratureRule rule;
  append_mapped_rule(tet_quadrature_rule(degree), X, pieces.pieces[static_cast<std::size_t>(piece)].volume / pieces.volume, rule);
  return rule;
}

void append_cell_gauss_rule(const ConvexCell& cell, int degree, PieceQuadratureRule& rule) {
  const TetQuadratureRule reference = tet_quadrature_rule(degree);
  for (const Eigen::Matrix<double, 4, 3>& T : convex_cell_tetrahedra(cell)) append_mapped_rule(reference, T, 1.0, rule);
}

PieceQuadratureRule subtet_rule(const TetPieces& pieces, int piece, int degree) {
  PieceQuadratureRule rule;
  for (int c : pieces.pieces[static_cast<std::size_t>(piece)].cells)
    append_cell_gauss_rule(pieces.cells[static_cast<std::size_t>(c)], degree, rule);
  return rule;
}

PieceQuadratureRule refined_subtet_rule(const TetPieces& pieces, int piece, int degree, int refinements) {
  if (refinements < 0) throw std::invalid_argument("refined_subtet_rule: refinements must be >= 0");
  const TetQuadratureRule reference = tet_quadrature_rule(degree);
  PieceQuadratureRule rule;
  for (int c : pieces.pieces[static_cast<std::size_t>(piece)].cells) {
    std::vector<Eigen::Matrix<double, 4, 3>> tets = convex_cell_tetrahedra(pieces.cells[static_cast<std::size_t>(c)]);
    for (int level = 0; level < refinements; ++level) {
      std::vector<Eigen::Matrix<double, 4, 3>> finer;
      for (const Eigen::Matrix<double, 4, 3>& T : tets)
        for (const Eigen::Matrix<double, 4, 3>& child : refine_tet(T)) finer.push_back(child);
      tets = std::move(finer);
    }
    for (const Eigen::Matrix<double, 4, 3>& T : tets) append_mapped_rule(reference, T, 1.0, rule);
  }
  return rule;
}

} // namespace kerf
