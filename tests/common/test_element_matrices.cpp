// Element matrices: stiffness symmetric, positive semidefinite with exactly six zero
// eigenvalues (three translations, three infinitesimal rotations), equal to B^T C B with the
// Voigt matrix of eq. (6); mass summing to rho V; load integrals.
#include "kerf/fem/linear_material.hpp"
#include "kerf/fem/tet_loads.hpp"
#include "kerf/fem/tet_mass.hpp"
#include "kerf/fem/tet_shape_functions.hpp"
#include "kerf/fem/tet_stiffness.hpp"
#include "kerf/mesh/tet_mesh.hpp"

#include <doctest/doctest.h>

#include <Eigen/Dense>

namespace {

Eigen::Matrix<double, 4, 3> distorted_tet() {
  Eigen::Matrix<double, 4, 3> X;
  X << 0.01, 0.0, 0.002, 0.032, 0.004, 0.0, 0.003, 0.027, 0.001, 0.002, 0.005, 0.041;
  return X;
}

Eigen::Matrix<double, 10, 3> straight_tet10(const Eigen::Matrix<double, 4, 3>& X4) {
  Eigen::Matrix<double, 10, 3> X;
  X.topRows<4>() = X4;
  for (int e = 0; e < 6; ++e) X.row(4 + e) = 0.5 * (X4.row(kerf::tet_edge_corners[e][0]) + X4.row(kerf::tet_edge_corners[e][1]));
  return X;
}

double volume_of(const Eigen::Matrix<double, 4, 3>& X) {
  Eigen::Matrix3d J;
  for (int c = 0; c < 3; ++c) J.col(c) = (X.row(c + 1) - X.row(0)).transpose();
  return J.determinant() / 6.0;
}

// Six zero eigenvalues: below 1e-10 of the largest (round-off of a 12x12 or 30x30 symmetric
// eigen-solve is ~1e-15 relative); the seventh well above it (it is a real deformation mode).
template <class Matrix>
void check_rigid_body_null_space(const Matrix& K) {
  CHECK((K - K.transpose()).cwiseAbs().maxCoeff() <= 1e-14 * K.cwiseAbs().maxCoeff());
  const Eigen::MatrixXd dense = K;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(dense);
  const Eigen::VectorXd lambda = eigen.eigenvalues();
  const double largest = lambda.maxCoeff();
  int zeros = 0;
  for (Eigen::Index i = 0; i < lambda.size(); ++i) {
    CHECK(lambda[i] > -1e-10 * largest);
    if (std::abs(lambda[i]) < 1e-10 * largest) ++zeros;
  }
  CHECK(zeros == 6);
  CHECK(lambda[6] > 1e-4 * largest);
}

} // namespace

TEST_CASE("Tet4 stiffness: symmetric, six rigid-body zero modes, equal to B^T C B") {
  const kerf::LinearMaterial material{300e3, 0.35, 1070};
  const Eigen::Matrix<double, 4, 3> X = distorted_tet();
  const Eigen::Matrix<double, 12, 12> K = kerf::tet4_stiffness(X, material);
  check_rigid_body_null_space(K);

  // The textbook form with the strain-displacement matrix B (6x12) in the paper's Voigt order.
  double det_J = 0.0;
  const Eigen::Matrix<double, 4, 3> g = kerf::physical_shape_gradients<4>(X, kerf::tet4_shape_gradients(), det_J);
  Eigen::Matrix<double, 6, 12> B = Eigen::Matrix<double, 6, 12>::Zero();
  for (int a = 0; a < 4; ++a) {
    B(0, 3 * a) = g(a, 0);
    B(1, 3 * a + 1) = g(a, 1);
    B(2, 3 * a + 2) = g(a, 2);
    B(3, 3 * a) = g(a, 1), B(3, 3 * a + 1) = g(a, 0); // gamma_xy
    B(4, 3 * a) = g(a, 2), B(4, 3 * a + 2) = g(a, 0); // gamma_xz
    B(5, 3 * a + 1) = g(a, 2), B(5, 3 * a + 2) = g(a, 1); // gamma_yz
  }
  const Eigen::Matrix<double, 12, 12> K_voigt = volume_of(X) * B.transpose() * kerf::voigt_elasticity_matrix(material) * B;
  CHECK((K - K_voigt).cwiseAbs().maxCoeff() <= 1e-12 * K.cwiseAbs().maxCoeff());
}

TEST_CASE("Tet10 stiffness: symmetric, six rigid-body zero modes") {
  const kerf::LinearMaterial material{300e3, 0.35, 1070};
  check_rigid_body_null_space(kerf::tet10_stiffness(straight_tet10(distorted_tet()), material));
}

TEST_CASE("a rigid motion costs no force: K times a rotation field is zero") {
  const kerf::LinearMaterial material{300e3, 0.49, 1070};
  const Eigen::Matrix<double, 10, 3> X = straight_tet10(distorted_tet());
  const Eigen::Matrix<double, 30, 30> K = kerf::tet10_stiffness(X, material);
  const Eigen::Vector3d omega(0.3, -0.2, 0.5), translation(1.0, 2.0, -3.0);
  Eigen::Matrix<double, 30, 1> u;
  for (int a = 0; a < 10; ++a) u.segment<3>(3 * a) = translation + omega.cross(X.row(a).transpose());
  CHECK((K * u).norm() <= 1e-12 * K.norm() * u.norm());
}

TEST_CASE("consistent mass sums to rho V, and its closed form matches quadrature") {
  const double rho = 1070.0;
  const Eigen::Matrix<double, 4, 3> X = distorted_tet();
  const double V = volume_of(X);
  CHECK(kerf::tet4_mass(X, rho).sum() == doctest::Approx(rho * V).epsilon(1e-14));
  const Eigen::Matrix<double, 10, 10> m10 = kerf::tet10_mass(straight_tet10(X), rho);
  CHECK(m10.sum() == doctest::Approx(rho * V).epsilon(1e-13));
  CHECK((m10 - m10.transpose()).cwiseAbs().maxCoeff() <= 1e-15 * m10.cwiseAbs().maxCoeff());
  // Row sums are the shape-function integrals: -V/20 at corners, V/5 at mid-edge nodes.
  const Eigen::VectorXd s = kerf::tet_shape_integrals(10, V);
  CHECK((m10.rowwise().sum() - rho * s).cwiseAbs().maxCoeff() < 1e-13 * rho * V);
  const Eigen::MatrixXd dense = m10;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(dense);
  CHECK(eigen.eigenvalues().minCoeff() > 0.0);
}

TEST_CASE("load integrals: shape functions integrate to the volume and the area") {
  CHECK(kerf::tet_shape_integrals(4, 2.0).sum() == doctest::Approx(2.0));
  CHECK(kerf::tet_shape_integrals(10, 2.0).sum() == doctest::Approx(2.0));
  CHECK(kerf::face_shape_integrals(3, 0.5).sum() == doctest::Approx(0.5));
  CHECK(kerf::face_shape_integrals(6, 0.5).sum() == doctest::Approx(0.5));
  CHECK(kerf::face_shape_integrals(6, 0.5)[0] == 0.0);
}
