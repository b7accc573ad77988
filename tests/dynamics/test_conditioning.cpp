// Koschier's conditioning of the implicit step (Koschier et al. section 6): the five-tet cube's
// mesh; the bilateral preconditioner's entries on one tet cut by a plane, against eqs. 26-27
// worked out by hand; the preconditioned solve (eqs. 24-25) against a direct one; and on the
// cut cube of Fig. 14, the growth of the condition number of M + dt^2 K as the cut nears a face,
// bare, Jacobi-scaled and with eqs. 26-27, against the exponents the integrals predict, and
// eq. 22's constraining, which keeps it at d^-1 (not bounded: the shifted basis's near-dependence,
// which the part basis with Jacobi scaling removes).
#include "dynamics/cut_body.hpp"
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/dynamics/bilateral_preconditioner.hpp"
#include "kerf/dynamics/newton_matrix_conditioning.hpp"
#include "kerf/dynamics/part_basis.hpp"
#include "kerf/fem/tet_mass.hpp"
#include "kerf/mesh/five_tet_cube.hpp"
#include "kerf/xfem/cut_xfem_mass.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <vector>

namespace {

const kerf::LinearMaterial cube_material{1e6, 0.3, 1000.0}; // Koschier et al. section 7
const double dt = 1e-3;

double signed_volume(const kerf::TetMesh& mesh, Eigen::Index t) {
  const Eigen::Matrix<double, 4, 3> X = kerf::tet_corners(mesh, t);
  Eigen::Matrix3d J;
  for (int a = 0; a < 3; ++a) J.col(a) = (X.row(a + 1) - X.row(0)).transpose();
  return J.determinant() / 6.0;
}

// The cube [-1, 1]^3 of five tets cut by the plane x = x_c (uncut for NaN), measured.
kerf::NewtonMatrixConditioning cube_cut_at(double x_c, double epsilon = kerf::koschier_sliver_fraction) {
  std::vector<kerf::TriangleSurface> surfaces;
  if (!std::isnan(x_c)) surfaces.push_back(cut_body::plane_surface({1, 0, 0}, x_c, Eigen::Vector3d::Zero(), 3.0));
  const cut_body::CutBody body(kerf::make_five_tet_cube({-1, -1, -1}, {1, 1, 1}), surfaces, cube_material);
  return kerf::newton_matrix_conditioning(body.model, cube_material.density, dt, cut_body::subtets, epsilon);
}

// p in kappa ~ d^-p from two distances.
double exponent(double kappa_far, double d_far, double kappa_near, double d_near) {
  return std::log(kappa_near / kappa_far) / std::log(d_far / d_near);
}

} // namespace

TEST_CASE("the five-tet cube fills the box with positively oriented tets: a central third and four corner sixths") {
  const kerf::TetMesh mesh = kerf::make_five_tet_cube({-1, -1, -1}, {1, 1, 1});
  REQUIRE(mesh.num_tets() == 5);
  REQUIRE(mesh.num_nodes() == 8);
  // Edge 2, volume 8: the central tet 8/3, each corner tet 8/6, exactly in floating point up to
  // the rounding of a 3x3 determinant of small integers (exact), hence 1e-14.
  CHECK(signed_volume(mesh, 0) == kerf_test::relative(8.0 / 3.0, 1e-14));
  for (Eigen::Index t = 1; t < 5; ++t) CHECK(signed_volume(mesh, t) == kerf_test::relative(8.0 / 6.0, 1e-14));
  CHECK_THROWS_AS(kerf::make_five_tet_cube({0, 0, 0}, {1, 0, 1}), std::invalid_argument);
}

TEST_CASE("Koschier's T on the unit tet cut by x = 1/2: 1 on u, 1/sqrt(v) on a with v = 7/8 for node 1 and 1/8 for the others") {
  // The plane x = c cuts off the corner of node 1, a copy of the tet scaled by 1 - c about
  // node 1: volume (1 - c)^3 / 6. Every node's support is the one tet (V_supp = 1/6) and is cut
  // in two, so every node has one enrichment, on the part it does not lie in: node 1's on the
  // big part, v = 1 - (1 - c)^3 = 7/8; nodes 0, 2, 3's on the corner, v = (1 - c)^3 = 1/8
  // (eq. 27). Eq. 26: T = 1/sqrt(v) on the three components of each a.
  const double c = 0.5;
  const cut_body::CutBody body(cut_body::unit_tet(), {cut_body::plane_surface({1, 0, 0}, c, Eigen::Vector3d(0.3, 0.3, 0.3), 2.0)},
                               cube_material);
  const kerf::SurfaceEnrichment& enrichment = body.model.enrichment();
  REQUIRE(enrichment.num_enrichments() == 4);
  const Eigen::VectorXd t = kerf::koschier_preconditioner(body.model.enrichment_volumes(), 4);
  REQUIRE(t.size() == 24);
  // The sub-tetrahedra's weights sum to the pieces' volumes to round-off: 1e-13.
  for (int k = 0; k < 12; ++k) CHECK(t[k] == 1.0);
  for (int k = 0; k < 4; ++k) {
    const int node = enrichment.enrichment_node[static_cast<std::size_t>(k)];
    const double v = node == 1 ? 1.0 - std::pow(1.0 - c, 3) : std::pow(1.0 - c, 3);
    for (int p = 0; p < 3; ++p) CHECK(t[3 * (4 + k) + p] == kerf_test::relative(1.0 / std::sqrt(v), 1e-13));
  }
  // And the values printed out: sqrt(8 / 7) and sqrt(8).
  CHECK(t[3 * 4 + 3 * 1] == kerf_test::relative(std::sqrt(8.0 / 7.0), 1e-13));
  CHECK(t[3 * 4 + 3 * 0] == kerf_test::relative(std::sqrt(8.0), 1e-13));
}

TEST_CASE("eqs. 24-25 solve A x = c: the same x as a dense Cholesky of A, with Koschier's and with Jacobi's T") {
  const cut_body::CutBody body(cut_body::unit_tet(), {cut_body::plane_surface({1, 0, 0}, 0.8, Eigen::Vector3d(0.3, 0.3, 0.3), 2.0)},
                               cube_material);
  const Eigen::SparseMatrix<double> A =
      kerf::assemble_cut_xfem_mass(body.model, cube_material.density, cut_body::subtets) + dt * dt * body.stiffness();
  Eigen::VectorXd c(A.rows());
  for (Eigen::Index k = 0; k < c.size(); ++k) c[k] = std::sin(1.0 + k);
  const Eigen::VectorXd x_dense = Eigen::MatrixXd(A).llt().solve(c);
  const kerf::SolverSettings settings;
  for (const Eigen::VectorXd& t : {kerf::koschier_preconditioner(body.model.enrichment_volumes(), 4), kerf::jacobi_preconditioner(A)}) {
    const Eigen::VectorXd x = kerf::solve_bilaterally_preconditioned(A, c, t, settings);
    // Two direct solves of a matrix with kappa below 1e6: they agree to ~1e-10 relative.
    CHECK((x - x_dense).norm() <= 1e-9 * x_dense.norm());
  }
  // Jacobi's T makes the diagonal of T A T all ones.
  const Eigen::SparseMatrix<double> scaled = kerf::scale_bilaterally(A, kerf::jacobi_preconditioner(A));
  for (Eigen::Index k = 0; k < scaled.rows(); ++k) CHECK(scaled.coeff(k, k) == kerf_test::relative(1.0, 1e-14));
  CHECK_THROWS_AS(kerf::jacobi_preconditioner(Eigen::SparseMatrix<double>(3, 3)), std::invalid_argument);
}

TEST_CASE("Fig. 14's cube: bare kappa grows like 1 / v_min (d^-3), scaled like d^-1, and eq. 22 keeps d^-1 down to d = 1e-8") {
  // The cut x = -1 + d. The tets with one corner on the face x = -1 leave a corner sliver of
  // relative volume v ~ d^3 to the enrichment of a node on the far face; there N_i ~ d but
  // |grad N_i| = O(1), so its row of A = M + dt^2 K (rho = 1000 against dt^2 E = 1) is ruled by
  // dt^2 E int |grad N_i|^2 ~ v once d << 0.1: lambda_min ~ v while lambda_max stays, and
  // kappa ~ 1 / v_min ~ d^-3. A diagonal scaling (Jacobi's or eqs. 26-27, both O(1 / v) on such
  // a row) cures that, but not the near-dependence of u_i and a_i of a node on the face x = -1,
  // whose own part is the thin slab of the corner tets with a face on x = -1 (relative volume
  // ~ d): the field N_i on that slab alone has an A-norm ~ d against O(1) diagonals, so
  // kappa ~ d^-1 with any diagonal preconditioner [derived]. The exponents are measured between
  // d = 1e-3 and 1e-4, in the asymptotic range (the study shows 1e-2 is not yet: 0.8 there for
  // eqs. 26-27); 0.03 of tolerance on an exponent over a decade is a 7 % change of the constant
  // in kappa ~ C d^-p, which the leading-order argument above allows and a wrong power does not.
  const kerf::NewtonMatrixConditioning far = cube_cut_at(-1.0 + 1e-3, 0.0), near = cube_cut_at(-1.0 + 1e-4, 0.0);
  REQUIRE(std::isfinite(near.plain));
  CHECK(exponent(far.plain, far.smallest_fraction, near.plain, near.smallest_fraction) == kerf_test::relative(1.0, 0.03));
  CHECK(exponent(far.plain, 1e-3, near.plain, 1e-4) == kerf_test::relative(3.0, 0.01));
  CHECK(exponent(far.jacobi, 1e-3, near.jacobi, 1e-4) == kerf_test::relative(1.0, 0.03));
  CHECK(exponent(far.koschier, 1e-3, near.koschier, 1e-4) == kerf_test::relative(1.0, 0.03));
  // The preconditioned matrix is better than the bare one by many orders (measured 2e9 at 1e-4).
  CHECK(near.koschier < 1e-6 * near.plain);

  // Eq. 22 (epsilon = 1e-9) constrains the slivers once v < 1e-9; below d ~ 1e-5 the bare matrix
  // is numerically singular (kappa beyond 1e15, or a non-positive computed eigenvalue), the
  // slivers' entries being round-off; constrained and preconditioned, kappa keeps its d^-1 to
  // d = 1e-8 (same tolerance argument, over four decades: 0.01).
  const kerf::NewtonMatrixConditioning tiny = cube_cut_at(-1.0 + 1e-8), start = cube_cut_at(-1.0 + 1e-4);
  CHECK(start.constrained > 0);
  CHECK(tiny.constrained > start.constrained);
  CHECK(!(tiny.plain < 1e15));
  CHECK(exponent(start.koschier_constrained, 1e-4, tiny.koschier_constrained, 1e-8) == kerf_test::relative(1.0, 0.01));
  CHECK(tiny.koschier_constrained < 1e10);
  // And it is the slab's d^-1, the same as without constraining at d = 1e-4: eq. 22 removed
  // only DOFs that the diagonal scaling had already tamed.
  CHECK(start.koschier_constrained == kerf_test::relative(near.koschier, 0.01));

  // The d^-1 is the basis's, as derived: in the part basis (u_i on the home part, u_i + a_k on
  // part k: the same field) the near-dependent pair is split, and Jacobi scaling keeps kappa at
  // the uncut cube's Jacobi-scaled value (4.99) as d -> 0: measured 5.03 from d = 1e-3 to 1e-8.
  // Bounded means: within a factor 2 of the uncut value, and no growth over four decades.
  const kerf::NewtonMatrixConditioning uncut = cube_cut_at(std::numeric_limits<double>::quiet_NaN());
  for (const kerf::NewtonMatrixConditioning* c : {&far, &near, &start, &tiny}) {
    const double part = c == &far || c == &near ? c->part_jacobi : c->part_jacobi_constrained;
    CHECK(part < 2.0 * uncut.jacobi);
  }
  CHECK(std::abs(exponent(start.part_jacobi_constrained, 1e-4, tiny.part_jacobi_constrained, 1e-8)) < 0.01);
}

TEST_CASE("eq. 22 on every part of a support: Fig. 14's home slab is held, and Jacobi's kappa stays at the uncut cube's") {
  // The cut x = -1 + d leaves each node of the face x = -1 a home part that is the slab between
  // the face and the cut (relative volume ~ d), and its enrichment the rest of the support
  // (fraction ~ 1 - d). Tested on the enrichments' parts only, eq. 22 never holds that node, and
  // Jacobi-scaled kappa grows like d^-1 (1.6e7 at d = 1e-6 with epsilon = 1e-3). Tested on the
  // home part too, the enrichment of the node's largest part is held, the slab moves with it,
  // and the near-dependent pair N_i, N_i psi_i is gone: kappa is the uncut cube's Jacobi-scaled
  // value (4.99), for every d the test reaches. Bounded means within a factor 2 of it.
  const double epsilon = 1e-3;
  const kerf::NewtonMatrixConditioning uncut = cube_cut_at(std::numeric_limits<double>::quiet_NaN());
  for (const double d : {1e-4, 1e-6, 1e-8}) {
    CAPTURE(d);
    const kerf::NewtonMatrixConditioning cut = cube_cut_at(-1.0 + d, epsilon);
    MESSAGE("d = " << d << ": " << cut.constrained << " of " << cut.enrichments << " enrichments held, Jacobi-scaled kappa "
                   << cut.jacobi_constrained << " (uncut " << uncut.jacobi << ")");
    // Four nodes lie on the face x = -1: their home slabs are held, as are the far corner
    // slivers of the others (relative volume ~ d^3 < epsilon; from d = 1e-6 on, some corner
    // slivers are pieces of their own, glued to nothing, which adds enrichments): every one.
    CHECK(cut.constrained == cut.enrichments);
    CHECK(cut.jacobi_constrained < 2.0 * uncut.jacobi);
  }
  // With Koschier's epsilon (1e-9) the home slab is held once it is thinner than that: at
  // d = 1e-10 (relative volume ~ 1e-10), where the bare matrix is numerically singular.
  const kerf::NewtonMatrixConditioning thin = cube_cut_at(-1.0 + 1e-10);
  REQUIRE(thin.enrichments >= 8);
  CHECK(thin.constrained == thin.enrichments);
  CHECK(thin.jacobi_constrained < 2.0 * uncut.jacobi);
  MESSAGE("d = 1e-10, epsilon = 1e-9: " << thin.constrained << " of " << thin.enrichments << " held, kappa " << thin.jacobi_constrained);
}

TEST_CASE("Fig. 14's cube cut through its centre: all eight nodes enriched, kappa well above the uncut cube's, eqs. 26-27 lower it") {
  const kerf::NewtonMatrixConditioning uncut = cube_cut_at(std::numeric_limits<double>::quiet_NaN());
  const kerf::NewtonMatrixConditioning centre = cube_cut_at(0.0);
  CHECK(uncut.enrichments == 0);
  CHECK(centre.enrichments == 8); // every tet is cut at x = 0, every node's support in two
  CHECK(centre.constrained == 0);
  // Koschier: "nearly two orders of magnitude higher" than the uncut matrix's (read off a
  // figure of an unstated five-tet split and norm); we measure 32 (14.3 -> 457): at least one
  // order is the claim we can hold our split to.
  CHECK(centre.plain > 10.0 * uncut.plain);
  // "considerably lower" with the preconditioner: measured 66, a factor 6.9; Jacobi's 20.
  CHECK(centre.koschier < centre.plain / 5.0);
  CHECK(centre.jacobi < centre.koschier);
}

TEST_CASE("the part basis changes the basis, not the field: P w gives [u; a] with u_i = w_i and a_k = w_k - w_i") {
  const cut_body::CutBody body(cut_body::unit_tet(), {cut_body::plane_surface({1, 0, 0}, 0.5, Eigen::Vector3d(0.3, 0.3, 0.3), 2.0)},
                               cube_material);
  const kerf::SurfaceEnrichment& enrichment = body.model.enrichment();
  const Eigen::SparseMatrix<double> P = kerf::part_basis(enrichment, 4);
  // The per-part values of a field that is (1, 2, 3) on the part holding x = 0 and (4, 5, 6) on
  // the part holding x = 1, and the [u; a] the shared helper writes for it by its own route.
  const auto side = [](const Eigen::Vector3d& x) { return x.x() > 0.5 ? 1 : 0; };
  const auto value = [](const Eigen::Vector3d&, int s) { return s == 1 ? Eigen::Vector3d(4, 5, 6) : Eigen::Vector3d(1, 2, 3); };
  const Eigen::VectorXd x = body.piecewise_field(side, value);
  Eigen::VectorXd w(24);
  for (int i = 0; i < 4; ++i) w.segment<3>(3 * i) = value(Eigen::Vector3d::Zero(), i == 1 ? 1 : 0);          // home part
  for (int k = 0; k < 4; ++k) w.segment<3>(3 * (4 + k)) = value(Eigen::Vector3d::Zero(), enrichment.enrichment_node[static_cast<std::size_t>(k)] == 1 ? 0 : 1);
  CHECK((P * w - x).cwiseAbs().maxCoeff() < 1e-14);
}
