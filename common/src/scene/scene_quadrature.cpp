#include "kerf/scene/scene_quadrature.hpp"

#include "kerf/app/input_error.hpp"
#include "kerf/quadrature/piece_quadrature_rule.hpp"

namespace kerf {

PieceRuleFunction scene_piece_rule(const Scene& scene, int order) {
  const QuadratureRuleKind kind = parse_quadrature_rule_kind(scene.quadrature.rule);
  if (kind == QuadratureRuleKind::volume_ratio && order == 2)
    throw InputError(scene.source.string(), "quadrature.rule",
                     "\"volume_ratio\" is exact for Tet4 only: a Tet10's stiffness varies over a piece (use \"exact\" or \"subtets\")");
  return [kind](const Eigen::Matrix<double, 4, 3>& X, const TetPieces& pieces, int piece, int degree) {
    PieceRuleOptions options;
    options.degree = degree;
    return piece_quadrature_rule(kind, X, pieces.triangles, pieces, piece, options);
  };
}

} // namespace kerf
