// One enriched Tet4: the side-operator form of the stiffness (xfem_tet4_stiffness) against
// Schoch et al.'s eqs. 60-63 typed in block by block for all 16 sign patterns of H, against eqs.
// 54-57 with the generalized (unshifted) Heaviside values, and the change of basis that makes
// the two enrichments span the same space.
#include "kerf/fem/tet_stiffness.hpp"
#include "kerf/xfem/xfem_element.hpp"

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <random>

namespace {

// A random positively oriented tet of size about 1 cm, away from degenerate.
Eigen::Matrix<double, 4, 3> random_tet(std::mt19937& rng) {
  std::uniform_real_distribution<double> jitter(-0.003, 0.003);
  Eigen::Matrix<double, 4, 3> X;
  X << 0, 0, 0, 0.01, 0, 0, 0, 0.01, 0, 0, 0, 0.01;
  for (int a = 0; a < 4; ++a)
    for (int d = 0; d < 3; ++d) X(a, d) += jitter(rng);
  return X;
}

using Matrix24 = Eigen::Matrix<double, 24, 24>;
using Block = Eigen::Matrix3d;

Block K_block(const Eigen::Matrix<double, 12, 12>& K, int i, int j) { return K.block<3, 3>(3 * i, 3 * j); }

// Eqs. 60-63 with the misprint of eq. 61 corrected (its second case is H_j = -1).
Matrix24 eqs_60_to_63(const Eigen::Matrix<double, 12, 12>& K, double Va_V, double Vb_V, const Eigen::Vector4i& H) {
  Matrix24 KX = Matrix24::Zero();
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      const Block Kij = K_block(K, i, j);
      KX.block<3, 3>(3 * i, 3 * j) = Kij;                                           // eq. 60
      KX.block<3, 3>(3 * i, 12 + 3 * j) = H[j] == +1 ? Block(-Vb_V * Kij) : Block(+Va_V * Kij); // eq. 61
      KX.block<3, 3>(12 + 3 * i, 3 * j) = H[i] == +1 ? Block(-Vb_V * Kij) : Block(+Va_V * Kij); // eq. 62
      Block aa = Block::Zero();                                                     // eq. 63
      if (H[i] == +1 && H[j] == +1) aa = Vb_V * Kij;
      if (H[i] == -1 && H[j] == -1) aa = Va_V * Kij;
      KX.block<3, 3>(12 + 3 * i, 12 + 3 * j) = aa;
    }
  return KX;
}

// Eqs. 54-57 for any values Psi_a,i and Psi_b,i.
Matrix24 eqs_54_to_57(const Eigen::Matrix<double, 12, 12>& K, double Va_V, double Vb_V, const Eigen::Vector4d& psi_a,
                      const Eigen::Vector4d& psi_b) {
  Matrix24 KX = Matrix24::Zero();
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      const Block Kij = K_block(K, i, j);
      KX.block<3, 3>(3 * i, 3 * j) = Kij;
      KX.block<3, 3>(3 * i, 12 + 3 * j) = (Va_V * psi_a[j] + Vb_V * psi_b[j]) * Kij;
      KX.block<3, 3>(12 + 3 * i, 3 * j) = (Va_V * psi_a[i] + Vb_V * psi_b[i]) * Kij;
      KX.block<3, 3>(12 + 3 * i, 12 + 3 * j) = (Va_V * psi_a[i] * psi_a[j] + Vb_V * psi_b[i] * psi_b[j]) * Kij;
    }
  return KX;
}

// Relative difference in the max norm, scaled by the largest entry of K. Both sides sum at most
// two products of an entry of K by numbers in [0, 1], so they agree to a few ulps of |K|_max:
// 1e-12 leaves three orders of magnitude of room and still catches any wrong factor or sign.
double relative_difference(const Matrix24& A, const Matrix24& B, const Eigen::Matrix<double, 12, 12>& K) {
  return (A - B).cwiseAbs().maxCoeff() / K.cwiseAbs().maxCoeff();
}

} // namespace

TEST_CASE("xfem element: the side-operator stiffness is eqs. 60-63 for every sign pattern of H") {
  std::mt19937 rng(20261123);
  std::uniform_real_distribution<double> fraction(0.02, 0.98);
  const kerf::LinearMaterial material{300e3, 0.35, 1070.0};
  double worst = 0.0;
  int patterns = 0;
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::Matrix<double, 12, 12> K = kerf::tet4_stiffness(random_tet(rng), material);
    const double Va_V = fraction(rng), Vb_V = 1.0 - Va_V;
    for (int bits = 0; bits < 16; ++bits) {
      Eigen::Vector4i H;
      Eigen::Vector4d psi_a, psi_b;
      for (int i = 0; i < 4; ++i) {
        H[i] = (bits >> i) & 1 ? +1 : -1;
        psi_a[i] = kerf::shifted_enrichment(+1, H[i]);
        psi_b[i] = kerf::shifted_enrichment(-1, H[i]);
      }
      // Eqs. 58-59: Psi_a = 0 above, +1 below; Psi_b = -1 above, 0 below.
      for (int i = 0; i < 4; ++i) {
        CHECK(psi_a[i] == (H[i] > 0 ? 0.0 : 1.0));
        CHECK(psi_b[i] == (H[i] > 0 ? -1.0 : 0.0));
      }
      const Matrix24 KX = kerf::xfem_tet4_stiffness(K, Va_V, psi_a, psi_b);
      const double d = relative_difference(KX, eqs_60_to_63(K, Va_V, Vb_V, H), K);
      worst = std::max(worst, d);
      CHECK(d <= 1e-12);
      // The generic eqs. 54-57 with the shifted values are the same matrix.
      CHECK(relative_difference(KX, eqs_54_to_57(K, Va_V, Vb_V, psi_a, psi_b), K) <= 1e-12);
      ++patterns;
    }
  }
  MESSAGE("eqs. 60-63 vs side operators: worst relative difference " << worst << " over " << patterns << " cases");
}

TEST_CASE("xfem element: a corner without enriched DOFs (Psi = 0) gets zero a-rows and a-columns") {
  std::mt19937 rng(7);
  const kerf::LinearMaterial material{300e3, 0.35, 1070.0};
  const Eigen::Matrix<double, 12, 12> K = kerf::tet4_stiffness(random_tet(rng), material);
  const Eigen::Vector4i H(+1, -1, +1, -1);
  Eigen::Vector4d psi_a, psi_b;
  for (int i = 0; i < 4; ++i) {
    psi_a[i] = kerf::shifted_enrichment(+1, H[i]);
    psi_b[i] = kerf::shifted_enrichment(-1, H[i]);
  }
  psi_a[2] = psi_b[2] = 0.0; // corner 2 not enriched
  const Matrix24 KX = kerf::xfem_tet4_stiffness(K, 0.3, psi_a, psi_b);
  CHECK(KX.block<24, 3>(0, 12 + 6).cwiseAbs().maxCoeff() == 0.0);
  CHECK(KX.block<3, 24>(12 + 6, 0).cwiseAbs().maxCoeff() == 0.0);
  // The other blocks are still eqs. 60-63's.
  Matrix24 expected = eqs_60_to_63(K, 0.3, 0.7, H);
  expected.block<24, 3>(0, 12 + 6).setZero();
  expected.block<3, 24>(12 + 6, 0).setZero();
  CHECK(relative_difference(KX, expected, K) <= 1e-12);
  // The uncut limit V_a = V: eqs. 60-63 with V_b = 0, corner 2's rows and columns still empty.
  Matrix24 expected_above = eqs_60_to_63(K, 1.0, 0.0, H);
  expected_above.block<24, 3>(0, 12 + 6).setZero();
  expected_above.block<3, 24>(12 + 6, 0).setZero();
  CHECK(relative_difference(kerf::xfem_tet4_stiffness(K, 1.0, psi_a, psi_b), expected_above, K) <= 1e-12);
}

TEST_CASE("xfem element: the generalized Heaviside (eqs. 54-57 with Psi_a = +1, Psi_b = -1) spans the same space") {
  // Phi_i (H - H_i)/2 a_i = Phi_i H (a_i / 2) - Phi_i (H_i / 2) a_i: the shifted DOFs [u; a]
  // are the generalized ones [u - H a / 2; a / 2]. With that matrix A, K_shifted = A^T K_gen A.
  std::mt19937 rng(11);
  const kerf::LinearMaterial material{300e3, 0.35, 1070.0};
  const Eigen::Matrix<double, 12, 12> K = kerf::tet4_stiffness(random_tet(rng), material);
  const double Va_V = 0.37, Vb_V = 1.0 - Va_V;
  const Eigen::Vector4d gen_a = Eigen::Vector4d::Constant(1.0), gen_b = Eigen::Vector4d::Constant(-1.0);
  const Matrix24 K_gen = kerf::xfem_tet4_stiffness(K, Va_V, gen_a, gen_b);
  CHECK(relative_difference(K_gen, eqs_54_to_57(K, Va_V, Vb_V, gen_a, gen_b), K) <= 1e-12);
  // Eqs. 55 and 57 with H = +-1: K^ua = (V_a - V_b)/V K, K^aa = K.
  CHECK((K_gen.block<12, 12>(0, 12) - (Va_V - Vb_V) * K).cwiseAbs().maxCoeff() <= 1e-12 * K.cwiseAbs().maxCoeff());
  CHECK((K_gen.block<12, 12>(12, 12) - K).cwiseAbs().maxCoeff() <= 1e-12 * K.cwiseAbs().maxCoeff());
  for (int bits = 0; bits < 16; ++bits) {
    Eigen::Vector4i H;
    Eigen::Vector4d psi_a, psi_b;
    Matrix24 A = Matrix24::Identity();
    for (int i = 0; i < 4; ++i) {
      H[i] = (bits >> i) & 1 ? +1 : -1;
      psi_a[i] = kerf::shifted_enrichment(+1, H[i]);
      psi_b[i] = kerf::shifted_enrichment(-1, H[i]);
      A.block<3, 3>(3 * i, 12 + 3 * i) = -0.5 * H[i] * Eigen::Matrix3d::Identity();
      A.block<3, 3>(12 + 3 * i, 12 + 3 * i) = 0.5 * Eigen::Matrix3d::Identity();
    }
    const Matrix24 K_shift = kerf::xfem_tet4_stiffness(K, Va_V, psi_a, psi_b);
    CHECK(relative_difference(K_shift, A.transpose() * K_gen * A, K) <= 1e-12);
    // A different matrix all the same: the coupling blocks differ by O(|K|).
    CHECK(relative_difference(K_shift, K_gen, K) > 0.1);
  }
}
