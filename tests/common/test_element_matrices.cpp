// Element matrices: stiffness symmetric, positive semidefinite with exactly six zero
// eigenvalues (three translations, three infinitesimal rotations), equal to B^T C B with the
// Voigt matrix of eq. (6); the Tet10 stiffness against an exact integration of B^T C B written
// here from the barycentric coordinates (no quadrature); the Tet4 and Tet10 masses entry by
// entry against their closed forms and against exact integrals of the shape-function products
// as polynomials in the barycentric coordinates; load integrals.
#include "kerf/fem/linear_material.hpp"
#include "kerf/fem/tet_loads.hpp"
#include "kerf/fem/tet_mass.hpp"
#include "kerf/fem/tet_shape_functions.hpp"
#include "kerf/fem/tet_stiffness.hpp"
#include "kerf/mesh/tet_mesh.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <map>

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

double factorial(int n) { return std::tgamma(n + 1.0); }

// A polynomial in the four barycentric coordinates: exponents (a, b, c, d) -> coefficient.
using BarycentricPolynomial = std::map<std::array<int, 4>, double>;

BarycentricPolynomial times(const BarycentricPolynomial& p, const BarycentricPolynomial& q) {
  BarycentricPolynomial r;
  for (const auto& [ep, cp] : p)
    for (const auto& [eq, cq] : q) {
      std::array<int, 4> e{};
      for (int i = 0; i < 4; ++i) e[static_cast<std::size_t>(i)] = ep[static_cast<std::size_t>(i)] + eq[static_cast<std::size_t>(i)];
      r[e] += cp * cq;
    }
  return r;
}

// int_T p dV, term by term with int_T lambda^e dV = 6 V e0! e1! e2! e3! / (|e| + 3)!: exact,
// and independent of any quadrature rule.
double integrate(const BarycentricPolynomial& p, double volume) {
  double sum = 0.0;
  for (const auto& [e, c] : p)
    sum += c * 6.0 * volume * factorial(e[0]) * factorial(e[1]) * factorial(e[2]) * factorial(e[3]) /
           factorial(e[0] + e[1] + e[2] + e[3] + 3);
  return sum;
}

// The Tet10 shape functions in Kerf's node order as barycentric polynomials, written from
// their definition: corners lambda_a (2 lambda_a - 1), mid-edge nodes 4 lambda_i lambda_j.
std::array<BarycentricPolynomial, 10> tet10_polynomials() {
  std::array<BarycentricPolynomial, 10> N;
  for (int a = 0; a < 4; ++a) {
    std::array<int, 4> square{}, linear{};
    square[static_cast<std::size_t>(a)] = 2;
    linear[static_cast<std::size_t>(a)] = 1;
    N[static_cast<std::size_t>(a)] = {{square, 2.0}, {linear, -1.0}};
  }
  for (int e = 0; e < 6; ++e) {
    std::array<int, 4> product{};
    product[static_cast<std::size_t>(kerf::tet_edge_corners[e][0])] = 1;
    product[static_cast<std::size_t>(kerf::tet_edge_corners[e][1])] = 1;
    N[static_cast<std::size_t>(4 + e)] = {{product, 4.0}};
  }
  return N;
}

// The gradients of the barycentric coordinates (4x3, row a = grad lambda_a) from the inverse of
// [1 1 1 1; X^T], which maps (1, x) to lambda: no shape-function code of the library.
Eigen::Matrix<double, 4, 3> barycentric_gradients(const Eigen::Matrix<double, 4, 3>& X) {
  Eigen::Matrix4d A;
  A.row(0).setOnes();
  A.bottomRows<3>() = X.transpose();
  return A.inverse().rightCols<3>();
}

// The isotropic Voigt matrix written from lambda and mu (order xx, yy, zz, xy, xz, yz,
// engineering shear strains), without the library's voigt_elasticity_matrix.
Eigen::Matrix<double, 6, 6> isotropic_voigt(double young, double poisson) {
  const double mu = young / (2.0 * (1.0 + poisson)), lambda = young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
  Eigen::Matrix<double, 6, 6> C = Eigen::Matrix<double, 6, 6>::Zero();
  C.topLeftCorner<3, 3>().setConstant(lambda);
  for (int i = 0; i < 3; ++i) C(i, i) += 2.0 * mu;
  for (int i = 3; i < 6; ++i) C(i, i) = mu;
  return C;
}

// The strain-displacement matrix (6 x 3n) of gradients G (n x 3), same Voigt order.
template <int n>
Eigen::Matrix<double, 6, 3 * n> strain_matrix(const Eigen::Matrix<double, n, 3>& G) {
  Eigen::Matrix<double, 6, 3 * n> B = Eigen::Matrix<double, 6, 3 * n>::Zero();
  for (int a = 0; a < n; ++a) {
    B(0, 3 * a) = G(a, 0);
    B(1, 3 * a + 1) = G(a, 1);
    B(2, 3 * a + 2) = G(a, 2);
    B(3, 3 * a) = G(a, 1), B(3, 3 * a + 1) = G(a, 0);
    B(4, 3 * a) = G(a, 2), B(4, 3 * a + 2) = G(a, 0);
    B(5, 3 * a + 1) = G(a, 2), B(5, 3 * a + 2) = G(a, 1);
  }
  return B;
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

TEST_CASE("Tet10 stiffness: symmetric, six rigid-body zero modes, equal to an exact integration of B^T C B") {
  const kerf::LinearMaterial material{300e3, 0.35, 1070};
  const Eigen::Matrix<double, 4, 3> X4 = distorted_tet();
  const Eigen::Matrix<double, 30, 30> K = kerf::tet10_stiffness(straight_tet10(X4), material);
  check_rigid_body_null_space(K);

  // The independent integration. With g_a = grad lambda_a (constant on a straight tet), the
  // Tet10 gradients are linear in lambda, and homogeneous once -1 is written -sum_k lambda_k:
  //   corner a:     grad N_a = (4 lambda_a - 1) g_a     = sum_k lambda_k (4 delta_ka - 1) g_a,
  //   edge (i, j):  grad N   = 4 (lambda_i g_j + lambda_j g_i) = sum_k lambda_k 4 (delta_ki g_j + delta_kj g_i).
  // So B = sum_k lambda_k B_k, and with int_T lambda_k lambda_l dV = V (1 + delta_kl) / 20,
  //   K = V / 20 sum_kl (1 + delta_kl) B_k^T C B_l,
  // exact, with no quadrature rule and none of the library's shape functions.
  const Eigen::Matrix<double, 4, 3> g = barycentric_gradients(X4);
  std::array<Eigen::Matrix<double, 6, 30>, 4> B;
  for (int k = 0; k < 4; ++k) {
    Eigen::Matrix<double, 10, 3> G = Eigen::Matrix<double, 10, 3>::Zero();
    for (int a = 0; a < 4; ++a) G.row(a) = (4.0 * (k == a) - 1.0) * g.row(a);
    for (int e = 0; e < 6; ++e) {
      const int i = kerf::tet_edge_corners[e][0], j = kerf::tet_edge_corners[e][1];
      G.row(4 + e) = 4.0 * ((k == i) * g.row(j) + (k == j) * g.row(i));
    }
    B[static_cast<std::size_t>(k)] = strain_matrix<10>(G);
  }
  const Eigen::Matrix<double, 6, 6> C = isotropic_voigt(material.young, material.poisson);
  Eigen::Matrix<double, 30, 30> K_exact = Eigen::Matrix<double, 30, 30>::Zero();
  for (std::size_t k = 0; k < 4; ++k)
    for (std::size_t l = 0; l < 4; ++l)
      K_exact += (k == l ? 2.0 : 1.0) * B[k].transpose() * C * B[l];
  K_exact *= volume_of(X4) / 20.0;
  // Both are sums of a few dozen terms of the size of the largest entry: round-off ~1e-15
  // relative; a wrong rule (e.g. the centroid) or a wrong gradient changes entries at O(1).
  const double difference = (K - K_exact).cwiseAbs().maxCoeff() / K_exact.cwiseAbs().maxCoeff();
  MESSAGE("Tet10 stiffness vs exact B^T C B integration: max difference " << difference << " of the largest entry");
  CHECK(difference <= 1e-12);
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

TEST_CASE("Tet4 consistent mass: entry by entry rho V (1 + delta_ab) / 20") {
  const double rho = 1070.0;
  const Eigen::Matrix<double, 4, 3> X = distorted_tet();
  const double V = volume_of(X);
  const Eigen::Matrix4d m = kerf::tet4_mass(X, rho);
  // rho int lambda_a lambda_b dV = rho 6 V (1 + delta_ab) / 5! (the Dirichlet integral), the
  // same closed form reached through the polynomial integration below. One product and a
  // division per entry: 1e-14 relative.
  double worst = 0.0;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) {
      BarycentricPolynomial la, lb;
      std::array<int, 4> ea{}, eb{};
      ea[static_cast<std::size_t>(a)] = 1;
      eb[static_cast<std::size_t>(b)] = 1;
      la[ea] = 1.0;
      lb[eb] = 1.0;
      const double closed_form = rho * V * (a == b ? 2.0 : 1.0) / 20.0;
      CHECK(std::abs(rho * integrate(times(la, lb), V) - closed_form) <= 1e-14 * closed_form);
      worst = std::max(worst, std::abs(m(a, b) - closed_form) / closed_form);
    }
  CHECK(worst <= 1e-14);
}

TEST_CASE("Tet10 consistent mass: entry by entry against the closed form rho V / 420 [...]") {
  const double rho = 1070.0;
  const Eigen::Matrix<double, 4, 3> X = distorted_tet();
  const double V = volume_of(X);
  const Eigen::Matrix<double, 10, 10> m10 = kerf::tet10_mass(straight_tet10(X), rho);
  // The closed form (e.g. Zienkiewicz & Taylor), in units of rho V / 420: corner-corner 6 on
  // the diagonal and 1 off it; corner-edge -4 if the edge ends at the corner, -6 if not;
  // edge-edge 32 on the diagonal, 16 for two edges sharing a corner, 8 for opposite edges.
  // We also derive every entry here, exactly, from the shape functions as polynomials in the
  // barycentric coordinates (tet10_polynomials, integrate): the two must agree, and the
  // library's degree-4 quadrature must agree with both.
  const auto N = tet10_polynomials();
  const auto ends_at = [](int e, int a) { return kerf::tet_edge_corners[e][0] == a || kerf::tet_edge_corners[e][1] == a; };
  double worst = 0.0, worst_table = 0.0;
  for (int a = 0; a < 10; ++a)
    for (int b = 0; b < 10; ++b) {
      double units = 0.0;
      if (a < 4 && b < 4) units = a == b ? 6.0 : 1.0;
      else if (a < 4 || b < 4) units = ends_at(a < 4 ? b - 4 : a - 4, a < 4 ? a : b) ? -4.0 : -6.0;
      else if (a == b) units = 32.0;
      else {
        const int e = a - 4, f = b - 4;
        const bool share = ends_at(f, kerf::tet_edge_corners[e][0]) || ends_at(f, kerf::tet_edge_corners[e][1]);
        units = share ? 16.0 : 8.0;
      }
      const double closed_form = rho * V / 420.0 * units;
      const double derived = rho * integrate(times(N[static_cast<std::size_t>(a)], N[static_cast<std::size_t>(b)]), V);
      CAPTURE(a);
      CAPTURE(b);
      // The derived entry is a sum of at most 9 exact rational terms of size <= rho V / 50:
      // round-off ~1e-16 rho V, i.e. ~1e-13 of the scale rho V / 420 at worst (measured 7e-15).
      // The library's is a 27-point sum of terms up to rho V / 27 that cancel down to entries
      // ~rho V / 420: ~400 eps of that scale (measured 3e-14). 1e-12 bounds both; a wrong rule
      // or shape function errs by whole units.
      worst_table = std::max(worst_table, std::abs(derived - closed_form) / (rho * V / 420.0));
      worst = std::max(worst, std::abs(m10(a, b) - closed_form) / (rho * V / 420.0));
    }
  MESSAGE("Tet10 mass: closed form vs exact polynomial integration " << worst_table << ", library vs closed form " << worst
                                                                     << " (in units of rho V / 420)");
  CHECK(worst_table <= 1e-12);
  CHECK(worst <= 1e-12);
  CHECK(m10.sum() == kerf_test::relative(rho * V, 1e-13));
  CHECK((m10 - m10.transpose()).cwiseAbs().maxCoeff() <= 1e-15 * m10.cwiseAbs().maxCoeff());
  // Row sums are the shape-function integrals: -V/20 at corners, V/5 at mid-edge nodes.
  const Eigen::VectorXd s = kerf::tet_shape_integrals(10, V);
  CHECK((m10.rowwise().sum() - rho * s).cwiseAbs().maxCoeff() < 1e-13 * rho * V);
  const Eigen::MatrixXd dense = m10;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(dense);
  CHECK(eigen.eigenvalues().minCoeff() > 0.0);
}

TEST_CASE("load integrals: shape functions integrate to the volume and the area") {
  CHECK(kerf::tet_shape_integrals(4, 2.0).sum() == kerf_test::relative(2.0));
  CHECK(kerf::tet_shape_integrals(10, 2.0).sum() == kerf_test::relative(2.0));
  CHECK(kerf::face_shape_integrals(3, 0.5).sum() == kerf_test::relative(0.5));
  CHECK(kerf::face_shape_integrals(6, 0.5).sum() == kerf_test::relative(0.5));
  CHECK(kerf::face_shape_integrals(6, 0.5)[0] == 0.0);
}
