// Lumped masses of a cut body (dynamics/lumped_mass.hpp) on every way a plane cuts one Tet4
// (a corner off, the opposite corner's big piece, two against two) and on a cut block: the
// body's mass, each piece's mass and translational kinetic energy, first moments, free fall;
// eqs. 81-82's wrong inertia of a separated piece and its opening in free fall, at the values
// derived below; and on a cut Tet10, which diagonals stay positive and which keep a piece's
// centre of mass.
#include "dynamics/cut_body.hpp"
#include "kerf/dynamics/lumped_mass.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <functional>
#include <cmath>
#include <string>
#include <vector>

namespace {

const kerf::LinearMaterial material{1000.0, 0.3, 1100.0};
const double rho = material.density;

// A plane n . x = offset cutting the unit tet, with the closed-form volume and first moment
// (int x, int y, int z) of its "minus" side n . x < offset, and which corners lie there.
struct TetCut {
  std::string name;
  Eigen::Vector3d normal;
  double offset;
  double volume_minus;
  Eigen::Vector3d moment_minus;
  std::vector<int> corners_minus;
};

std::vector<TetCut> tet_cuts() {
  std::vector<TetCut> cuts;
  // x + y + z < s is the unit tet scaled by s about the origin: V = s^3 / 6, centroid s / 4.
  const double s = 0.4;
  cuts.push_back({"corner 0 cut off (1:3)", {1, 1, 1}, s, s * s * s / 6.0, Eigen::Vector3d::Constant(s * s * s * s / 24.0), {0}});
  // x > c is the tet scaled by 1 - c about corner 1: the minus side is the rest.
  const double c = 0.55, r = 1.0 - c;
  const double v_plus = r * r * r / 6.0;
  const Eigen::Vector3d centroid_plus = Eigen::Vector3d(1, 0, 0) + r * (Eigen::Vector3d::Constant(0.25) - Eigen::Vector3d(1, 0, 0));
  cuts.push_back({"corner 1 cut off (3:1)", {1, 0, 0}, c, 1.0 / 6.0 - v_plus,
                  Eigen::Vector3d::Constant(1.0 / 24.0) - v_plus * centroid_plus, {0, 2, 3}});
  // x + y < w: with w = x + y the region is 0 <= x <= w, 0 <= z <= 1 - w, so V = int_0^w u (1 - u) du,
  // int x = int y = int_0^w u^2 (1 - u) / 2 du, int z = int_0^w u (1 - u)^2 / 2 du.
  const double w = 0.6;
  const double mx = w * w * w / 6.0 - w * w * w * w / 8.0;
  const double mz = 0.5 * (w * w / 2.0 - 2.0 * w * w * w / 3.0 + w * w * w * w / 4.0);
  cuts.push_back({"two corners against two (2:2)", {1, 1, 0}, w, w * w / 2.0 - w * w * w / 3.0, Eigen::Vector3d(mx, mx, mz), {0, 3}});
  return cuts;
}

const std::array<kerf::LumpingScheme, 4> piecewise_schemes{kerf::LumpingScheme::bernstein, kerf::LumpingScheme::row_sum,
                                                           kerf::LumpingScheme::hrz, kerf::LumpingScheme::virtual_tet};

const char* name_of(kerf::LumpingScheme scheme) {
  switch (scheme) {
  case kerf::LumpingScheme::bernstein: return "bernstein";
  case kerf::LumpingScheme::row_sum: return "row_sum";
  case kerf::LumpingScheme::hrz: return "hrz";
  case kerf::LumpingScheme::virtual_tet: return "virtual_tet";
  case kerf::LumpingScheme::schoch_eq_81_82: return "schoch_eq_81_82";
  }
  return "?";
}

// The DOFs of the field "side `moving` translates by t, the other side rests" (moving = 0: both move).
Eigen::VectorXd translation(const cut_body::CutBody& body, const std::function<int(const Eigen::Vector3d&)>& side,
                            int moving, const Eigen::Vector3d& t) {
  return body.piecewise_field(side, [&](const Eigen::Vector3d&, int s) {
    return (moving == 0 || s == moving) ? t : Eigen::Vector3d::Zero().eval();
  });
}

} // namespace

TEST_CASE("piece-wise lumped masses give every piece of a cut tet its mass and falling acceleration exactly") {
  const double V = 1.0 / 6.0;
  const Eigen::Vector3d t(0.3, -0.2, 0.7);
  for (const TetCut& cut : tet_cuts()) {
    CAPTURE(cut.name);
    const cut_body::CutBody body(cut_body::unit_tet(), {cut_body::plane_surface(cut.normal, cut.offset, {0.25, 0.25, 0.25}, 3.0)},
                                 material);
    REQUIRE(body.pieces.num_pieces(0) == 2);
    REQUIRE(body.enrichment.num_enrichments() == 4);
    const auto side = [&](const Eigen::Vector3d& x) { return cut.normal.dot(x) < cut.offset ? -1 : 1; };
    const double volume[3] = {cut.volume_minus, 0.0, V - cut.volume_minus}; // indexed by side + 1
    const Eigen::Vector3d moment[3] = {cut.moment_minus, Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(1.0 / 24.0) - cut.moment_minus};
    for (const kerf::LumpingScheme scheme : piecewise_schemes) {
      CAPTURE(std::string(name_of(scheme)));
      const Eigen::SparseMatrix<double> M = kerf::lump_cut_xfem_mass(body.model, rho, scheme, cut_body::subtets);
      // The body's mass: a rigid translation of both pieces, 2 T / |t|^2 = rho V. Sums of a
      // dozen products of volumes of order 0.1: round-off is ~1e-16, asked to 1e-13.
      const Eigen::VectorXd all = translation(body, side, 0, t);
      CHECK(all.dot(M * all) / t.squaredNorm() == kerf_test::relative(rho * V, 1e-13));
      for (const int s : {-1, 1}) {
        CAPTURE(s);
        const Eigen::VectorXd alone = translation(body, side, s, t);
        // One piece translating alone has the kinetic energy of its own mass.
        CHECK(alone.dot(M * alone) / t.squaredNorm() == kerf_test::relative(rho * volume[s + 1], 1e-13));
        // Its first moment int_p x rho (x-field on the piece, paired with its translation e_x):
        // exact for row sums and Bernstein (on a Tet4 the same diagonal); the virtual tet puts
        // the piece's mass on the element's centroid.
        const Eigen::VectorXd unit_x = translation(body, side, s, Eigen::Vector3d::UnitX());
        const Eigen::VectorXd x_field = body.piecewise_field(side, [&](const Eigen::Vector3d& x, int q) {
          return q == s ? Eigen::Vector3d(x.x(), 0, 0) : Eigen::Vector3d::Zero().eval();
        });
        const double first_moment = unit_x.dot(M * x_field);
        if (scheme == kerf::LumpingScheme::row_sum || scheme == kerf::LumpingScheme::bernstein)
          CHECK(first_moment == kerf_test::relative(rho * moment[s + 1].x(), 1e-13));
        if (scheme == kerf::LumpingScheme::virtual_tet) CHECK(first_moment == kerf_test::relative(rho * volume[s + 1] * 0.25, 1e-13));
      }
      // The two pieces share no mass.
      CHECK(std::abs(translation(body, side, -1, t).dot(M * translation(body, side, 1, t))) <= 1e-15 * rho);
      // Free fall: M acc = f has every phantom node accelerate at g: u'' = g, a'' = 0.
      const Eigen::Vector3d g(0.0, 0.0, -9.81);
      const Eigen::VectorXd f = kerf::lumped_gravity_load(body.model, rho, g, scheme, cut_body::subtets);
      const Eigen::VectorXd acc = Eigen::MatrixXd(M).ldlt().solve(f);
      const Eigen::VectorXd expected = body.piecewise_field(side, [&](const Eigen::Vector3d&, int) { return g; });
      CHECK((acc - expected).lpNorm<Eigen::Infinity>() <= 1e-12 * g.norm());
    }
  }
}

TEST_CASE("eqs. 81-82 give a separated piece the wrong inertia and open a falling tet at the cut") {
  const double V = 1.0 / 6.0, m = rho * V;
  const Eigen::Vector3d t(0.3, -0.2, 0.7), g(0.0, 0.0, -9.81);
  for (const TetCut& cut : tet_cuts()) {
    CAPTURE(cut.name);
    const cut_body::CutBody body(cut_body::unit_tet(), {cut_body::plane_surface(cut.normal, cut.offset, {0.25, 0.25, 0.25}, 3.0)},
                                 material);
    const auto side = [&](const Eigen::Vector3d& x) { return cut.normal.dot(x) < cut.offset ? -1 : 1; };
    const Eigen::SparseMatrix<double> M =
        kerf::lump_cut_xfem_mass(body.model, rho, kerf::LumpingScheme::schoch_eq_81_82, cut_body::subtets);
    // Eq. 81 alone carries a rigid translation of the whole body: m.
    const Eigen::VectorXd all = translation(body, side, 0, t);
    CHECK(all.dot(M * all) / t.squaredNorm() == kerf_test::relative(m, 1e-13));
    for (const int s : {-1, 1}) {
      CAPTURE(s);
      const int k = s < 0 ? static_cast<int>(cut.corners_minus.size()) : 4 - static_cast<int>(cut.corners_minus.size());
      const double vs = s < 0 ? cut.volume_minus : V - cut.volume_minus;
      const Eigen::VectorXd alone = translation(body, side, s, t);
      const double mass_seen = alone.dot(M * alone) / t.squaredNorm();
      // [derived] the k home nodes carry m/4 in u and (V_other/V) m/4 in a, the 4 - k others
      // (V_s / V) m/4 in a: (m/4)(k + k V_other/V + (4 - k) V_s/V); m itself for every 2:2 cut.
      const double predicted = m / 4.0 * (k + k * (V - vs) / V + (4 - k) * vs / V);
      CHECK(mass_seen == kerf_test::relative(predicted, 1e-13));
      CHECK(std::abs(mass_seen - rho * vs) > 0.05 * rho * vs);
      if (k == 2) CHECK(mass_seen == kerf_test::relative(m, 1e-13));
    }
    // Free fall with Schoch et al.'s consistent body load: u'' = g, but a_k'' = 4 <N_a>_p g on the
    // piece p where node a's enrichment is active, so the phantom node there falls at
    // (1 + 4 <N_a>_p) g: the tet opens. <N_a>_p from the closed-form moments (N = 1 - x - y - z, x, y, z).
    const Eigen::VectorXd f = kerf::lumped_gravity_load(body.model, rho, g, kerf::LumpingScheme::schoch_eq_81_82, cut_body::subtets);
    const Eigen::VectorXd acc = Eigen::MatrixXd(M).ldlt().solve(f);
    double largest_factor = 0.0;
    for (int a = 0; a < 4; ++a) {
      const bool home_minus = std::find(cut.corners_minus.begin(), cut.corners_minus.end(), a) != cut.corners_minus.end();
      const double vp = home_minus ? V - cut.volume_minus : cut.volume_minus; // the other side's piece
      const Eigen::Vector3d mp = home_minus ? Eigen::Vector3d(Eigen::Vector3d::Constant(1.0 / 24.0) - cut.moment_minus) : cut.moment_minus;
      const double integral = a == 0 ? vp - mp.sum() : mp[a - 1];
      const double factor = 1.0 + 4.0 * integral / vp;
      CAPTURE(a);
      CHECK((acc.segment<3>(3 * a) - g).norm() <= 1e-12 * g.norm());
      CHECK((acc.segment<3>(3 * (4 + a)) - (factor - 1.0) * g).norm() <= 1e-12 * g.norm());
      largest_factor = std::max(largest_factor, factor);
    }
    CHECK(largest_factor > 1.3);
  }
}

TEST_CASE("on a cut block the piece-wise lumped masses weigh each part exactly and row sums and Bernstein place it") {
  // The unit cube of 2 x 2 x 2 cells cut clean through by the tilted plane z = 0.37 + 0.1 x:
  // below it V = int (0.37 + 0.1 x) dx = 0.42, int x dV = 0.37 / 2 + 0.1 / 3, int z dV = int h^2 / 2 dx.
  const cut_body::CutBody body(kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {2, 2, 2}),
                               {cut_body::plane_surface({-0.1, 0, 1}, 0.37, {0.5, 0.5, 0.5}, 3.0)}, material);
  REQUIRE(body.enrichment.num_enrichments() > 0);
  const auto side = [](const Eigen::Vector3d& x) { return x.z() - 0.1 * x.x() < 0.37 ? -1 : 1; };
  const double volume_below = 0.42, x_below = 0.37 / 2.0 + 0.1 / 3.0;
  const double z_below = 0.5 * (0.37 * 0.37 + 0.37 * 0.1 + 0.01 / 3.0);
  const Eigen::Vector3d t(1.0, 2.0, -0.5);
  for (const kerf::LumpingScheme scheme : {kerf::LumpingScheme::bernstein, kerf::LumpingScheme::row_sum, kerf::LumpingScheme::hrz,
                                           kerf::LumpingScheme::virtual_tet, kerf::LumpingScheme::schoch_eq_81_82}) {
    CAPTURE(std::string(name_of(scheme)));
    const Eigen::SparseMatrix<double> M = kerf::lump_cut_xfem_mass(body.model, rho, scheme, cut_body::subtets);
    const Eigen::VectorXd all = translation(body, side, 0, t);
    CHECK(all.dot(M * all) / t.squaredNorm() == kerf_test::relative(rho, 1e-13));
    const Eigen::VectorXd below = translation(body, side, -1, t), above = translation(body, side, 1, t);
    const double mass_below = below.dot(M * below) / t.squaredNorm(), mass_above = above.dot(M * above) / t.squaredNorm();
    if (scheme == kerf::LumpingScheme::schoch_eq_81_82) {
      // Each part weighs more than it is, by the mass of the cut tets' other pieces it drags along.
      CHECK(mass_below > 1.02 * rho * volume_below);
      CHECK(mass_above > 1.02 * rho * (1.0 - volume_below));
      continue;
    }
    CHECK(mass_below == kerf_test::relative(rho * volume_below, 1e-13));
    CHECK(mass_above == kerf_test::relative(rho * (1.0 - volume_below), 1e-13));
    if (scheme == kerf::LumpingScheme::row_sum || scheme == kerf::LumpingScheme::bernstein) {
      const auto unit = [&](int c) { return translation(body, side, -1, Eigen::Vector3d::Unit(c)); };
      const Eigen::VectorXd position = body.piecewise_field(side, [](const Eigen::Vector3d& x, int s) {
        return s < 0 ? x : Eigen::Vector3d::Zero().eval();
      });
      CHECK(unit(0).dot(M * position) == kerf_test::relative(rho * x_below, 1e-13));
      CHECK(unit(1).dot(M * position) == kerf_test::relative(rho * 0.5 * volume_below, 1e-13));
      CHECK(unit(2).dot(M * position) == kerf_test::relative(rho * z_below, 1e-13));
    }
    // Free fall of the whole block: every phantom node at g.
    const Eigen::Vector3d g(0.0, -9.81, 0.0);
    const Eigen::VectorXd f = kerf::lumped_gravity_load(body.model, rho, g, scheme, cut_body::subtets);
    const Eigen::VectorXd acc = Eigen::MatrixXd(M).ldlt().solve(f);
    const Eigen::VectorXd expected = body.piecewise_field(side, [&](const Eigen::Vector3d&, int) { return g; });
    CHECK((acc - expected).lpNorm<Eigen::Infinity>() <= 1e-11 * g.norm());
  }
}

TEST_CASE("on a cut Tet10, Bernstein and HRZ stay positive and weigh each piece exactly, Bernstein places it; row sums go negative") {
  const double V = 1.0 / 6.0;
  const Eigen::Vector3d t(0.3, -0.2, 0.7), g(0.0, 0.0, -9.81);
  for (const TetCut& cut : tet_cuts()) {
    CAPTURE(cut.name);
    const cut_body::CutBody body(kerf::tet10_from_tet4(cut_body::unit_tet()),
                                 {cut_body::plane_surface(cut.normal, cut.offset, {0.25, 0.25, 0.25}, 3.0)}, material);
    REQUIRE(body.pieces.num_pieces(0) == 2);
    const auto side = [&](const Eigen::Vector3d& x) { return cut.normal.dot(x) < cut.offset ? -1 : 1; };
    const double volume[3] = {cut.volume_minus, 0.0, V - cut.volume_minus}; // indexed by side + 1
    const Eigen::Vector3d moment[3] = {cut.moment_minus, Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(1.0 / 24.0) - cut.moment_minus};
    for (const kerf::LumpingScheme scheme : {kerf::LumpingScheme::bernstein, kerf::LumpingScheme::hrz}) {
      CAPTURE(std::string(name_of(scheme)));
      const Eigen::SparseMatrix<double> M = kerf::lump_cut_xfem_mass(body.model, rho, scheme, cut_body::subtets);
      // Positive definite: every pivot of its LDL^T is positive.
      CHECK(Eigen::MatrixXd(M).ldlt().vectorD().minCoeff() > 0.0);
      double moment_error = 0.0;
      for (const int s : {-1, 1}) {
        CAPTURE(s);
        const Eigen::VectorXd alone = translation(body, side, s, t);
        CHECK(alone.dot(M * alone) / t.squaredNorm() == kerf_test::relative(rho * volume[s + 1], 1e-13));
        // The first moment, the x-field on the piece paired with its unit translations.
        const Eigen::VectorXd position = body.piecewise_field(side, [&](const Eigen::Vector3d& x, int q) {
          return q == s ? x : Eigen::Vector3d::Zero().eval();
        });
        for (int c = 0; c < 3; ++c)
          moment_error = std::max(moment_error,
                                  std::abs(translation(body, side, s, Eigen::Vector3d::Unit(c)).dot(M * position) - rho * moment[s + 1][c]));
      }
      // Bernstein: exact to round-off (sums of ten products of order 0.01; measured 1.6e-16 of
      // rho V at most); HRZ keeps the mass only, and places the pieces elsewhere (measured 0.0030,
      // 0.0116 and 0.0069 of rho V).
      if (scheme == kerf::LumpingScheme::bernstein) CHECK(moment_error <= 1e-13 * rho * V);
      if (scheme == kerf::LumpingScheme::hrz) CHECK(moment_error > 1e-4 * rho * V);
      MESSAGE(std::string(name_of(scheme)) << ": first moment error / rho V " << moment_error / (rho * V));
      // Free fall: M acc = f has every phantom node accelerate at g.
      const Eigen::VectorXd f = kerf::lumped_gravity_load(body.model, rho, g, scheme, cut_body::subtets);
      const Eigen::VectorXd acc = Eigen::MatrixXd(M).ldlt().solve(f);
      const Eigen::VectorXd expected = body.piecewise_field(side, [&](const Eigen::Vector3d&, int) { return g; });
      CHECK((acc - expected).lpNorm<Eigen::Infinity>() <= 1e-12 * g.norm());
    }
    // Row sums: corner 0's u entry is the sum of its two pieces' row sums, rho int_T N_0 = -rho V / 20.
    const Eigen::SparseMatrix<double> row_sum = kerf::lump_cut_xfem_mass(body.model, rho, kerf::LumpingScheme::row_sum, cut_body::subtets);
    CHECK(row_sum.coeff(0, 0) == kerf_test::relative(-rho * V / 20.0, 1e-12));
    // Bernstein's: rho int_T L_0^2 = rho V / 10, the two pieces' shares summed.
    const Eigen::SparseMatrix<double> bernstein = kerf::lump_cut_xfem_mass(body.model, rho, kerf::LumpingScheme::bernstein, cut_body::subtets);
    CHECK(bernstein.coeff(0, 0) == kerf_test::relative(rho * V / 10.0, 1e-12));
  }
}

TEST_CASE("a whole Tet10 gets rho V / 10 at every node from Bernstein, as from the virtual tet") {
  // The plane x = 2 misses the unit tet: one whole piece, no enrichment. Bernstein's corner
  // masses rho int L_a^2 and edge masses rho int 2 L_a L_b are both rho V / 10 (int over the
  // tet of L_a^i L_b^j = i! j! 3! V / (i + j + 3)!).
  const double V = 1.0 / 6.0;
  const cut_body::CutBody body(kerf::tet10_from_tet4(cut_body::unit_tet()), {cut_body::plane_surface({1, 0, 0}, 2.0, {0.25, 0.25, 0.25}, 3.0)},
                               material);
  REQUIRE(body.enrichment.num_enrichments() == 0);
  for (const kerf::LumpingScheme scheme : {kerf::LumpingScheme::bernstein, kerf::LumpingScheme::virtual_tet}) {
    CAPTURE(std::string(name_of(scheme)));
    const Eigen::SparseMatrix<double> M = kerf::lump_cut_xfem_mass(body.model, rho, scheme, cut_body::subtets);
    REQUIRE(M.rows() == 30);
    for (int i = 0; i < 30; ++i) CHECK(M.coeff(i, i) == kerf_test::relative(rho * V / 10.0, 1e-13));
    CHECK(M.nonZeros() == 30);
  }
}
