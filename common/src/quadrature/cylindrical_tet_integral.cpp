#include "kerf/quadrature/cylindrical_tet_integral.hpp"

#include "kerf/fem/tet_quadrature.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace kerf {

namespace {

// Sorted, with duplicates (to 1e-14 of the range) removed, restricted to [lo, hi] and holding both.
std::vector<double> breakpoints(std::vector<double> v, double lo, double hi) {
  v.push_back(lo);
  v.push_back(hi);
  std::sort(v.begin(), v.end());
  std::vector<double> out;
  for (const double x : v) {
    if (x < lo || x > hi) continue;
    if (out.empty() || x - out.back() > 1e-14 * (hi - lo)) out.push_back(x);
  }
  if (out.back() < hi) out.back() = hi;
  return out;
}

} // namespace

double cylindrical_tet_integral(const Eigen::Matrix<double, 4, 3>& X, const Eigen::Vector3d& origin, const Eigen::Vector3d& a,
                                const Eigen::Vector3d& c, double alpha, const std::function<double(double)>& g, int points) {
  if (!(alpha > -2.0)) throw std::invalid_argument("cylindrical_tet_integral: alpha must be > -2");
  const Eigen::Vector3d b = c.cross(a);
  // The corners in the line's frame (x_a, x_b, z).
  Eigen::Matrix<double, 4, 3> L;
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector3d y = X.row(k).transpose() - origin;
    L.row(k) << y.dot(a), y.dot(b), y.dot(c);
  }
  std::vector<double> u, w;
  gauss_jacobi_01(points, 0, u, w);
  const std::array<std::array<int, 2>, 6> edges{{{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}};

  // The heights where the section's integral is not smooth: the corners (the section changes
  // shape), where the line pierces a face (the singularity crosses the section's boundary), and
  // where an edge crosses the cut's half-plane x_b = 0, x_a < 0 (a corner of the section crosses
  // the jump of g).
  const double z_lo = L.col(2).minCoeff(), z_hi = L.col(2).maxCoeff();
  std::vector<double> z_breaks(L.col(2).data(), L.col(2).data() + 4);
  Eigen::Matrix3d J;
  for (int k = 0; k < 3; ++k) J.col(k) = (L.row(k + 1) - L.row(0)).transpose();
  const Eigen::Matrix3d Jinv = J.inverse();
  // Barycentric coordinates of the line's points (0, 0, z): lambda = l0 + z dl.
  const Eigen::Vector3d xi0 = Jinv * (-L.row(0).transpose()), dxi = Jinv.col(2);
  const Eigen::Vector4d l0(1.0 - xi0.sum(), xi0(0), xi0(1), xi0(2)), dl(-dxi.sum(), dxi(0), dxi(1), dxi(2));
  for (int k = 0; k < 4; ++k)
    if (dl(k) != 0.0) z_breaks.push_back(-l0(k) / dl(k));
  for (const auto& [i, j] : edges) {
    const double bi = L(i, 1), bj = L(j, 1);
    if (bi * bj >= 0.0) continue;
    const double s = bi / (bi - bj);
    if (L(i, 0) + s * (L(j, 0) - L(i, 0)) < 0.0) z_breaks.push_back(L(i, 2) + s * (L(j, 2) - L(i, 2)));
  }
  // An edge that passes at a distance delta from the line, at height z_c, makes I(z) vary on
  // the scale delta there: breakpoints at z_c +- delta 2^k grade the parts towards it.
  for (const auto& [i, j] : edges) {
    const Eigen::Vector2d p = L.row(i).head<2>().transpose(), e = (L.row(j) - L.row(i)).head<2>().transpose();
    const double dz = L(j, 2) - L(i, 2);
    if (e.squaredNorm() == 0.0 || dz == 0.0) continue;
    const double t = std::clamp(-p.dot(e) / e.squaredNorm(), 0.0, 1.0);
    const double delta = (p + t * e).norm(), z_c = L(i, 2) + t * dz;
    for (double step = delta; step < z_hi - z_lo && delta > 0.0; step *= 2.0) {
      z_breaks.push_back(z_c - step);
      z_breaks.push_back(z_c + step);
    }
  }
  z_breaks = breakpoints(z_breaks, z_lo, z_hi);

  // int over the triangle (origin, p, q) of r^alpha g(theta) dA, signed by its orientation, for
  // an edge p q that does not cross the cut line. With F the foot of the perpendicular from the
  // origin, d its length and s = d sinh(v) the position along the edge from F, the ray to the
  // edge has length d cosh(v), dtheta = dv / cosh(v), and
  //   int r^(alpha + 1) dr dtheta = d^(alpha + 2) cosh(v)^(alpha + 1) / (alpha + 2) dv:
  // smooth in v however close the edge passes to the origin.
  const auto triangle = [&](const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
    const Eigen::Vector2d e = (q - p).normalized();
    const Eigen::Vector2d F = p - p.dot(e) * e;
    const double d = F.norm(), orientation = p.x() * q.y() - p.y() * q.x();
    if (d == 0.0 || orientation == 0.0) return 0.0;
    const double v0 = std::asinh((p - F).dot(e) / d), v1 = std::asinh((q - F).dot(e) / d);
    // Parts of width <= 1 in v (cosh grows like e^v).
    const int parts = std::max(1, static_cast<int>(std::ceil(v1 - v0)));
    double sum = 0.0;
    for (int part = 0; part < parts; ++part) {
      const double a0 = v0 + (v1 - v0) * part / parts, a1 = v0 + (v1 - v0) * (part + 1) / parts;
      for (std::size_t k = 0; k < u.size(); ++k) {
        const double v = a0 + (a1 - a0) * u[k];
        const Eigen::Vector2d x = F + d * std::sinh(v) * e;
        sum += w[k] * (a1 - a0) * g(std::atan2(x.y(), x.x())) * std::pow(std::cosh(v), alpha + 1.0);
      }
    }
    return (orientation > 0.0 ? 1.0 : -1.0) * std::pow(d, alpha + 2.0) / (alpha + 2.0) * sum;
  };
  // The section at height z as a fan of signed triangles from the line's point (exact for any
  // position of the line, inside the section or not), its edges split where they cross the cut.
  const auto section = [&](double z) {
    std::vector<Eigen::Vector2d> corners;
    for (const auto& [i, j] : edges) {
      const double zi = L(i, 2), zj = L(j, 2);
      if ((z - zi) * (z - zj) > 0.0 || zi == zj) continue;
      const Eigen::RowVector3d p = L.row(i) + (z - zi) / (zj - zi) * (L.row(j) - L.row(i));
      corners.emplace_back(p(0), p(1));
    }
    if (corners.size() < 3) return 0.0;
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (const Eigen::Vector2d& p : corners) mean += p / static_cast<double>(corners.size());
    std::sort(corners.begin(), corners.end(), [&mean](const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
      return std::atan2(p.y() - mean.y(), p.x() - mean.x()) < std::atan2(q.y() - mean.y(), q.x() - mean.x());
    });
    double sum = 0.0;
    for (std::size_t k = 0; k < corners.size(); ++k) {
      const Eigen::Vector2d p = corners[k], q = corners[(k + 1) % corners.size()];
      // Split at the cut line x_b = 0, x_a < 0, where theta jumps from pi to -pi.
      if (p.y() * q.y() < 0.0) {
        const Eigen::Vector2d m = p + p.y() / (p.y() - q.y()) * (q - p);
        if (m.x() < 0.0) {
          sum += triangle(p, m) + triangle(m, q);
          continue;
        }
      }
      sum += triangle(p, q);
    }
    return sum;
  };
  double total = 0.0;
  for (std::size_t s = 0; s + 1 < z_breaks.size(); ++s) {
    const double z0 = z_breaks[s], z1 = z_breaks[s + 1];
    for (std::size_t q = 0; q < u.size(); ++q) {
      // z = z0 + (z1 - z0)(3u^2 - 2u^3), dz = 6 u (1 - u)(z1 - z0) du.
      const double v = u[q], z = z0 + (z1 - z0) * v * v * (3.0 - 2.0 * v);
      total += w[q] * 6.0 * v * (1.0 - v) * (z1 - z0) * section(z);
    }
  }
  return total;
}

} // namespace kerf
