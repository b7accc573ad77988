// Tet4 and Tet10 shape functions: partition of unity, Kronecker delta, gradients against
// central finite differences.
#include "kerf/fem/tet_shape_functions.hpp"
#include "kerf/mesh/tet_mesh.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <random>

namespace {

// Reference positions of the ten Tet10 nodes: corners, then edge midpoints.
Eigen::Matrix<double, 10, 3> tet10_reference_nodes() {
  Eigen::Matrix<double, 10, 3> P;
  P.topRows<4>() << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  for (int e = 0; e < 6; ++e) P.row(4 + e) = 0.5 * (P.row(kerf::tet_edge_corners[e][0]) + P.row(kerf::tet_edge_corners[e][1]));
  return P;
}

std::vector<Eigen::Vector3d> random_reference_points(int count) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<Eigen::Vector3d> points;
  while (static_cast<int>(points.size()) < count) {
    const Eigen::Vector3d xi(uniform(rng), uniform(rng), uniform(rng));
    if (xi.sum() <= 1.0) points.push_back(xi);
  }
  return points;
}

} // namespace

TEST_CASE("Tet4 and Tet10 shape functions are a partition of unity") {
  for (const auto& xi : random_reference_points(50)) {
    CHECK(kerf::tet4_shape(xi).sum() == kerf_test::relative(1.0, 1e-14));
    CHECK(kerf::tet10_shape(xi).sum() == kerf_test::relative(1.0, 1e-14));
    // The gradients of a partition of unity sum to zero.
    CHECK(kerf::tet10_shape_gradients(xi).colwise().sum().norm() < 1e-13);
  }
  CHECK(kerf::tet4_shape_gradients().colwise().sum().norm() == 0.0);
}

TEST_CASE("Tet4 and Tet10 shape functions have the Kronecker delta property") {
  const Eigen::Matrix<double, 10, 3> P = tet10_reference_nodes();
  for (int b = 0; b < 10; ++b) {
    const Eigen::Matrix<double, 10, 1> N = kerf::tet10_shape(P.row(b).transpose());
    for (int a = 0; a < 10; ++a) CHECK(N[a] == kerf_test::relative(a == b ? 1.0 : 0.0, 1e-15));
  }
  for (int b = 0; b < 4; ++b) {
    const Eigen::Vector4d N = kerf::tet4_shape(P.row(b).transpose());
    for (int a = 0; a < 4; ++a) CHECK(N[a] == (a == b ? 1.0 : 0.0));
  }
}

TEST_CASE("Tet10 gradients match central finite differences") {
  // Central differences have error h^2 |N'''| / 6; the Tet10 functions are quadratic, so the
  // third derivative vanishes and only round-off ~ eps / h ~ 1e-10 is left.
  const double h = 1e-6;
  for (const auto& xi : random_reference_points(20)) {
    const Eigen::Matrix<double, 10, 3> dN = kerf::tet10_shape_gradients(xi);
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d step = h * Eigen::Vector3d::Unit(k);
      const Eigen::Matrix<double, 10, 1> fd = (kerf::tet10_shape(xi + step) - kerf::tet10_shape(xi - step)) / (2 * h);
      CHECK((fd - dN.col(k)).cwiseAbs().maxCoeff() < 1e-8);
    }
  }
  const Eigen::Vector3d xi(0.2, 0.3, 0.1);
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d step = h * Eigen::Vector3d::Unit(k);
    const Eigen::Vector4d fd = (kerf::tet4_shape(xi + step) - kerf::tet4_shape(xi - step)) / (2 * h);
    CHECK((fd - kerf::tet4_shape_gradients().col(k)).cwiseAbs().maxCoeff() < 1e-8);
  }
}

TEST_CASE("physical gradients reproduce a linear field on a distorted tet") {
  Eigen::Matrix<double, 4, 3> X;
  X << 0.1, 0.0, 0.2, 1.3, 0.1, 0.0, 0.2, 0.9, 0.1, 0.3, 0.2, 1.4;
  const Eigen::Vector3d a(0.7, -1.1, 2.5);
  Eigen::Vector4d values;
  for (int i = 0; i < 4; ++i) values[i] = a.dot(X.row(i).transpose()) + 3.0;
  double det_J = 0.0;
  const Eigen::Matrix<double, 4, 3> g = kerf::physical_shape_gradients<4>(X, kerf::tet4_shape_gradients(), det_J);
  CHECK(det_J > 0.0);
  CHECK((g.transpose() * values - a).norm() < 1e-13);
}
