// Three uncoupled oscillators m u'' + c u' + k u = 0, one per component of a single DOF node,
// and the exact discrete solution of a one-step scheme applied to them.
#pragma once

#include "kerf/dynamics/linear_dynamic_system.hpp"
#include "kerf/fem/dof_map.hpp"

#include <complex>
#include <functional>

namespace oscillators {

inline Eigen::SparseMatrix<double> diagonal(const Eigen::Vector3d& d) {
  Eigen::SparseMatrix<double> A(3, 3);
  for (int i = 0; i < 3; ++i) A.insert(i, i) = d[i];
  A.makeCompressed();
  return A;
}

// M = diag(m), C = diag(c), K = diag(k), no Dirichlet DOF, no load.
inline kerf::LinearDynamicSystem make_system(const Eigen::Vector3d& m, const Eigen::Vector3d& c, const Eigen::Vector3d& k) {
  kerf::LinearDynamicSystem system;
  system.M = diagonal(m);
  system.C = diagonal(c);
  system.K = diagonal(k);
  system.dofs = kerf::make_dof_map(1, {});
  system.load = [](double) { return Eigen::VectorXd::Zero(3).eval(); };
  return system;
}

// The discrete solution u_n of m u'' + c u' + k u = 0 from (u0, v0) under a one-step method
// whose step is R(dt J) for the first-order form y' = J y, y = (u, v),
// J = [0 1; -k/m -c/m]. J's eigenvectors are (1, s) for the roots s of m s^2 + c s + k = 0,
// so y_n = sum_i c_i R(dt s_i)^n (1, s_i) with c_1 + c_2 = u0, c_1 s_1 + c_2 s_2 = v0.
// The average acceleration rule is the trapezoidal rule, R(z) = (1 + z/2) / (1 - z/2); backward
// Euler has R(z) = 1 / (1 - z). (Distinct roots assumed: not critically damped.)
inline double discrete_solution(double m, double c, double k, double u0, double v0, double dt, int n,
                                const std::function<std::complex<double>(std::complex<double>)>& R) {
  const std::complex<double> root = std::sqrt(std::complex<double>(c * c - 4.0 * m * k, 0.0));
  const std::complex<double> s1 = (-c + root) / (2.0 * m), s2 = (-c - root) / (2.0 * m);
  const std::complex<double> c2 = (v0 - s1 * u0) / (s2 - s1), c1 = u0 - c2;
  return (c1 * std::pow(R(dt * s1), n) + c2 * std::pow(R(dt * s2), n)).real();
}

inline std::complex<double> trapezoidal(std::complex<double> z) { return (1.0 + 0.5 * z) / (1.0 - 0.5 * z); }
inline std::complex<double> backward_euler(std::complex<double> z) { return 1.0 / (1.0 - z); }

} // namespace oscillators
