/// @file piece_quadrature_rule.hpp
/// @brief A quadrature rule for one piece of a cut tet, in physical coordinates.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace kerf {

/// sum_q w_q f(x_q) for the integral of f over one piece of a cut tet.
///
/// Points and weights are physical (m, m^3). A point may lie outside the piece (moment fitting
/// places its points on the whole tet): the integrand is then the piece's smooth extension, the
/// polynomial that f is on the piece (Koschier eq. 16, corrected in the notes: evaluate every
/// enrichment with the value it has on this piece, wherever the point lies). XFEM evaluates
/// every piece as its own "phantom" element, which is that extension by construction.
struct PieceQuadratureRule {
  std::vector<Eigen::Vector3d> points; ///< x_q (m)
  std::vector<double> weights;         ///< w_q (m^3)
};

} // namespace kerf
