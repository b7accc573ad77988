#include "kerf/fem/tet_loads.hpp"

#include <stdexcept>

namespace kerf {

Eigen::VectorXd tet_shape_integrals(int nodes_per_tet, double volume) {
  if (nodes_per_tet == 4) return Eigen::VectorXd::Constant(4, volume / 4.0);
  if (nodes_per_tet != 10) throw std::invalid_argument("tet_shape_integrals: 4 or 10 nodes");
  Eigen::VectorXd s(10);
  s.head(4).setConstant(-volume / 20.0); // int lambda (2 lambda - 1) = 2 V/10 - V/4
  s.tail(6).setConstant(volume / 5.0);   // int 4 lambda_i lambda_j = 4 V/20
  return s;
}

Eigen::VectorXd face_shape_integrals(int nodes_per_face, double area) {
  if (nodes_per_face == 3) return Eigen::VectorXd::Constant(3, area / 3.0);
  if (nodes_per_face != 6) throw std::invalid_argument("face_shape_integrals: 3 or 6 nodes");
  Eigen::VectorXd s(6);
  s.head(3).setZero();                  // int mu (2 mu - 1) = 2 A/6 - A/3 = 0
  s.tail(3).setConstant(area / 3.0);    // int 4 mu_i mu_j = 4 A/12
  return s;
}

} // namespace kerf
