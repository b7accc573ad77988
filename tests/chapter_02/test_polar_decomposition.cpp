// The polar decomposition F = R S (eq. 31), both algorithms, where it must hold and where
// Higham's iteration is known to fail: random F, nearly singular F, inverted F, singular F;
// and the derivative dR of polar_rotation_derivative against finite differences.
//
// Every F is built from its singular value decomposition, F = U diag(s) V^T with random
// rotations U and V, so that we choose exactly how close to singular it is.
#include "kerf/corotation/polar_decomposition.hpp"

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <string>

namespace {

// A uniformly distributed random rotation (a normalised Gaussian quaternion).
Eigen::Matrix3d random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  Eigen::Quaterniond q(gauss(rng), gauss(rng), gauss(rng), gauss(rng));
  return q.normalized().toRotationMatrix();
}

// F = U diag(s) V^T with random rotations U, V: det F has the sign of s0 s1 s2.
Eigen::Matrix3d matrix_with_singular_values(const Eigen::Vector3d& s, std::mt19937& rng) {
  return random_rotation(rng) * s.asDiagonal() * random_rotation(rng).transpose();
}

// Singular values 1, a, b with a, b log-uniform in [1e-8, 1]: condition numbers up to 1e8,
// including the hard case of two small singular values.
Eigen::Vector3d near_singular_values(std::mt19937& rng) {
  std::uniform_real_distribution<double> exponent(-8.0, 0.0);
  return {1.0, std::pow(10.0, exponent(rng)), std::pow(10.0, exponent(rng))};
}

// What every decomposition that claims a rotation must satisfy, measured.
struct PolarErrors {
  double orthogonality = 0; // |R^T R - I|_max
  double det_error = 0;     // |det R - 1|
  double asymmetry = 0;     // |S - S^T|_max / |S|_max
  double reconstruction = 0; // |R S - F|_max / |F|_max
};

PolarErrors polar_errors(const kerf::PolarDecomposition& p, const Eigen::Matrix3d& F) {
  PolarErrors e;
  e.orthogonality = (p.R.transpose() * p.R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  e.det_error = std::abs(p.R.determinant() - 1.0);
  e.asymmetry = (p.S - p.S.transpose()).cwiseAbs().maxCoeff() / p.S.cwiseAbs().maxCoeff();
  e.reconstruction = (p.R * p.S - F).cwiseAbs().maxCoeff() / F.cwiseAbs().maxCoeff();
  return e;
}

// The eigenvalues of the symmetric part of S, in increasing order.
Eigen::Vector3d stretch_eigenvalues(const kerf::PolarDecomposition& p) {
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(0.5 * (p.S + p.S.transpose())).eigenvalues();
}

} // namespace

TEST_CASE("polar decomposition of 1000 random and 1000 nearly singular F with det F > 0, both algorithms") {
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> moderate(0.2, 3.0);
  for (const bool near_singular : {false, true}) {
    CAPTURE(near_singular);
    PolarErrors worst_higham, worst_svd;
    // Higham's S = R^T F is only as symmetric as R is close to the exact polar factor, and that
    // factor is ill-conditioned when the two smallest singular values are: a relative change of
    // eps in F moves it by ~eps s0 / (s1 + s2) (Higham, Functions of Matrices, thm. 8.9). We
    // measure the asymmetry in units of that condition number.
    double worst_higham_scaled_asymmetry = 0.0;
    double worst_eigenvalue_error = 0.0; // |eig(S) - s| / s_max: S's eigenvalues are F's singular values
    int max_higham_iterations = 0;
    bool all_converged = true;
    for (int sample = 0; sample < 1000; ++sample) {
      const Eigen::Vector3d s = near_singular ? near_singular_values(rng) : Eigen::Vector3d(moderate(rng), moderate(rng), moderate(rng));
      const Eigen::Matrix3d F = matrix_with_singular_values(s, rng);
      Eigen::Vector3d s_sorted = s;
      std::sort(s_sorted.data(), s_sorted.data() + 3);
      for (const bool higham : {true, false}) {
        const kerf::PolarDecomposition p = higham ? kerf::polar_higham(F) : kerf::polar_svd(F);
        const PolarErrors e = polar_errors(p, F);
        PolarErrors& worst = higham ? worst_higham : worst_svd;
        worst.orthogonality = std::max(worst.orthogonality, e.orthogonality);
        worst.det_error = std::max(worst.det_error, e.det_error);
        worst.asymmetry = std::max(worst.asymmetry, e.asymmetry);
        worst.reconstruction = std::max(worst.reconstruction, e.reconstruction);
        worst_eigenvalue_error = std::max(worst_eigenvalue_error, (stretch_eigenvalues(p) - s_sorted).cwiseAbs().maxCoeff() / s_sorted[2]);
        // Positive definite: the smallest eigenvalue of S is the smallest singular value, >= 1e-8,
        // far above the 1e-16 |F| that round-off can move it by.
        CHECK(stretch_eigenvalues(p)[0] > 0.0);
        if (higham) {
          worst_higham_scaled_asymmetry = std::max(worst_higham_scaled_asymmetry, e.asymmetry * (s_sorted[0] + s_sorted[1]) / s_sorted[2]);
          all_converged = all_converged && p.converged;
          max_higham_iterations = std::max(max_higham_iterations, p.iterations);
        }
      }
    }
    MESSAGE(std::string(near_singular ? "nearly singular" : "random") << " F: Higham orthogonality " << worst_higham.orthogonality << ", det "
                                                           << worst_higham.det_error << ", asymmetry " << worst_higham.asymmetry
                                                           << ", |RS-F| " << worst_higham.reconstruction << ", max iterations "
                                                           << max_higham_iterations << "; SVD orthogonality " << worst_svd.orthogonality
                                                           << ", det " << worst_svd.det_error << ", asymmetry " << worst_svd.asymmetry
                                                           << ", |RS-F| " << worst_svd.reconstruction << "; eig(S) vs s "
                                                           << worst_eigenvalue_error << "; Higham asymmetry * (s1 + s2) / s0 "
                                                           << worst_higham_scaled_asymmetry);
    CHECK(all_converged);
    // Scaled Newton needs about log2(log2(cond)) + a few steps: 10 even at cond = 1e8.
    CHECK(max_higham_iterations <= 12);
    // Both algorithms end in a product of a few rotations and a Newton step that squares the
    // orthogonality error, so R is orthogonal to a few ulps: 1e-12 is a hundred times that.
    for (const PolarErrors* worst : {&worst_higham, &worst_svd}) {
      CHECK(worst->orthogonality < 1e-12);
      CHECK(worst->det_error < 1e-12);
      // F = R S holds to the round-off of one 3x3 product, a few 1e-16 of |F|, for both.
      CHECK(worst->reconstruction < 1e-12);
    }
    // The SVD's S = V diag(s) V^T is symmetric by construction, to round-off.
    CHECK(worst_svd.asymmetry < 1e-12);
    // Higham's S = R^T F is symmetric to round-off times the conditioning of R: 1e-12 for
    // moderate F (s >= 0.2, condition <= 15). For nearly singular F we measured asymmetries
    // up to 6e-10, but at most 3e-16 in units of the condition number; we allow 1e-14.
    if (!near_singular) CHECK(worst_higham.asymmetry < 1e-12);
    CHECK(worst_higham_scaled_asymmetry < 1e-14);
    // The eigenvalues of S are the singular values of F, to round-off relative to |F|.
    CHECK(worst_eigenvalue_error < 1e-12);
  }
}

TEST_CASE("an inverted F (det F < 0): Higham reaches a reflection, the SVD variant a rotation and an inverted S") {
  std::mt19937 rng(32);
  std::uniform_real_distribution<double> moderate(0.2, 3.0);
  for (int sample = 0; sample < 200; ++sample) {
    CAPTURE(sample);
    // One negative singular value: a reflected (inside-out) element. Every 4th sample nearly
    // flat (s2 = -1e-6), as an element just past inversion is.
    const Eigen::Vector3d s(moderate(rng), moderate(rng), sample % 4 == 0 ? -1e-6 : -moderate(rng));
    const Eigen::Matrix3d F = matrix_with_singular_values(s, rng);
    REQUIRE(F.determinant() < 0.0);

    const kerf::PolarDecomposition higham = kerf::polar_higham(F);
    CHECK_FALSE(higham.converged);
    // The orthogonal factor of an inverted F is a reflection, which is why Higham alone fails.
    CHECK(std::abs(higham.R.determinant() + 1.0) < 1e-12);

    const kerf::PolarDecomposition svd = kerf::polar_svd(F);
    const PolarErrors e = polar_errors(svd, F);
    CHECK(e.orthogonality < 1e-12);
    CHECK(e.det_error < 1e-12); // det R = +1: a rotation
    CHECK(e.asymmetry < 1e-12);
    CHECK(e.reconstruction < 1e-12);
    // The inversion lands in S: exactly one negative eigenvalue. The sign goes to the smallest
    // singular value (whichever of s had the minus), the least stretch that explains det F < 0.
    const Eigen::Vector3d eig = stretch_eigenvalues(svd);
    CHECK(eig[0] < 0.0);
    CHECK(eig[1] > 0.0);
    CHECK(std::abs(eig[0] + s.cwiseAbs().minCoeff()) < 1e-12 * s.cwiseAbs().maxCoeff());
  }
}

TEST_CASE("a singular F (det F = 0): the SVD variant still gives a rotation, Higham's iteration does not start") {
  // Exactly singular in floating point: integer entries whose third column is the sum of the
  // first two, a flattened diagonal, a zero column. Their determinants round to exactly 0.
  Eigen::Matrix3d dependent_columns, flattened, zero_column;
  dependent_columns << 1, 2, 3, 4, 5, 9, 7, 8, 15;
  flattened = Eigen::Vector3d(1.0, 2.0, 0.0).asDiagonal();
  zero_column << 1, 0, 0, 2, 0, 1, 0, 0, 3;
  for (const Eigen::Matrix3d& F : {dependent_columns, flattened, zero_column}) {
    CAPTURE(F);
    REQUIRE(F.determinant() == 0.0);
    const kerf::PolarDecomposition higham = kerf::polar_higham(F);
    CHECK_FALSE(higham.converged);
    const kerf::PolarDecomposition svd = kerf::polar_svd(F);
    const PolarErrors e = polar_errors(svd, F);
    CHECK(e.orthogonality < 1e-12);
    CHECK(e.det_error < 1e-12);
    CHECK(e.asymmetry < 1e-12);
    CHECK(e.reconstruction < 1e-12);
    // S keeps the zero singular value: one eigenvalue at round-off level.
    CHECK(stretch_eigenvalues(svd).cwiseAbs().minCoeff() < 1e-12 * svd.S.norm());
  }
}

TEST_CASE("polar_rotation_derivative equals the central difference of polar_svd's R") {
  std::mt19937 rng(33);
  std::uniform_real_distribution<double> moderate(0.3, 3.0);
  std::normal_distribution<double> gauss(0.0, 1.0);
  // h = 1e-6 with |dF| = 1 and singular values in [0.3, 3]. The central difference's
  // truncation error is h^2/6 |R'''| ~ 1e-12 / s^3 ~ 1e-11; its round-off is the SVD's error
  // in R, a few 1e-16 / (s1 + s2), divided by h: ~1e-9. Both are absolute (per unit |dF|),
  // while |dR| itself ranges from ~0.05 to ~3; so we bound |dR - dR_fd| by 1e-8 |dF|, ten
  // times the round-off estimate, and the relative error by 1e-7.
  const double h = 1e-6;
  double worst = 0.0, worst_relative = 0.0, smallest_derivative = 1e300;
  for (int sample = 0; sample < 200; ++sample) {
    const Eigen::Matrix3d F = matrix_with_singular_values({moderate(rng), moderate(rng), moderate(rng)}, rng);
    Eigen::Matrix3d dF;
    for (int i = 0; i < 9; ++i) dF(i) = gauss(rng);
    dF /= dF.norm();
    const Eigen::Matrix3d dR = kerf::polar_rotation_derivative(kerf::polar_svd(F), dF);
    const Eigen::Matrix3d dR_fd = (kerf::polar_svd(F + h * dF).R - kerf::polar_svd(F - h * dF).R) / (2.0 * h);
    worst = std::max(worst, (dR - dR_fd).norm());
    worst_relative = std::max(worst_relative, (dR - dR_fd).norm() / dR_fd.norm());
    smallest_derivative = std::min(smallest_derivative, dR_fd.norm());
    // The same derivative belongs to Higham's R: it is the same rotation where det F > 0.
    CHECK((kerf::polar_rotation_derivative(kerf::polar_higham(F), dF) - dR).norm() < 1e-12);
  }
  MESSAGE("polar_rotation_derivative vs central difference: worst |dR - dR_fd| " << worst << " per unit |dF|, worst relative "
                                                                                 << worst_relative << " (smallest |dR| "
                                                                                 << smallest_derivative << ")");
  CHECK(worst < 1e-8);
  CHECK(worst_relative < 1e-7);
  // The test can fail: the derivatives are not tiny, so a wrong formula shows.
  CHECK(smallest_derivative > 1e-2);
}
