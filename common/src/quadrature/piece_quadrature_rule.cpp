#include "kerf/quadrature/piece_quadrature_rule.hpp"

#include "kerf/quadrature/gauss_piece_rules.hpp"
#include "kerf/quadrature/koschier_moment_fitting.hpp"
#include "kerf/quadrature/moment_fitting.hpp"
#include "kerf/quadrature/sampled_piece_rules.hpp"

#include <stdexcept>

namespace kerf {

const char* to_string(QuadratureRuleKind kind) {
  switch (kind) {
  case QuadratureRuleKind::exact: return "exact";
  case QuadratureRuleKind::subtets: return "subtets";
  case QuadratureRuleKind::moment_fitting: return "moment_fitting";
  case QuadratureRuleKind::volume_ratio: return "volume_ratio";
  case QuadratureRuleKind::lattice: return "lattice";
  case QuadratureRuleKind::regular: return "regular";
  }
  return "unknown";
}

QuadratureRuleKind parse_quadrature_rule_kind(const std::string& name) {
  for (QuadratureRuleKind kind : {QuadratureRuleKind::exact, QuadratureRuleKind::subtets, QuadratureRuleKind::moment_fitting,
                                  QuadratureRuleKind::volume_ratio, QuadratureRuleKind::lattice, QuadratureRuleKind::regular})
    if (name == to_string(kind)) return kind;
  throw std::invalid_argument("unknown quadrature rule \"" + name +
                              "\" (expected exact, subtets, moment_fitting, volume_ratio, lattice or regular)");
}

PieceQuadratureRule piece_quadrature_rule(QuadratureRuleKind kind, const Eigen::Matrix<double, 4, 3>& X,
                                          const std::vector<CutTriangle>& triangles, const TetPieces& pieces, int piece,
                                          const PieceRuleOptions& options) {
  if (piece < 0 || piece >= pieces.num_pieces()) throw std::invalid_argument("piece_quadrature_rule: no such piece");
  switch (kind) {
  case QuadratureRuleKind::exact: return exact_moment_fitting_rule(X, pieces, piece, options.degree);
  case QuadratureRuleKind::subtets: return subtet_rule(pieces, piece, options.degree);
  case QuadratureRuleKind::moment_fitting: return koschier_moment_fitting_rule(X, triangles, pieces, piece, options.degree);
  case QuadratureRuleKind::volume_ratio: return volume_ratio_rule(X, pieces, piece, options.degree);
  case QuadratureRuleKind::lattice: return lattice_rule(X, pieces, piece, options.lattice_divisions);
  case QuadratureRuleKind::regular: return regular_rule(X, pieces, piece, options.regular_cells);
  }
  throw std::invalid_argument("piece_quadrature_rule: unknown kind");
}

Eigen::Matrix<double, 10, 1> piece_moments(const PieceQuadratureRule& rule) {
  Eigen::Matrix<double, 10, 1> m = Eigen::Matrix<double, 10, 1>::Zero();
  for (std::size_t q = 0; q < rule.points.size(); ++q) {
    const Eigen::Vector3d& x = rule.points[q];
    Eigen::Matrix<double, 10, 1> f;
    f << 1.0, x.x(), x.y(), x.z(), x.x() * x.x(), x.y() * x.y(), x.z() * x.z(), x.x() * x.y(), x.y() * x.z(), x.x() * x.z();
    m += rule.weights[q] * f;
  }
  return m;
}

double integrate(const PieceQuadratureRule& rule, const std::function<double(const Eigen::Vector3d&)>& f) {
  double sum = 0.0;
  for (std::size_t q = 0; q < rule.points.size(); ++q) sum += rule.weights[q] * f(rule.points[q]);
  return sum;
}

int count_points(const PieceQuadratureRule& rule) {
  int n = 0;
  for (double w : rule.weights) n += w != 0.0;
  return n;
}

} // namespace kerf
