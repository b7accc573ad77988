/// @file scene_quadrature.hpp
/// @brief The scene's "quadrature" field as the rule every piece of a split tet is integrated with.
#pragma once

#include "kerf/scene/scene.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"

namespace kerf {

/// The rule named by `scene.quadrature.rule` (piece_quadrature_rule.hpp), at the degree the
/// model asks for. "volume_ratio" is refused for a Tet10 mesh (`order` 2): its stiffness
/// varies over a piece, so scaling the whole tet's integral by the piece's volume fraction is
/// wrong for it (Schoch et al.'s remark after eq. 63 does not hold); an InputError names
/// the scene file and "quadrature.rule".
PieceRuleFunction scene_piece_rule(const Scene& scene, int order);

} // namespace kerf
