#include "kerf/xfem/phantom_piece.hpp"

#include "kerf/fem/tet_shape_functions.hpp"
#include "kerf/fem/tet_stiffness.hpp"

#include <Eigen/Dense>

namespace kerf {

Eigen::Matrix3d tet_corner_jacobian(const Eigen::Matrix<double, 4, 3>& X) {
  Eigen::Matrix3d J;
  for (int c = 0; c < 3; ++c) J.col(c) = (X.row(c + 1) - X.row(0)).transpose();
  return J;
}

PiecePoint piece_point_at_reference(const Eigen::Vector3d& xi, const Eigen::Matrix3d& J_inverse, double weight, int n) {
  PiecePoint point;
  point.weight = weight;
  if (n == 4) {
    point.N.head<4>() = tet4_shape(xi);
    point.G.topRows<4>() = tet4_shape_gradients() * J_inverse;
  } else {
    point.N = tet10_shape(xi);
    point.G = tet10_shape_gradients(xi) * J_inverse;
  }
  return point;
}

std::vector<PiecePoint> piece_points(const PieceQuadratureRule& rule, const Eigen::Matrix<double, 4, 3>& X, int n) {
  const Eigen::Matrix3d J_inverse = tet_corner_jacobian(X).inverse();
  std::vector<PiecePoint> points;
  for (std::size_t q = 0; q < rule.points.size(); ++q)
    points.push_back(
        piece_point_at_reference(J_inverse * (rule.points[q] - X.row(0).transpose()), J_inverse, rule.weights[q], n));
  return points;
}

Eigen::MatrixXd phantom_piece_stiffness(const std::vector<PiecePoint>& points, int n, const LinearMaterial& material) {
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(3 * n, 3 * n);
  for (const PiecePoint& point : points) {
    if (n == 4) {
      Eigen::Matrix<double, 12, 12> K_q = Eigen::Matrix<double, 12, 12>::Zero();
      add_stiffness_integrand<4>(point.G.topRows<4>(), point.weight, material.mu(), material.lambda(), K_q);
      K += K_q;
    } else {
      Eigen::Matrix<double, 30, 30> K_q = Eigen::Matrix<double, 30, 30>::Zero();
      add_stiffness_integrand<10>(point.G, point.weight, material.mu(), material.lambda(), K_q);
      K += K_q;
    }
  }
  return K;
}

std::shared_ptr<const Eigen::Matrix<double, 12, 12>> tet4_piece_stiffness(const std::vector<PiecePoint>& points,
                                                                            const LinearMaterial& material) {
  double weight = 0.0;
  for (const PiecePoint& point : points) weight += point.weight;
  auto K = std::make_shared<Eigen::Matrix<double, 12, 12>>(Eigen::Matrix<double, 12, 12>::Zero());
  if (!points.empty())
    add_stiffness_integrand<4>(points.front().G.topRows<4>(), weight, material.mu(), material.lambda(), *K);
  return K;
}

void phantom_slot_values(const PhantomPiece& piece, std::size_t q, int n, Eigen::VectorXd& g) {
  const PiecePoint& point = piece.points[q];
  g.setZero();
  for (int a = 0; a < n; ++a) {
    g[a] += point.N[a];
    if (const int s = piece.enrichment_slot[static_cast<std::size_t>(a)]; s >= 0) g[s] += point.N[a];
  }
}

void phantom_slot_gradients(const PhantomPiece& piece, std::size_t q, int n, Eigen::MatrixX3d& g) {
  const PiecePoint& point = piece.points[q];
  g.setZero();
  for (int a = 0; a < n; ++a) {
    g.row(a) += point.G.row(a);
    if (const int s = piece.enrichment_slot[static_cast<std::size_t>(a)]; s >= 0) g.row(s) += point.G.row(a);
  }
}

} // namespace kerf
