// A bar hanging under its own weight: a loaded problem whose exact solution is quadratic, so
// Tet10 reproduces it exactly (to round-off) at every point, an independent reference for the
// chapter programs run from the command line.
#pragma once

#include <Eigen/Core>
#include <sstream>
#include <string>

namespace support {

/// The beam [0, 0.03] x [0, 0.06] x [0, 0.2] under gravity -g e_z, held up by a uniform
/// traction rho g L on its top face z = L and free elsewhere. Equilibrium div sigma = rho g e_z
/// with the sides and the bottom free is solved exactly by the uniaxial stress sigma_zz = rho g z
/// (Timoshenko & Goodier, the prismatic bar under its own weight). Its strains
/// eps_zz = rho g z / E, eps_xx = eps_yy = -nu rho g z / E, no shear, integrate to
///   u_x = -nu rho g (x - x_c) z / E,   u_y = -nu rho g (y - y_c) z / E,
///   u_z = rho g / (2 E) (z^2 + nu ((x - x_c)^2 + (y - y_c)^2)),
/// up to a rigid motion, with (x_c, y_c) the centre of the section. The traction's total force
/// is rho g V e_z, balancing the weight. The rigid motion is fixed by holding three corners of
/// the top face at this field: more conditions than the six a free body needs, but consistent
/// ones, so the field still solves the constrained problem. It is quadratic, so it lies in the
/// Tet10 space; with exact loads (Tet10's are) the finite element solution is this field.
struct HangingBar {
  double young = 300e3, poisson = 0.35, density = 1070.0, g = 9.81;
  double a = 0.03, b = 0.06, length = 0.2;

  Eigen::Vector3d displacement(const Eigen::Vector3d& x) const {
    const double k = density * g / young, dx = x.x() - 0.5 * a, dy = x.y() - 0.5 * b, z = x.z();
    return {-poisson * k * dx * z, -poisson * k * dy * z, 0.5 * k * (z * z + poisson * (dx * dx + dy * dy))};
  }

  /// The scene: mesh of `cells` at `order`, the three held corners, gravity and the traction.
  std::string scene_json(int order, const std::string& cells = "[2, 3, 8]", const std::string& extra = "") const {
    std::ostringstream s;
    s.precision(17);
    s << R"({"mesh": {"box": {"min": [0, 0, 0], "max": [)" << a << ", " << b << ", " << length << R"(], "cells": )" << cells
      << R"(}, "order": )" << order << R"(}, "material": {"young": )" << young << R"(, "poisson": )" << poisson
      << R"(, "density": )" << density << R"(}, "dirichlet": [)";
    const Eigen::Vector3d held[3] = {{0, 0, length}, {a, 0, length}, {0, b, length}};
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& x = held[k];
      const Eigen::Vector3d u = displacement(x);
      s << (k ? ", " : "") << R"({"region": {"box": {"min": [)" << x[0] << ", " << x[1] << ", " << x[2] << R"(], "max": [)" << x[0]
        << ", " << x[1] << ", " << x[2] << R"(]}}, "displacement": [)" << u[0] << ", " << u[1] << ", " << u[2] << "]}";
    }
    s << R"(], "gravity": [0, 0, )" << -g << R"(], "traction": [{"region": {"box": {"min": [0, 0, )" << length << R"(], "max": [)" << a
      << ", " << b << ", " << length << R"(]}}, "total_force": [0, 0, )" << density * g * a * b * length << "]}]" << extra << "}";
    return s.str();
  }
};

} // namespace support
