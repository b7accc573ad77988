#include "kerf/quadrature/gauss_piece_rules.hpp"

#include "kerf/cut/convex_cell.hpp"
#include "kerf/fem/tet_quadrature.hpp"
#include "kerf/quadrature/polyhedron_moments.hpp"

#include <Eigen/LU>
#include <cmath>

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

PieceQuadratureRule volume_ratio_rule(const Eigen::Matrix<double, 4, 3>& X, const TetPieces& pieces, int piece, int degree) {
  PieceQuadratureRule rule;
  append_mapped_rule(tet_quadrature_rule(degree), X, pieces.pieces[static_cast<std::size_t>(piece)].volume / pieces.volume, rule);
  return rule;
}

PieceQuadratureRule subtet_rule(const TetPieces& pieces, int piece, int degree) {
  const TetQuadratureRule reference = tet_quadrature_rule(degree);
  PieceQuadratureRule rule;
  for (int c : pieces.pieces[static_cast<std::size_t>(piece)].cells)
    for (const Eigen::Matrix<double, 4, 3>& T : convex_cell_tetrahedra(pieces.cells[static_cast<std::size_t>(c)]))
      append_mapped_rule(reference, T, 1.0, rule);
  return rule;
}

} // namespace kerf
