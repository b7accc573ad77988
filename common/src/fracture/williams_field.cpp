#include "kerf/fracture/williams_field.hpp"

#include "kerf/io/probes_csv.hpp"

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace kerf {

namespace {

/// One displacement component C sqrt(r) f(theta): its angular factor f and f' = df/dtheta.
struct Angular {
  double f = 0.0;
  double df = 0.0;
};

/// The angular factors of (u_a, u_b, u_c) per unit C, for each mode, at theta (see the header).
struct ModeFactors {
  std::array<Angular, 2> mode_I, mode_II; ///< (u_a, u_b)
  Angular mode_III;                       ///< u_c
};

ModeFactors mode_factors(double theta, double kappa) {
  const double s = std::sin(theta / 2), c = std::cos(theta / 2);
  const double st = std::sin(theta), ct = std::cos(theta);
  ModeFactors m;
  m.mode_I[0] = {c * (kappa - ct), -0.5 * s * (kappa - ct) + c * st};
  m.mode_I[1] = {s * (kappa - ct), 0.5 * c * (kappa - ct) + s * st};
  m.mode_II[0] = {s * (kappa + 2 + ct), 0.5 * c * (kappa + 2 + ct) - s * st};
  m.mode_II[1] = {-c * (kappa - 2 + ct), 0.5 * s * (kappa - 2 + ct) + c * st};
  m.mode_III = {4 * s, 2 * c};
  return m;
}

/// C = K / (2 mu sqrt(2 pi)) for each mode.
Eigen::Vector3d mode_scales(const StressIntensityFactors& K, const LinearMaterial& material) {
  const double unit = 1.0 / (2.0 * material.mu() * std::sqrt(2.0 * std::numbers::pi));
  return unit * Eigen::Vector3d(K.K_I, K.K_II, K.K_III);
}

double kappa_plane_strain(const LinearMaterial& material) { return 3.0 - 4.0 * material.poisson; }

StraightFrontPolar polar_off_front(const StraightFrontFrame& front, const Eigen::Vector3d& x, const char* what) {
  const StraightFrontPolar p = front_polar(front, x);
  if (!(p.r > 0.0)) throw std::invalid_argument(std::string("williams_") + what + ": the point lies on the front, where the field is singular");
  return p;
}

/// The gradient in the frame, H_local(i, j) = du_i/dx_j with j in (a, b, c), of the field with
/// mode scales C at p: d/dx_a = cos(theta) d/dr - sin(theta)/r d/dtheta and
/// d/dx_b = sin(theta) d/dr + cos(theta)/r d/dtheta applied to sqrt(r) f(theta); d/dx_c = 0.
Eigen::Matrix3d local_gradient(const StraightFrontPolar& p, const ModeFactors& m, const Eigen::Vector3d& C) {
  const double st = std::sin(p.theta), ct = std::cos(p.theta), inv_sqrt_r = 1.0 / std::sqrt(p.r);
  const auto d_da = [&](const Angular& g) { return inv_sqrt_r * (0.5 * ct * g.f - st * g.df); };
  const auto d_db = [&](const Angular& g) { return inv_sqrt_r * (0.5 * st * g.f + ct * g.df); };
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 2; ++i) {
    H(i, 0) = C[0] * d_da(m.mode_I[i]) + C[1] * d_da(m.mode_II[i]);
    H(i, 1) = C[0] * d_db(m.mode_I[i]) + C[1] * d_db(m.mode_II[i]);
  }
  H(2, 0) = C[2] * d_da(m.mode_III);
  H(2, 1) = C[2] * d_db(m.mode_III);
  return H;
}

/// The stress in the frame at p, from the textbook's table (see the header).
Eigen::Matrix3d local_stress(const StraightFrontPolar& p, const StressIntensityFactors& K, double nu) {
  const double t = p.theta, scale = 1.0 / std::sqrt(2.0 * std::numbers::pi * p.r);
  const double s = std::sin(t / 2), c = std::cos(t / 2), s3 = std::sin(1.5 * t), c3 = std::cos(1.5 * t);
  const double sI = scale * K.K_I, sII = scale * K.K_II, sIII = scale * K.K_III;
  Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
  S(0, 0) = sI * c * (1 - s * s3) - sII * s * (2 + c * c3);
  S(1, 1) = sI * c * (1 + s * s3) + sII * s * c * c3;
  S(0, 1) = S(1, 0) = sI * c * s * c3 + sII * c * (1 - s * s3);
  S(2, 2) = nu * (S(0, 0) + S(1, 1));
  S(0, 2) = S(2, 0) = -sIII * s;
  S(1, 2) = S(2, 1) = sIII * c;
  return S;
}

} // namespace

StraightFrontFrame make_straight_front_frame(const Eigen::Vector3d& origin, const Eigen::Vector3d& ahead, const Eigen::Vector3d& normal) {
  if (!(ahead.norm() > 0.0) || !(normal.norm() > 0.0)) throw std::invalid_argument("make_straight_front_frame: a zero direction");
  const Eigen::Vector3d a = ahead.normalized(), b = normal.normalized();
  if (std::abs(a.dot(b)) > 1e-12) throw std::invalid_argument("make_straight_front_frame: `ahead` is not perpendicular to `normal`");
  StraightFrontFrame frame;
  frame.origin = origin;
  frame.R.col(0) = a;
  frame.R.col(1) = b;
  frame.R.col(2) = a.cross(b);
  return frame;
}

StraightFrontPolar front_polar(const StraightFrontFrame& front, const Eigen::Vector3d& x) {
  const Eigen::Vector3d y = front.local(x);
  StraightFrontPolar p;
  p.r = std::hypot(y[0], y[1]);
  p.theta = (y[1] == 0.0 && y[0] < 0.0) ? std::numbers::pi : std::atan2(y[1], y[0]);
  return p;
}

Eigen::Vector3d williams_displacement(const StraightFrontFrame& front, const StressIntensityFactors& K, const LinearMaterial& material,
                                      const Eigen::Vector3d& x) {
  const StraightFrontPolar p = front_polar(front, x);
  const ModeFactors m = mode_factors(p.theta, kappa_plane_strain(material));
  const Eigen::Vector3d C = mode_scales(K, material);
  const double sqrt_r = std::sqrt(p.r);
  const Eigen::Vector3d local(sqrt_r * (C[0] * m.mode_I[0].f + C[1] * m.mode_II[0].f),
                              sqrt_r * (C[0] * m.mode_I[1].f + C[1] * m.mode_II[1].f), sqrt_r * C[2] * m.mode_III.f);
  return front.R * local;
}

Eigen::Matrix3d williams_displacement_gradient(const StraightFrontFrame& front, const StressIntensityFactors& K,
                                               const LinearMaterial& material, const Eigen::Vector3d& x) {
  const StraightFrontPolar p = polar_off_front(front, x, "displacement_gradient");
  return front.R * local_gradient(p, mode_factors(p.theta, kappa_plane_strain(material)), mode_scales(K, material)) * front.R.transpose();
}

Eigen::Matrix3d williams_stress(const StraightFrontFrame& front, const StressIntensityFactors& K, const LinearMaterial& material,
                                const Eigen::Vector3d& x) {
  const StraightFrontPolar p = polar_off_front(front, x, "stress");
  return front.R * local_stress(p, K, material.poisson) * front.R.transpose();
}

WilliamsUnitFields williams_unit_fields(const StraightFrontFrame& front, const LinearMaterial& material, const Eigen::Vector3d& x) {
  const StraightFrontPolar p = polar_off_front(front, x, "unit_fields");
  const ModeFactors m = mode_factors(p.theta, kappa_plane_strain(material));
  const double unit = 1.0 / (2.0 * material.mu() * std::sqrt(2.0 * std::numbers::pi));
  WilliamsUnitFields fields;
  for (int mode = 0; mode < 3; ++mode) {
    StressIntensityFactors K;
    (mode == 0 ? K.K_I : mode == 1 ? K.K_II : K.K_III) = 1.0;
    fields.gradient[mode] = front.R * local_gradient(p, m, unit * Eigen::Vector3d::Unit(mode)) * front.R.transpose();
    fields.stress[mode] = front.R * local_stress(p, K, material.poisson) * front.R.transpose();
  }
  return fields;
}

Eigen::MatrixXd williams_displacements_at(const StraightFrontFrame& front, const StressIntensityFactors& K, const LinearMaterial& material,
                                          const Eigen::MatrixXd& points) {
  Eigen::MatrixXd u(points.rows(), 3);
  for (Eigen::Index i = 0; i < points.rows(); ++i) u.row(i) = williams_displacement(front, K, material, points.row(i).transpose()).transpose();
  return u;
}

void write_williams_displacement_file(const std::filesystem::path& file, const StraightFrontFrame& front, const StressIntensityFactors& K,
                                      const LinearMaterial& material, const Eigen::MatrixXd& points) {
  write_probes_csv(file, points, williams_displacements_at(front, K, material, points));
}

} // namespace kerf
