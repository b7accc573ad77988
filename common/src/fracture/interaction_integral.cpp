#include "kerf/fracture/interaction_integral.hpp"

#include "kerf/cut/convex_cell.hpp"
#include "kerf/fem/tet_quadrature.hpp"
#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/mesh/node_region.hpp"

#include <Eigen/LU>

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace kerf {

namespace {

/// The smooth step g(s) = 1 - 10 s^3 + 15 s^4 - 6 s^5 from g(0) = 1 to g(1) = 0, with g' and g''
/// zero at both ends, and its derivative in `slope`. C2, so the integrand has no jump, and no
/// kink, where q starts or stops falling; its integral over [0, 1] is 1/2.
double smooth_step(double s, double& slope) {
  slope = -30.0 * s * s * (1.0 - s) * (1.0 - s);
  return 1.0 - s * s * s * (10.0 - 15.0 * s + 6.0 * s * s);
}

/// A sphere around a set of points: enough to decide quickly that q is 0 (or flat) on all of them.
struct BoundingSphere {
  Eigen::Vector3d center;
  double radius = 0.0;
};

BoundingSphere bounding_sphere(const Eigen::Matrix<double, 4, 3>& X) {
  BoundingSphere sphere{X.colwise().mean().transpose(), 0.0};
  for (int a = 0; a < 4; ++a) sphere.radius = std::max(sphere.radius, (X.row(a).transpose() - sphere.center).norm());
  return sphere;
}

/// Whether q may vary somewhere in the sphere (otherwise grad q = 0 there and the integrand too):
/// the sphere meets the ring inner <= r <= outer within the segment, or the ramps of w.
bool weight_may_vary(const InteractionDomain& domain, const BoundingSphere& sphere) {
  const Eigen::Vector3d y = domain.front.local(sphere.center);
  const double r = std::hypot(y[0], y[1]), s = sphere.radius;
  if (r - s >= domain.outer_radius || y[2] + s <= domain.front_begin || y[2] - s >= domain.front_end) return false;
  const bool inside_plateau = r + s <= domain.inner_radius && y[2] - s >= domain.front_begin + domain.end_ramp &&
                              y[2] + s <= domain.front_end - domain.end_ramp;
  return !inside_plateau;
}

/// The tet T split into its eight children by its edges' midpoints (Bey's red refinement: four
/// corner tets and the inner octahedron cut along its diagonal m02-m13), each 1/8 of T.
std::array<Eigen::Matrix<double, 4, 3>, 8> red_children(const Eigen::Matrix<double, 4, 3>& T) {
  const auto m = [&](int i, int j) -> Eigen::RowVector3d { return 0.5 * (T.row(i) + T.row(j)); };
  const Eigen::RowVector3d m01 = m(0, 1), m02 = m(0, 2), m03 = m(0, 3), m12 = m(1, 2), m13 = m(1, 3), m23 = m(2, 3);
  std::array<Eigen::Matrix<double, 4, 3>, 8> children;
  children[0] << T.row(0), m01, m02, m03;
  children[1] << m01, T.row(1), m12, m13;
  children[2] << m02, m12, T.row(2), m23;
  children[3] << m03, m13, m23, T.row(3);
  children[4] << m02, m13, m01, m12;
  children[5] << m02, m13, m12, m23;
  children[6] << m02, m13, m23, m03;
  children[7] << m02, m13, m03, m01;
  return children;
}

/// Calls integrate(T) on T or, when T may hold the front where w's ramps make q vary along it
/// (the one place where the integrand reaches the front's 1/r), on T's red children, down to
/// `levels` times: the children away from the front take Gauss rules that suit them, and the
/// error of the few along it shrinks with their size.
template <class Integrate>
void refine_towards_front(const InteractionDomain& domain, const Eigen::Matrix<double, 4, 3>& T, int levels, const Integrate& integrate) {
  const BoundingSphere sphere = bounding_sphere(T);
  const Eigen::Vector3d y = domain.front.local(sphere.center);
  const double s = sphere.radius;
  const bool near_front = std::hypot(y[0], y[1]) <= s;
  const bool in_ramp = (y[2] - s < domain.front_begin + domain.end_ramp && y[2] + s > domain.front_begin) ||
                       (y[2] + s > domain.front_end - domain.end_ramp && y[2] - s < domain.front_end);
  if (levels <= 0 || !near_front || !in_ramp) {
    integrate(T);
    return;
  }
  for (const Eigen::Matrix<double, 4, 3>& child : red_children(T)) refine_towards_front(domain, child, levels - 1, integrate);
}

/// The domain form drops the integral over the domain's boundary, which is right only if q = 0
/// on the mesh's boundary (but for the cut faces, which are traction-free). We check q on a
/// lattice of 15 points of each boundary face.
void check_weight_vanishes_on_boundary(const TetMesh& mesh, const InteractionDomain& domain) {
  const BoundaryFaces boundary = boundary_faces(mesh);
  const double tolerance = region_tolerance(mesh);
  for (Eigen::Index f = 0; f < boundary.faces.rows(); ++f) {
    Eigen::Matrix3d X;
    for (int a = 0; a < 3; ++a) X.row(a) = mesh.nodes.row(boundary.faces(f, a));
    bool on_cut = true;
    for (int a = 0; a < 3; ++a) {
      const Eigen::Vector3d y = domain.front.local(X.row(a).transpose());
      on_cut = on_cut && std::abs(y[1]) <= tolerance && y[0] <= tolerance;
    }
    if (on_cut) continue;
    constexpr int n = 4;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        const double s = static_cast<double>(i) / n, t = static_cast<double>(j) / n;
        const Eigen::Vector3d x = ((1.0 - s - t) * X.row(0) + s * X.row(1) + t * X.row(2)).transpose();
        Eigen::Vector3d gradient;
        if (domain.weight(x, gradient) > 1e-12)
          throw std::invalid_argument("interaction_integral_sifs: the domain reaches the mesh's boundary (q = " +
                                      std::to_string(domain.weight(x, gradient)) + " on boundary face " + std::to_string(f) +
                                      "): make outer_radius or the front segment smaller");
      }
  }
}

} // namespace

void InteractionDomain::check() const {
  const auto fail = [](const std::string& what) { throw std::invalid_argument("InteractionDomain: " + what); };
  if (!(front_end > front_begin)) fail("front_end must exceed front_begin");
  if (!(end_ramp > 0.0 && end_ramp <= 0.5 * (front_end - front_begin))) fail("end_ramp must be in (0, (front_end - front_begin) / 2]");
  if (!(inner_radius >= 0.0)) fail("inner_radius must be >= 0");
  if (!(outer_radius > inner_radius)) fail("outer_radius must exceed inner_radius");
  if (quadrature_degree < 1 || quadrature_degree > 15) fail("quadrature_degree must be in [1, 15]");
  if (front_refinement_levels < 0 || front_refinement_levels > 6) fail("front_refinement_levels must be in [0, 6]");
}

double InteractionDomain::weight(const Eigen::Vector3d& x, Eigen::Vector3d& gradient) const {
  gradient.setZero();
  const Eigen::Vector3d y = front.local(x);
  const double r = std::hypot(y[0], y[1]);
  if (r >= outer_radius || y[2] <= front_begin || y[2] >= front_end) return 0.0;
  // q_r(r) and dq_r/dr.
  double q_r = 1.0, dq_r = 0.0;
  if (r > inner_radius) {
    const double width = outer_radius - inner_radius;
    q_r = smooth_step((r - inner_radius) / width, dq_r);
    dq_r /= width;
  }
  // w(x_c) and dw/dx_c.
  double w = 1.0, dw = 0.0;
  if (y[2] < front_begin + end_ramp) {
    w = smooth_step((front_begin + end_ramp - y[2]) / end_ramp, dw);
    dw = -dw / end_ramp;
  } else if (y[2] > front_end - end_ramp) {
    w = smooth_step((y[2] - (front_end - end_ramp)) / end_ramp, dw);
    dw /= end_ramp;
  }
  // grad r = (x_a a + x_b b) / r (r > inner_radius >= 0 wherever dq_r is not zero).
  Eigen::Vector3d grad_r = Eigen::Vector3d::Zero();
  if (dq_r != 0.0) grad_r = (front.R.col(0) * y[0] + front.R.col(1) * y[1]) / r;
  gradient = w * dq_r * grad_r + q_r * dw * front.R.col(2);
  return q_r * w;
}

double InteractionDomain::weighted_front_length() const { return (front_end - front_begin) - end_ramp; }

Eigen::Vector3d interaction_integrand(const InteractionDomain& domain, const LinearMaterial& material, const Eigen::Vector3d& x,
                                      const Eigen::Matrix3d& grad_u) {
  Eigen::Vector3d grad_q;
  domain.weight(x, grad_q);
  Eigen::Vector3d density = Eigen::Vector3d::Zero();
  if (grad_q.isZero(0.0)) return density;
  const Eigen::Vector3d a = domain.front.R.col(0);
  const Eigen::Matrix3d strain = 0.5 * (grad_u + grad_u.transpose());
  const Eigen::Matrix3d stress = material.lambda() * strain.trace() * Eigen::Matrix3d::Identity() + 2.0 * material.mu() * strain;
  const Eigen::Vector3d du_da = grad_u * a;
  const WilliamsUnitFields auxiliary = williams_unit_fields(domain.front, material, x);
  for (int mode = 0; mode < 3; ++mode) {
    const Eigen::Matrix3d& grad_u2 = auxiliary.gradient[static_cast<std::size_t>(mode)];
    const Eigen::Matrix3d& stress2 = auxiliary.stress[static_cast<std::size_t>(mode)];
    // W12 = sigma : eps2 = sigma : grad u2 (sigma is symmetric).
    const double W12 = (stress.array() * grad_u2.array()).sum();
    // P_j = sigma_ij du2_i/dx_a + sigma2_ij du_i/dx_a - W12 delta_aj, the integrand of Moës et al.'s domain form.
    const Eigen::Vector3d P = stress * (grad_u2 * a) + stress2 * du_da - W12 * a;
    density[mode] = P.dot(grad_q);
  }
  return density;
}

StressIntensityFactors sifs_from_interaction_integrals(const Eigen::Vector3d& integrals, const LinearMaterial& material,
                                                       const InteractionDomain& domain) {
  // Plane strain: J = (K_I^2 + K_II^2) / E' + K_III^2 / (2 mu), so the cross term of the field
  // with a unit auxiliary field is I = 2 K / E' (modes I, II) or K / mu (mode III).
  const double E_prime = material.young / (1.0 - material.poisson * material.poisson);
  const double length = domain.weighted_front_length();
  return {0.5 * E_prime * integrals[0] / length, 0.5 * E_prime * integrals[1] / length, material.mu() * integrals[2] / length};
}

StressIntensityFactors interaction_integral_sifs(const TetMesh& mesh, const DisplacementGradientAt& grad_u, const LinearMaterial& material,
                                                 const InteractionDomain& domain) {
  domain.check();
  check_weight_vanishes_on_boundary(mesh, domain);
  const TetQuadratureRule rule = tet_quadrature_rule(domain.quadrature_degree);
  const Eigen::Vector3d b = domain.front.R.col(1);
  const Plane cut_plane{b, b.dot(domain.front.origin)};
  const auto side = [&](const Eigen::Vector3d& x) { return cut_plane.evaluate(x); };
  const Eigen::Vector3d c = domain.front.R.col(2);
  const double c0 = c.dot(domain.front.origin);
  std::vector<Plane> w_breaks;
  for (const double at : {domain.front_begin, domain.front_begin + domain.end_ramp, domain.front_end - domain.end_ramp, domain.front_end})
    w_breaks.push_back(Plane{c, c0 + at});
  Eigen::Vector3d integrals = Eigen::Vector3d::Zero();
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const Eigen::Matrix<double, 4, 3> X = tet_corners(mesh, t);
    if (!weight_may_vary(domain, bounding_sphere(X))) continue;
    // The two sides of the cut's plane apart: behind the front the field jumps across it. And
    // the tet cut by the planes x_c = const where w changes its formula (the segment's ends and
    // the ramps' inner ends), so that w is one polynomial on each cell: a Gauss rule across
    // w's jump in curvature would err by O(h^2) there, next to the front's 1/r.
    std::vector<ConvexCell> cells{tet_cell(X)};
    split_cell(cells, 0, side, cut_plane, FaceOrigin{FaceOrigin::Kind::cut_plane, 0});
    for (const Plane& plane : w_breaks)
      for (int c = static_cast<int>(cells.size()) - 1; c >= 0; --c)
        split_cell(cells, c, [&](const Eigen::Vector3d& x) { return plane.evaluate(x); }, plane, FaceOrigin{FaceOrigin::Kind::cut_plane, 1});
    const auto integrate = [&](const Eigen::Matrix<double, 4, 3>& T) {
      // x = T0 + J xi, dV = |det J| dxi; a fan's flat tet holds no volume.
      Eigen::Matrix3d J;
      for (int i = 0; i < 3; ++i) J.col(i) = (T.row(i + 1) - T.row(0)).transpose();
      const double volume_factor = std::abs(J.determinant());
      if (volume_factor == 0.0) return;
      for (std::size_t q = 0; q < rule.points.size(); ++q) {
        const Eigen::Vector3d x = T.row(0).transpose() + J * rule.points[q];
        Eigen::Vector3d grad_q;
        domain.weight(x, grad_q);
        if (grad_q.isZero(0.0)) continue; // no integrand, and no need to ask the field
        integrals += rule.weights[q] * volume_factor * interaction_integrand(domain, material, x, grad_u(t, x));
      }
    };
    for (const ConvexCell& cell : cells)
      for (const Eigen::Matrix<double, 4, 3>& T : convex_cell_tetrahedra(cell)) refine_towards_front(domain, T, domain.front_refinement_levels, integrate);
  }
  return sifs_from_interaction_integrals(integrals, material, domain);
}

} // namespace kerf
