// exact_moment_fitting_rule (moment_fitting.hpp): Koschier's moment fitting with exact moments,
// the rule "exact", in a file of its own, so that chapter 4's assignment can replace it
// (assignments/04_cut_quadrature/).
#include "kerf/quadrature/moment_fitting.hpp"

#include "kerf/quadrature/polyhedron_moments.hpp"

#include <cmath>

namespace kerf {

PieceQuadratureRule exact_moment_fitting_rule(const Eigen::Matrix<double, 4, 3>& X, const TetPieces& pieces, int piece,
                                              int degree) {
  const MomentFittingSystem& system = tet_moment_fitting_system(degree);
  const ReferenceMap map(X);
  // b_i = int_piece P_i = sum_k C_ik int_piece m_k, in reference coordinates.
  const Eigen::VectorXd monomial_moments =
      polyhedron_monomial_moments(reference_boundary(map, pieces.pieces[static_cast<std::size_t>(piece)]), degree);
  const Eigen::VectorXd w = fit_reference_weights(system, system.basis.coefficients * monomial_moments);
  PieceQuadratureRule rule;
  rule.points.reserve(system.points.size());
  for (std::size_t j = 0; j < system.points.size(); ++j) {
    rule.points.push_back(map.to_physical(system.points[j]));
    rule.weights.push_back(w[static_cast<Eigen::Index>(j)] * std::abs(map.det));
  }
  return rule;
}

} // namespace kerf
