// The fields a crack-tip test checks a support::TipBody (cut_body.hpp) against: Williams's
// near-front field of a straight front with its branch coefficients, and linear fields whose
// stress leaves a cut traction-free. (Williams's field is written here from the textbook, as an
// independent check of fracture/williams_field.hpp's.)
#pragma once

#include "kerf/cut/crack_front.hpp"
#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/fem/linear_material.hpp"
#include "kerf/xfem/branch_enrichment.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"

#include "support/cut_body.hpp"

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

namespace support {

// A straight front: a point of it and its frame, a ahead, b the cut's normal, c = a x b along it.
struct StraightFront {
  Eigen::Vector3d origin{0, 0, 0}, a{1, 0, 0}, b{0, 1, 0}, c{0, 0, 1};
  StraightFront(const Eigen::Vector3d& o, const Eigen::Vector3d& ahead, const Eigen::Vector3d& normal)
      : origin(o), a(ahead.normalized()), b(normal.normalized()), c(a.cross(b)) {}
};

// Williams's plane-strain modes I and II about `front` (Anderson, Fracture Mechanics, table
// 2.2): u = K / (2 mu) sqrt(r / 2 pi) (f_a(theta) a + f_b(theta) b), theta = +pi on the cut.
// `cut_side` (+1 or -1) is for a point the model puts ON the cut (a node with
// BranchEnrichment::cut_side != 0): theta = cut_side pi whatever the sign of x_b's round-off, as
// CrackFronts::polar takes it. The field is two-valued there, and a node's standard DOF holds
// the value of the model's side: a node of a box mesh is rarely exactly on a cut given by round
// numbers (the slab's node row y = -0.3 + 2/3 0.6 = 0.09999999999999998 lies 2.8e-17 below the
// cut y = 0.1, which chapter 4's snap and the model count as on it), and atan2 of that
// round-off gives the other face's value, off by the crack opening.
inline Eigen::Vector3d williams(const StraightFront& front, double K_I, double K_II, const kerf::LinearMaterial& material,
                                const Eigen::Vector3d& x, int cut_side = 0) {
  const Eigen::Vector3d y = x - front.origin;
  const double x_a = y.dot(front.a), x_b = y.dot(front.b);
  const double r = std::hypot(x_a, x_b);
  const double theta = cut_side != 0 ? cut_side * M_PI : (x_b == 0.0 && x_a < 0.0 ? M_PI : std::atan2(x_b, x_a));
  const double kappa = 3.0 - 4.0 * material.poisson;
  const double s = std::sin(theta / 2.0), c = std::cos(theta / 2.0);
  const double scale = std::sqrt(r / (2.0 * M_PI)) / (2.0 * material.mu());
  const double u_a = K_I * c * (kappa - 1.0 + 2.0 * s * s) + K_II * s * (kappa + 1.0 + 2.0 * c * c);
  const double u_b = K_I * s * (kappa + 1.0 - 2.0 * c * c) - K_II * c * (kappa - 1.0 - 2.0 * s * s);
  return scale * (u_a * front.a + u_b * front.b);
}

// The constant vectors c_l with Williams's modes I and II = sum_l F_l c_l in the front frame
// (A = K / (2 mu sqrt(2 pi))):
//   mode I:  c_1 = A_I (kappa + 1) b,  c_2 = A_I (kappa - 1) a,  c_3 = A_I a,  c_4 = -A_I b;
//   mode II: c_1 = A_II (kappa + 1) a, c_2 = -A_II (kappa - 1) b, c_3 = A_II b, c_4 = A_II a.
inline std::array<Eigen::Vector3d, 4> williams_branch_coefficients(const StraightFront& front, double K_I, double K_II,
                                                                 const kerf::LinearMaterial& material) {
  const Eigen::Vector3d& a = front.a;
  const Eigen::Vector3d& b = front.b;
  const double kappa = 3.0 - 4.0 * material.poisson;
  const double A_I = K_I / (2.0 * material.mu() * std::sqrt(2.0 * M_PI));
  const double A_II = K_II / (2.0 * material.mu() * std::sqrt(2.0 * M_PI));
  return {A_I * (kappa + 1.0) * b + A_II * (kappa + 1.0) * a, A_I * (kappa - 1.0) * a - A_II * (kappa - 1.0) * b,
          A_I * a + A_II * b, -A_I * b + A_II * a};
}

// The half-plane behind a straight front (behind = -a), as a rectangle reaching `reach` past
// the front's point along -a and both ways along c: edge1 x edge2 = c x a = b, its normal.
inline kerf::TriangleSurface half_plane_behind(const StraightFront& front, double reach = 2.0) {
  return kerf::rectangle_surface(kerf::RectangleCut(front.origin - reach * front.c - reach * front.a, 2.0 * reach * front.c, reach * front.a));
}

// The displacement gradient of a homogeneous stress sigma (Hooke's law inverted):
// eps = ((1 + nu) sigma - nu tr(sigma) I) / E, u = eps x.
inline Eigen::Matrix3d strain_of_stress(const Eigen::Matrix3d& sigma, const kerf::LinearMaterial& material) {
  return ((1.0 + material.poisson) * sigma - material.poisson * sigma.trace() * Eigen::Matrix3d::Identity()) / material.young;
}

} // namespace support
