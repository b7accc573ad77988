// Quadrature on the pieces of a cut tet (quadrature/): exact polyhedral moments against closed
// forms and against Gauss on sub-tetrahedra, moment fitting with exact moments reproducing every
// monomial of its degree on planar, kinked and folded pieces, the volume ratio's exactness for
// constants and its failure for x^2, the rules of all pieces summing to the tet's, Koschier's
// fitted moments (exact on planar cuts and, as measured, on kinks), and the convergence of the
// sampled rules.
#include "kerf/cut/tet_pieces.hpp"
#include "kerf/fem/tet_quadrature.hpp"
#include "kerf/quadrature/gauss_piece_rules.hpp"
#include "kerf/quadrature/koschier_moment_fitting.hpp"
#include "kerf/quadrature/moment_fitting.hpp"
#include "kerf/quadrature/piece_quadrature_rule.hpp"
#include "kerf/quadrature/polyhedron_moments.hpp"
#include "kerf/quadrature/sampled_piece_rules.hpp"
#include "kerf/quadrature/simplex_polynomials.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

namespace {

using Corners = Eigen::Matrix<double, 4, 3>;
using kerf::CutTriangle;

Corners unit_tet() {
  Corners X;
  X << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  return X;
}

CutTriangle triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, int index = 0) {
  return {{a, b, c}, 0, index};
}

std::vector<CutTriangle> square(const Eigen::Vector3d& origin, const Eigen::Vector3d& e1, const Eigen::Vector3d& e2,
                                int first_index = 0) {
  return {triangle(origin, origin + e1, origin + e1 + e2, first_index),
          triangle(origin, origin + e1 + e2, origin + e2, first_index + 1)};
}

// The plane n . x = n . x0 as one triangle far larger than any tet here.
CutTriangle large_triangle(const Eigen::Vector3d& x0, Eigen::Vector3d n) {
  n.normalize();
  const Eigen::Vector3d u = n.unitOrthogonal() * 10.0, v = n.cross(n.unitOrthogonal()) * 10.0;
  return triangle(x0 - u - v, x0 + 2.0 * u - v, x0 - u + 2.0 * v);
}

// The kink of test_tet_pieces.cpp: floor z = 0.3 for x >= 0.2 and wall x = 0.2 for z <= 0.3; the
// piece {x > 0.2, z < 0.3} holds corner 1. Its boundary is not convex.
std::vector<CutTriangle> kink() {
  std::vector<CutTriangle> k = square({0.2, -1.0, 0.3}, {0.0, 3.0, 0.0}, {3.0, 0.0, 0.0}, 0);
  const std::vector<CutTriangle> wall = square({0.2, -1.0, -1.0}, {0.0, 3.0, 0.0}, {0.0, 0.0, 1.3}, 2);
  k.insert(k.end(), wall.begin(), wall.end());
  return k;
}

// The fold of test_tet_pieces.cpp: sheets z = 0.1 and z = 0.2 joined outside the tet, three pieces.
std::vector<CutTriangle> fold() {
  std::vector<CutTriangle> f = square({-1.0, -1.0, 0.1}, {3.0, 0.0, 0.0}, {0.0, 3.0, 0.0}, 0);
  const std::vector<CutTriangle> wall = square({2.0, -1.0, 0.1}, {0.0, 0.0, 0.1}, {0.0, 3.0, 0.0}, 2);
  const std::vector<CutTriangle> upper = square({2.0, -1.0, 0.2}, {-3.0, 0.0, 0.0}, {0.0, 3.0, 0.0}, 4);
  f.insert(f.end(), wall.begin(), wall.end());
  f.insert(f.end(), upper.begin(), upper.end());
  return f;
}

std::vector<std::vector<Eigen::Vector3d>> boundary_polygons(const kerf::TetPiece& piece) {
  std::vector<std::vector<Eigen::Vector3d>> polygons;
  for (const kerf::PieceBoundaryPolygon& b : piece.boundary) polygons.push_back(b.polygon);
  return polygons;
}

// What a rule gives for every monomial of degree <= d.
Eigen::VectorXd rule_monomials(const kerf::PieceQuadratureRule& rule, int degree) {
  const auto exponents = kerf::monomial_exponents_3d(degree);
  Eigen::VectorXd m = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(exponents.size()));
  for (std::size_t q = 0; q < rule.points.size(); ++q) m += rule.weights[q] * kerf::evaluate_monomials_3d(exponents, rule.points[q]);
  return m;
}

// A scale for the integral of a monomial of degree k over a piece of the tet X: V R^k, R the
// largest distance of a corner from the origin. Round-off in a sum of such terms is a few
// epsilon times it, whatever the piece's own integral (which may be a small difference).
Eigen::VectorXd monomial_scales(const Corners& X, int degree) {
  const double R = X.rowwise().norm().maxCoeff();
  const double V = std::abs((X.row(1) - X.row(0)).cross(X.row(2) - X.row(0)).dot(X.row(3) - X.row(0))) / 6.0;
  const auto exponents = kerf::monomial_exponents_3d(degree);
  Eigen::VectorXd s(static_cast<Eigen::Index>(exponents.size()));
  for (std::size_t k = 0; k < exponents.size(); ++k)
    s[static_cast<Eigen::Index>(k)] = V * std::pow(R, exponents[k][0] + exponents[k][1] + exponents[k][2]);
  return s;
}

double worst_scaled_difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b, const Eigen::VectorXd& scale) {
  return (a - b).cwiseAbs().cwiseQuotient(scale).maxCoeff();
}

Corners random_tet(std::mt19937& random) {
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Corners X;
  do {
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 3; ++j) X(i, j) = uniform(random);
  } while (std::abs((X.row(1) - X.row(0)).cross(X.row(2) - X.row(0)).dot(X.row(3) - X.row(0))) < 0.05);
  return X;
}

} // namespace

TEST_CASE("exact polyhedral moments equal the closed forms on the unit tet and its corner piece") {
  const Corners X = unit_tet();
  const kerf::TetPieces uncut = kerf::split_tet_by_triangles(X, {});
  REQUIRE(uncut.num_pieces() == 1);
  // Every monomial of degree <= 6 over the unit tet: a! b! c! / (a + b + c + 3)!. Round-off of
  // some hundred terms of size <= 1: 1e-14 relative is some 50 epsilon.
  const auto exponents = kerf::monomial_exponents_3d(6);
  const Eigen::VectorXd moments = kerf::polyhedron_monomial_moments(boundary_polygons(uncut.pieces[0]), 6);
  for (std::size_t k = 0; k < exponents.size(); ++k) {
    const auto& e = exponents[k];
    CHECK(moments[static_cast<Eigen::Index>(k)] ==
          kerf_test::relative(kerf::reference_tet_monomial_integral(e[0], e[1], e[2]), 1e-14));
  }
  // The corner piece x + y + z <= t, the cut given as one large triangle.
  const double t = 0.3;
  const kerf::TetPieces pieces =
      kerf::split_tet_by_triangles(X, {large_triangle(Eigen::Vector3d::Constant(t / 3.0), Eigen::Vector3d(1, 1, 1))});
  REQUIRE(pieces.num_pieces() == 2);
  const kerf::TetPiece& corner = pieces.pieces[static_cast<std::size_t>(pieces.corner_pieces[0].front())];
  const Eigen::VectorXd m = kerf::polyhedron_monomial_moments(boundary_polygons(corner), 2);
  // Order: 1; x, y, z; x^2, xy, xz, y^2, yz, z^2. The piece's corners come from the cut, each
  // with its round-off: 1e-13 relative is some 500 epsilon (measured: 2.7e-14).
  CHECK(m[0] == kerf_test::relative(std::pow(t, 3) / 6.0, 1e-13));
  CHECK(m[1] + m[2] + m[3] == kerf_test::relative(std::pow(t, 4) / 8.0, 1e-13));
  CHECK(m[5] + m[6] + m[8] == kerf_test::relative(std::pow(t, 5) / 40.0, 1e-13));
  CHECK(m[4] + m[7] + m[9] == kerf_test::relative(std::pow(t, 5) / 20.0, 1e-13));
}

TEST_CASE("polygon moments by Green's theorem equal the triangle's closed forms") {
  const std::vector<Eigen::Vector2d> triangle{{0, 0}, {1, 0}, {0, 1}};
  const auto exponents = kerf::monomial_exponents_2d(5);
  const Eigen::VectorXd m = kerf::polygon_monomial_moments(triangle, 5);
  for (std::size_t k = 0; k < exponents.size(); ++k)
    CHECK(m[static_cast<Eigen::Index>(k)] ==
          kerf_test::relative(kerf::reference_triangle_monomial_integral(exponents[k][0], exponents[k][1]), 1e-14));
  // A non-convex L (the unit square minus its upper right quarter): area 3/4, int x = 1/4 + 1/8 - ... .
  const std::vector<Eigen::Vector2d> ell{{0, 0}, {1, 0}, {1, 0.5}, {0.5, 0.5}, {0.5, 1}, {0, 1}};
  const Eigen::VectorXd l = kerf::polygon_monomial_moments(ell, 1);
  CHECK(l[0] == kerf_test::relative(0.75, 1e-14));
  // int x over the L = int x over the square (1/2) - over the quarter [0.5, 1]^2 (0.25 * 0.75).
  CHECK(l[1] == kerf_test::relative(0.5 - 0.25 * 0.75, 1e-14));
}

TEST_CASE("exact moments equal Gauss on sub-tetrahedra on random planes, a fold and a kink") {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  double worst = 0.0;
  int pieces_checked = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const Corners X = random_tet(random);
    const Eigen::Vector3d n(uniform(random), uniform(random), uniform(random));
    const Eigen::Vector3d x0 = X.colwise().mean().transpose() + 0.2 * Eigen::Vector3d(uniform(random), uniform(random), uniform(random));
    const kerf::TetPieces pieces = kerf::split_tet_by_triangles(X, {large_triangle(x0, n)});
    for (int p = 0; p < pieces.num_pieces(); ++p) {
      const Eigen::VectorXd exact = kerf::polyhedron_monomial_moments(boundary_polygons(pieces.pieces[static_cast<std::size_t>(p)]), 4);
      const Eigen::VectorXd gauss = rule_monomials(kerf::subtet_rule(pieces, p, 4), 4);
      worst = std::max(worst, worst_scaled_difference(exact, gauss, monomial_scales(X, 4)));
      ++pieces_checked;
    }
  }
  for (const std::vector<CutTriangle>& cut : {fold(), kink()}) {
    const kerf::TetPieces pieces = kerf::split_tet_by_triangles(unit_tet(), cut);
    REQUIRE(pieces.num_pieces() >= 2);
    for (int p = 0; p < pieces.num_pieces(); ++p) {
      const Eigen::VectorXd exact = kerf::polyhedron_monomial_moments(boundary_polygons(pieces.pieces[static_cast<std::size_t>(p)]), 4);
      const Eigen::VectorXd gauss = rule_monomials(kerf::subtet_rule(pieces, p, 4), 4);
      worst = std::max(worst, worst_scaled_difference(exact, gauss, monomial_scales(unit_tet(), 4)));
    }
  }
  MESSAGE("exact moments vs sub-tets, degree 4: worst difference / (V R^k) = " << worst);
  CHECK(pieces_checked > 80);
  // Two independent sums of some hundred terms each: 1e-13 is a few hundred epsilon.
  CHECK(worst < 1e-13);
}

TEST_CASE("the fitting systems have full rank: 24 points for degree 2, 125 for degree 4") {
  const kerf::MomentFittingSystem& quadratic = kerf::tet_moment_fitting_system(2);
  CHECK(quadratic.points.size() == 24);
  CHECK(quadratic.rank == 10);
  const kerf::MomentFittingSystem& quartic = kerf::tet_moment_fitting_system(4);
  CHECK(quartic.points.size() == 125);
  CHECK(quartic.rank == 35);
  MESSAGE("condition numbers: degree 2 " << quadratic.condition << ", degree 4 " << quartic.condition);
  // Why 5^3 and not 4^3 Stroud points for degree 4: on the product of 4 points per direction the
  // quartic (xi_1 - u_1)...(xi_1 - u_4) vanishes at every point, so the rank drops below 35.
  const std::vector<Eigen::Vector3d> four_cubed = kerf::tet_quadrature_rule(7).points;
  REQUIRE(four_cubed.size() == 64);
  Eigen::MatrixXd A(35, 64);
  for (int j = 0; j < 64; ++j) A.col(j) = quartic.basis.evaluate(four_cubed[static_cast<std::size_t>(j)]);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A);
  int rank = 0;
  for (Eigen::Index k = 0; k < svd.singularValues().size(); ++k) rank += svd.singularValues()[k] > 1e-12 * svd.singularValues()[0];
  CHECK(rank < 35);
  // The orthonormal basis is orthonormal: its Gram matrix by a degree-8 rule is the identity.
  const kerf::TetQuadratureRule gauss = kerf::tet_quadrature_rule(8);
  Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(35, 35);
  for (std::size_t q = 0; q < gauss.points.size(); ++q) {
    const Eigen::VectorXd P = quartic.basis.evaluate(gauss.points[q]);
    gram += gauss.weights[q] * P * P.transpose();
  }
  CHECK((gram - Eigen::MatrixXd::Identity(35, 35)).cwiseAbs().maxCoeff() < 1e-9);
}

TEST_CASE("the rule \"exact\" integrates every monomial of its degree on planar, kinked and folded pieces") {
  std::mt19937 random(5);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int degree : {2, 4}) {
    double worst = 0.0;
    const auto check_pieces = [&](const Corners& X, const std::vector<CutTriangle>& cut) {
      const kerf::TetPieces pieces = kerf::split_tet_by_triangles(X, cut);
      for (int p = 0; p < pieces.num_pieces(); ++p) {
        const Eigen::VectorXd fitted = rule_monomials(kerf::exact_moment_fitting_rule(X, pieces, p, degree), degree);
        const Eigen::VectorXd gauss = rule_monomials(kerf::subtet_rule(pieces, p, degree), degree);
        worst = std::max(worst, worst_scaled_difference(fitted, gauss, monomial_scales(X, degree)));
      }
    };
    for (int trial = 0; trial < 30; ++trial) {
      const Corners X = random_tet(random);
      const Eigen::Vector3d n(uniform(random), uniform(random), uniform(random));
      check_pieces(X, {large_triangle(X.colwise().mean().transpose(), n)});
    }
    check_pieces(unit_tet(), kink());
    check_pieces(unit_tet(), fold());
    MESSAGE("exact rule, degree " << degree << ": worst difference / (V R^k) = " << worst);
    // The fit's residual is round-off times the condition of eq. 17 (tens for degree 2,
    // thousands for degree 4, see the test above): 1e-13 and 1e-11.
    CHECK(worst < (degree == 2 ? 1e-13 : 1e-11));
  }
}

TEST_CASE("volume ratios integrate constants exactly and do not integrate x^2 (Tet4 stiffness yes, mass no)") {
  const Corners X = unit_tet();
  const double t = 0.3;
  const kerf::TetPieces pieces =
      kerf::split_tet_by_triangles(X, {large_triangle(Eigen::Vector3d::Constant(t / 3.0), Eigen::Vector3d(1, 1, 1))});
  const int corner = pieces.corner_pieces[0].front();
  const Eigen::Matrix<double, 10, 1> ratio = kerf::piece_moments(kerf::volume_ratio_rule(X, pieces, corner, 2));
  const Eigen::Matrix<double, 10, 1> exact = kerf::piece_moments(kerf::exact_moment_fitting_rule(X, pieces, corner, 2));
  // A constant: V_piece / V times a rule that sums to V, to round-off (measured: 1.6e-14).
  CHECK(ratio[0] == kerf_test::relative(std::pow(t, 3) / 6.0, 1e-13));
  // x^2 over the corner piece is t^5 / 60; the ratio rule gives (t^3) int_tet x^2 = t^3 / 60: off
  // by a factor 1 / t^2 = 11.
  CHECK(exact[4] == kerf_test::relative(std::pow(t, 5) / 60.0, 1e-13));
  CHECK(std::abs(ratio[4] - exact[4]) > 5.0 * exact[4]);
}

TEST_CASE("the rules of all pieces of a tet add up to the rule of the whole tet") {
  const Corners X = unit_tet();
  const kerf::TetPieces uncut = kerf::split_tet_by_triangles(X, {});
  for (const std::vector<CutTriangle>& cut :
       {std::vector<CutTriangle>{large_triangle({0.2, 0.25, 0.3}, {1.0, -0.4, 0.7})}, kink(), fold()}) {
    const kerf::TetPieces pieces = kerf::split_tet_by_triangles(X, cut);
    REQUIRE(pieces.num_pieces() >= 2);
    for (kerf::QuadratureRuleKind kind :
         {kerf::QuadratureRuleKind::exact, kerf::QuadratureRuleKind::subtets, kerf::QuadratureRuleKind::moment_fitting,
          kerf::QuadratureRuleKind::volume_ratio, kerf::QuadratureRuleKind::lattice, kerf::QuadratureRuleKind::regular}) {
      CAPTURE(kerf::to_string(kind));
      kerf::PieceRuleOptions options;
      options.regular_cells = 20;
      Eigen::Matrix<double, 10, 1> sum = Eigen::Matrix<double, 10, 1>::Zero();
      for (int p = 0; p < pieces.num_pieces(); ++p) sum += kerf::piece_moments(kerf::piece_quadrature_rule(kind, X, cut, pieces, p, options));
      // The whole tet's rule of the same kind: for exact, subtets, moment fitting (exact on
      // these planar and kinked cuts) and volume ratios the exact integrals (they integrate
      // quadratics); for the sampled rules, the same samples uncut.
      const Eigen::Matrix<double, 10, 1> whole = kerf::piece_moments(kerf::piece_quadrature_rule(kind, X, {}, uncut, 0, options));
      // Sums of at most 8000 terms of size <= 1/6 / 8000 each: 1e-14 absolute.
      CHECK((sum - whole).cwiseAbs().maxCoeff() < 1e-14);
    }
  }
}

TEST_CASE("Koschier's fitted moments: exact on planar cuts and on kinks, with the stated ranks") {
  std::mt19937 random(3);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  double worst_planar = 0.0;
  kerf::KoschierFitReport report;
  for (int trial = 0; trial < 20; ++trial) {
    const Corners X = random_tet(random);
    const Eigen::Vector3d n(uniform(random), uniform(random), uniform(random));
    const std::vector<CutTriangle> cut{large_triangle(X.colwise().mean().transpose(), n)};
    const kerf::TetPieces pieces = kerf::split_tet_by_triangles(X, cut);
    for (int p = 0; p < pieces.num_pieces(); ++p) {
      const Eigen::VectorXd fitted = rule_monomials(kerf::koschier_moment_fitting_rule(X, cut, pieces, p, 2, &report), 2);
      const Eigen::VectorXd gauss = rule_monomials(kerf::subtet_rule(pieces, p, 2), 2);
      worst_planar = std::max(worst_planar, worst_scaled_difference(fitted, gauss, monomial_scales(X, 2)));
      CHECK(report.volume_rank == 10);
      CHECK(report.face_rank == 10);
      CHECK(report.interface_basis == 50);
    }
  }
  MESSAGE("Koschier, planar: worst difference / (V R^k) = " << worst_planar << ", last interface rank " << report.interface_rank
                                                           << " of " << report.interface_points << " points, condition "
                                                           << report.interface_condition);
  CHECK(worst_planar < 1e-9);
  double worst_kink = 0.0;
  const kerf::TetPieces pieces = kerf::split_tet_by_triangles(unit_tet(), kink());
  for (int p = 0; p < pieces.num_pieces(); ++p) {
    const Eigen::VectorXd fitted = rule_monomials(kerf::koschier_moment_fitting_rule(unit_tet(), kink(), pieces, p, 2, &report), 2);
    const Eigen::VectorXd gauss = rule_monomials(kerf::subtet_rule(pieces, p, 2), 2);
    worst_kink = std::max(worst_kink, worst_scaled_difference(fitted, gauss, monomial_scales(unit_tet(), 2)));
  }
  // A kink at an oblique angle: the floor z = 0.25 for x >= 0.25 and the wall x = 0.25 + (z - 0.25) / 5.
  std::vector<CutTriangle> tilted = square({0.25, -1.0, 0.25}, {0.0, 3.0, 0.0}, {3.0, 0.0, 0.0}, 0);
  const std::vector<CutTriangle> tilted_wall = square({0.0, -1.0, -1.0}, {0.0, 3.0, 0.0}, {0.25, 0.0, 1.25}, 2);
  tilted.insert(tilted.end(), tilted_wall.begin(), tilted_wall.end());
  const kerf::TetPieces tilted_pieces = kerf::split_tet_by_triangles(unit_tet(), tilted);
  REQUIRE(tilted_pieces.num_pieces() == 2);
  for (int p = 0; p < 2; ++p) {
    const Eigen::VectorXd fitted = rule_monomials(kerf::koschier_moment_fitting_rule(unit_tet(), tilted, tilted_pieces, p, 2, &report), 2);
    const Eigen::VectorXd gauss = rule_monomials(kerf::subtet_rule(tilted_pieces, p, 2), 2);
    worst_kink = std::max(worst_kink, worst_scaled_difference(fitted, gauss, monomial_scales(unit_tet(), 2)));
  }
  MESSAGE("Koschier, right-angled and oblique kinks: worst difference / (V R^k) = " << worst_kink);
  // Two planes meeting along a line: measured exact here too (the divergence-free fields'
  // fluxes on two planes through a line reach every pair of cubics that P^A . n can be), which
  // the fit does not promise. 1e-12 leaves room for the interface system's condition (~1e5).
  CHECK(worst_kink < 1e-12);
}

TEST_CASE("the lattice on the uncut tet is the centroid rule on its sub-tets: second order") {
  const Corners X = unit_tet();
  const kerf::TetPieces uncut = kerf::split_tet_by_triangles(X, {});
  // Uncut, the lattice is the centroid rule on n^3 sub-tets: its error for x^2 is O(h^2), so
  // doubling n divides it by 4.
  const double exact_x2 = 1.0 / 60.0;
  const double e8 = std::abs(kerf::piece_moments(kerf::lattice_rule(X, uncut, 0, 8))[4] - exact_x2);
  const double e16 = std::abs(kerf::piece_moments(kerf::lattice_rule(X, uncut, 0, 16))[4] - exact_x2);
  MESSAGE("lattice, x^2 on the uncut tet: n = 8: " << e8 << ", n = 16: " << e16);
  CHECK(e8 / e16 == kerf_test::relative(4.0, 0.05));
}

TEST_CASE("the regular grid and the lattice on a cut piece converge at least at first order") {
  // The volume of the piece below a random plane, sampled at n = 16 and n = 64 (h / 4). Only the
  // cells that straddle the plane err, by at most their volume: at worst O(h), so the error must
  // drop by at least 4; with errors of both signs along the plane it drops faster on average
  // (measured: some 40, near second order). The root mean square over 20 planes steadies the
  // ratio, which for one plane jumps about.
  const Corners X = unit_tet();
  std::mt19937 random(2);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  double regular[2] = {0.0, 0.0}, lattice[2] = {0.0, 0.0};
  const int n[2] = {16, 64};
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Vector3d normal(uniform(random), uniform(random), uniform(random));
    const Eigen::Vector3d x0 = Eigen::Vector3d::Constant(0.25) + 0.1 * Eigen::Vector3d(uniform(random), uniform(random), uniform(random));
    const kerf::TetPieces pieces = kerf::split_tet_by_triangles(X, {large_triangle(x0, normal)});
    REQUIRE(pieces.num_pieces() == 2);
    const double V = pieces.pieces[0].volume;
    for (int k = 0; k < 2; ++k) {
      regular[k] += std::pow(kerf::piece_moments(kerf::regular_rule(X, pieces, 0, n[k]))[0] / V - 1.0, 2);
      lattice[k] += std::pow(kerf::piece_moments(kerf::lattice_rule(X, pieces, 0, n[k]))[0] / V - 1.0, 2);
    }
  }
  MESSAGE("RMS relative volume error, n = 16 -> 64: regular " << std::sqrt(regular[0] / 20) << " -> " << std::sqrt(regular[1] / 20)
                                                             << ", lattice " << std::sqrt(lattice[0] / 20) << " -> "
                                                             << std::sqrt(lattice[1] / 20));
  CHECK(std::sqrt(regular[0] / regular[1]) > 4.0);
  CHECK(std::sqrt(lattice[0] / lattice[1]) > 4.0);
}

TEST_CASE("a point belongs to exactly one piece") {
  const kerf::TetPieces pieces = kerf::split_tet_by_triangles(unit_tet(), kink());
  REQUIRE(pieces.num_pieces() == 2);
  CHECK(kerf::piece_of_point(pieces, {0.6, 0.1, 0.1}) == pieces.corner_pieces[1].front()); // x > 0.2, z < 0.3
  CHECK(kerf::piece_of_point(pieces, {0.1, 0.1, 0.1}) == pieces.corner_pieces[0].front());
  CHECK(kerf::piece_of_point(pieces, {0.2, 0.1, 0.1}) >= 0); // on the wall: one of the two, not both, not none
  CHECK(kerf::piece_of_point(pieces, {0.6, 0.6, 0.6}) == -1); // outside the tet
}

TEST_CASE("rule kinds are named and parsed") {
  for (kerf::QuadratureRuleKind kind :
       {kerf::QuadratureRuleKind::exact, kerf::QuadratureRuleKind::subtets, kerf::QuadratureRuleKind::moment_fitting,
        kerf::QuadratureRuleKind::volume_ratio, kerf::QuadratureRuleKind::lattice, kerf::QuadratureRuleKind::regular})
    CHECK(kerf::parse_quadrature_rule_kind(kerf::to_string(kind)) == kind);
  CHECK_THROWS_AS(kerf::parse_quadrature_rule_kind("gauss"), std::invalid_argument);
}
