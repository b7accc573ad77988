#include "kerf/quadrature/moment_fitting.hpp"

#include "kerf/fem/tet_quadrature.hpp"
#include "kerf/quadrature/polyhedron_moments.hpp"

#include <Eigen/SVD>
#include <array>
#include <cmath>
#include <mutex>
#include <stdexcept>

namespace kerf {

namespace {

// Keast's 24-point rule of degree 6 (Keast 1986, also Zhang, Cui and Liu 2009): three orbits of
// barycentric coordinates (a, a, a, 1 - 3a) with 4 points each and one orbit (a, a, b, c) with 12.
// Only the points matter here: the weights are fitted.
std::vector<Eigen::Vector3d> keast_24_points() {
  std::vector<Eigen::Vector4d> barycentric;
  for (double a : {0.2146028712591517, 0.0406739585346113, 0.3223378901422757}) {
    const double b = 1.0 - 3.0 * a;
    for (int i = 0; i < 4; ++i) {
      Eigen::Vector4d l = Eigen::Vector4d::Constant(a);
      l[i] = b;
      barycentric.push_back(l);
    }
  }
  const double a = 0.0636610018750175, b = 0.2696723314583159, c = 0.6030056647916491;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      if (j == i) continue;
      Eigen::Vector4d l = Eigen::Vector4d::Constant(a);
      l[i] = b;
      l[j] = c;
      barycentric.push_back(l);
    }
  std::vector<Eigen::Vector3d> points;
  // Reference corner k has barycentric coordinate k: xi = (l1, l2, l3).
  for (const Eigen::Vector4d& l : barycentric) points.emplace_back(l[1], l[2], l[3]);
  return points;
}

MomentFittingSystem build_system(int degree) {
  MomentFittingSystem system;
  system.degree = degree;
  system.basis = orthonormal_basis_reference_tet(degree);
  system.points = moment_fitting_points(degree, &system.point_set);
  const auto M = static_cast<Eigen::Index>(system.basis.exponents.size());
  const auto N = static_cast<Eigen::Index>(system.points.size());
  Eigen::MatrixXd A(M, N);
  for (Eigen::Index j = 0; j < N; ++j) A.col(j) = system.basis.evaluate(system.points[static_cast<std::size_t>(j)]);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd& s = svd.singularValues();
  Eigen::VectorXd inverse = Eigen::VectorXd::Zero(s.size());
  for (Eigen::Index k = 0; k < s.size(); ++k)
    if (s[k] > MomentFittingSystem::cutoff * s[0]) {
      inverse[k] = 1.0 / s[k];
      ++system.rank;
      system.condition = s[0] / s[k];
    }
  system.pseudo_inverse = svd.matrixV() * inverse.asDiagonal() * svd.matrixU().transpose();
  return system;
}

} // namespace

std::vector<Eigen::Vector3d> moment_fitting_points(int degree, std::string* description) {
  if (degree < 1 || degree > 6) throw std::invalid_argument("moment_fitting_points: degree must be in 1..6");
  if (degree <= 2) {
    if (description) *description = "Keast 24 (symmetric, degree-6 rule's points)";
    return keast_24_points();
  }
  const int n = degree + 1;
  if (description) *description = "Stroud conical product " + std::to_string(n) + "^3";
  return tet_quadrature_rule(2 * n - 1).points; // that rule has n points per direction
}

const MomentFittingSystem& tet_moment_fitting_system(int degree) {
  if (degree < 1 || degree > 6) throw std::invalid_argument("tet_moment_fitting_system: degree must be in 1..6");
  // Each degree's system is built on its first use only (degree 6's SVD is the costly one).
  static std::array<std::once_flag, 6> built;
  static std::array<MomentFittingSystem, 6> systems;
  const auto k = static_cast<std::size_t>(degree - 1);
  std::call_once(built[k], [&] { systems[k] = build_system(degree); });
  return systems[k];
}

Eigen::VectorXd fit_reference_weights(const MomentFittingSystem& system, const Eigen::VectorXd& basis_moments) {
  return system.pseudo_inverse * basis_moments;
}

} // namespace kerf
