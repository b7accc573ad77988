// Helpers shared by the chapter 3 tests: meshes, cuts, independent piece integrals, node side
// values, sub-meshes and the affine fields of a traction-free cut.
#pragma once

#include "kerf/cut/clip_tet.hpp"
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/linear_material.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/tet_mesh.hpp"
#include "kerf/xfem/enrichment.hpp"
#include "kerf/xfem/xfem_element.hpp"
#include "kerf/xfem/xfem_model.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <vector>

namespace xfem_test {

// The beam of chapters 1-3 and its length.
constexpr double beam_length = 0.2;
inline kerf::TetMesh beam(const Eigen::Vector3i& cells) { return kerf::make_box_mesh({0, 0, 0}, {0.03, 0.06, beam_length}, cells); }

inline Eigen::Matrix<double, 4, 3> corners(const kerf::TetMesh& mesh, Eigen::Index t) {
  Eigen::Matrix<double, 4, 3> X;
  for (int a = 0; a < 4; ++a) X.row(a) = mesh.nodes.row(mesh.tets(t, a));
  return X;
}

inline Eigen::Vector3d node(const kerf::TetMesh& mesh, Eigen::Index v) { return mesh.nodes.row(v).transpose(); }

// A rectangle in the plane through `point` with normal `normal` (its positive side), 2 m by 2 m
// and centred on `point`: far larger than every body here, so the cut goes clean through.
inline kerf::RectangleCut plane_cut(const Eigen::Vector3d& point, const Eigen::Vector3d& normal) {
  const Eigen::Vector3d n = normal.normalized();
  const Eigen::Vector3d helper = std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d e1 = n.cross(helper).normalized(), e2 = n.cross(e1); // e1 x e2 = n
  return kerf::RectangleCut(point - e1 - e2, 2.0 * e1, 2.0 * e2);
}

// The barycentric coordinates (Phi_1..Phi_4) of x in the tet X, solved from scratch.
inline Eigen::Vector4d barycentric(const Eigen::Matrix<double, 4, 3>& X, const Eigen::Vector3d& x) {
  Eigen::Matrix4d A;
  A.row(0).setOnes();
  A.bottomRows<3>() = X.transpose();
  Eigen::Vector4d b;
  b << 1.0, x;
  return A.fullPivLu().solve(b);
}

// int over the part of tet t on side `side` of the plane (signed distances `lambda` at its
// corners, not snapped) of Phi_i dV, from clip_tet's sub-tets and barycentric coordinates.
inline Eigen::Vector4d piece_integrals(const kerf::TetMesh& mesh, Eigen::Index t, const Eigen::Vector4d& lambda, int side) {
  const Eigen::Matrix<double, 4, 3> X = corners(mesh, t);
  const kerf::ClippedTet clipped = kerf::clip_tet(X, lambda);
  Eigen::Vector4d integral = Eigen::Vector4d::Zero();
  for (const auto& sub : side > 0 ? clipped.above : clipped.below)
    integral += std::abs(kerf::signed_tet_volume(sub)) * barycentric(X, sub.colwise().mean().transpose());
  return integral;
}

// The body force rho g on all [u; a] DOFs of the model, built from the side values: the load
// on node i's u is int Phi_i rho g over the whole support, on its a it is
// sum_side Psi_side,i int_piece Phi_i rho g (eq. 46 with eq. 42's basis).
inline Eigen::VectorXd xfem_gravity(const kerf::XfemModel& model, const Eigen::Vector3d& body_force) {
  const kerf::TetMesh& mesh = model.mesh();
  const kerf::Enrichment& e = model.enrichment();
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * model.num_dof_nodes());
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    Eigen::Vector4d lambda;
    for (int a = 0; a < 4; ++a) lambda[a] = e.level_set.lambda[mesh.tets(t, a)];
    const Eigen::Vector4d above = piece_integrals(mesh, t, lambda, +1), below = piece_integrals(mesh, t, lambda, -1);
    const Eigen::Vector4d psi_a = model.psi(t, +1), psi_b = model.psi(t, -1);
    for (int a = 0; a < 4; ++a) {
      f.segment<3>(3 * mesh.tets(t, a)) += (above[a] + below[a]) * body_force;
      if (const int slot = model.assembly_slots()(t, 4 + a); slot >= 0)
        f.segment<3>(3 * slot) += (psi_a[a] * above[a] + psi_b[a] * below[a]) * body_force;
    }
  }
  return f;
}

// The displacement of node v as the side `side` sees it: u_v + Psi_side,v a_v (eq. 66).
inline Eigen::Vector3d node_side_value(const kerf::XfemModel& model, const Eigen::VectorXd& u, int v, int side) {
  Eigen::Vector3d value = u.segment<3>(3 * v);
  const int k = model.enrichment().enriched_index[static_cast<std::size_t>(v)];
  if (k >= 0)
    value += kerf::shifted_enrichment(side, model.enrichment().node_sign[static_cast<std::size_t>(v)]) *
             u.segment<3>(3 * (model.mesh().num_nodes() + k));
  return value;
}

// The DOF node of node v's enriched DOFs, or -1.
inline int enriched_dof_node(const kerf::XfemModel& model, int v) {
  const int k = model.enrichment().enriched_index[static_cast<std::size_t>(v)];
  return k < 0 ? -1 : static_cast<int>(model.mesh().num_nodes()) + k;
}

// The tets selected by `keep`, as a mesh of their own with the nodes renumbered; `original`
// receives the original index of every new node.
inline kerf::TetMesh submesh(const kerf::TetMesh& mesh, const std::function<bool(Eigen::Index)>& keep, std::vector<int>& original) {
  std::vector<int> renumber(static_cast<std::size_t>(mesh.num_nodes()), -1);
  std::vector<Eigen::Index> tets;
  original.clear();
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    if (!keep(t)) continue;
    tets.push_back(t);
    for (int a = 0; a < 4; ++a) {
      int& r = renumber[static_cast<std::size_t>(mesh.tets(t, a))];
      if (r < 0) {
        r = static_cast<int>(original.size());
        original.push_back(mesh.tets(t, a));
      }
    }
  }
  kerf::TetMesh sub;
  sub.nodes.resize(static_cast<Eigen::Index>(original.size()), 3);
  for (std::size_t i = 0; i < original.size(); ++i) sub.nodes.row(static_cast<Eigen::Index>(i)) = mesh.nodes.row(original[i]);
  sub.tets.resize(static_cast<Eigen::Index>(tets.size()), 4);
  for (std::size_t k = 0; k < tets.size(); ++k)
    for (int a = 0; a < 4; ++a) sub.tets(static_cast<Eigen::Index>(k), a) = renumber[static_cast<std::size_t>(mesh.tets(tets[k], a))];
  return sub;
}

// An affine displacement field u(x) = c + G x.
struct AffineField {
  Eigen::Vector3d c;
  Eigen::Matrix3d G;
  Eigen::Vector3d operator()(const Eigen::Vector3d& x) const { return c + G * x; }
};

// An affine field whose stress is the uniaxial stress sigma0 t (x) t with t perpendicular to
// the cut normal n, plus a small rotation W and a translation: sigma n = sigma0 t (t . n) = 0,
// so it satisfies the traction-free condition on the cut exactly, with no body force.
// Strain of a uniaxial stress: eps = sigma0 / E ((1 + nu) t t^T - nu I).
inline AffineField traction_free_field(const kerf::LinearMaterial& material, const Eigen::Vector3d& n, const Eigen::Vector3d& t_dir,
                                       double sigma0, const Eigen::Vector3d& rotation, const Eigen::Vector3d& c) {
  const Eigen::Vector3d t = (t_dir - t_dir.dot(n.normalized()) * n.normalized()).normalized();
  const double nu = material.poisson;
  Eigen::Matrix3d eps = sigma0 / material.young * ((1.0 + nu) * t * t.transpose() - nu * Eigen::Matrix3d::Identity());
  Eigen::Matrix3d W;
  W << 0, -rotation.z(), rotation.y(), rotation.z(), 0, -rotation.x(), -rotation.y(), rotation.x(), 0;
  return {c, eps + W};
}

// Whether node v lies on the surface of the axis-aligned box [lo, hi].
inline bool on_box_surface(const Eigen::Vector3d& x, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  for (int d = 0; d < 3; ++d)
    if (std::abs(x[d] - lo[d]) < 1e-12 || std::abs(x[d] - hi[d]) < 1e-12) return true;
  return false;
}

// Dirichlet conditions that hold every DOF of every surface node of the box at the values of
// the two affine fields: u_v its own side's value, a_v (other side - own side) / Psi_other.
//
// Why a_v too: for a surface node the a_v row of the equilibrium equations is
// int Phi_v Psi sigma n dA over the outer surface of the OTHER side's piece, which is not zero
// for the uniaxial stress (only the cut is traction-free). With a_v prescribed that row drops
// out; every remaining row belongs to an interior node, whose Phi vanishes on the outer surface.
inline std::vector<kerf::DirichletNodes> affine_conditions(const kerf::XfemModel& model, const AffineField& above,
                                                           const AffineField& below, const Eigen::Vector3d& lo,
                                                           const Eigen::Vector3d& hi) {
  std::vector<kerf::DirichletNodes> conditions;
  const kerf::TetMesh& mesh = model.mesh();
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) {
    const Eigen::Vector3d x = node(mesh, v);
    if (!on_box_surface(x, lo, hi)) continue;
    const int sign = model.enrichment().node_sign[static_cast<std::size_t>(v)];
    const Eigen::Vector3d own = sign > 0 ? above(x) : below(x), other = sign > 0 ? below(x) : above(x);
    conditions.push_back({{static_cast<int>(v)}, own});
    if (const int a_node = enriched_dof_node(model, static_cast<int>(v)); a_node >= 0)
      conditions.push_back({{a_node}, (other - own) / kerf::shifted_enrichment(-sign, sign)});
  }
  return conditions;
}

inline bool all_finite(const Eigen::VectorXd& v) { return v.allFinite(); }

// Integrals over the part of a tet on one side of a plane, in closed form, without clipping.
//
// Under the uniform distribution on a tet T the barycentric coordinates phi are Dirichlet(1,1,1,1),
// and weighting by phi^alpha = prod phi_k^alpha_k turns it into Dirichlet(1 + alpha). That is
// the law of a uniform point of an n-simplex, n = 3 + |alpha|, whose vertices are those of T,
// vertex k repeated 1 + alpha_k times, with the barycentric coordinates of the copies added up.
// The plane's level set f = sum lambda_k phi_k is linear, so
//   int_{T, side f > 0} phi^alpha dV = V 6 alpha! / (|alpha| + 3)!  P_n(f > 0),
// and the fraction of an n-simplex where a linear function with vertex values mu_0..mu_n is
// positive is the divided difference [mu_0, ..., mu_n] of t -> (t)_+^n (its density is the
// B-spline with those knots). Repeated knots make it a confluent divided difference, computed
// with derivatives. For alpha = 0 and distinct values this is sum_{lambda_k > 0} lambda_k^3 /
// prod_{j != k} (lambda_k - lambda_j), e.g. lambda_0^3 / prod (lambda_0 - lambda_j) for the small
// tet at a lone corner: the product of the three edge fractions.
inline double positive_part_divided_difference(std::vector<double> mu) {
  std::sort(mu.begin(), mu.end());
  const int n = static_cast<int>(mu.size()) - 1;
  // d^j/dt^j (t)_+^n / j! = C(n, j) t^(n - j) for t > 0, 0 otherwise.
  const auto derivative_over_factorial = [n](double t, int j) {
    if (t <= 0.0) return 0.0;
    double binomial = 1.0;
    for (int m = 0; m < j; ++m) binomial = binomial * (n - m) / (m + 1);
    return binomial * std::pow(t, n - j);
  };
  std::vector<double> column(mu.size());
  for (std::size_t i = 0; i < mu.size(); ++i) column[i] = derivative_over_factorial(mu[i], 0);
  for (int j = 1; j <= n; ++j)
    for (int i = n; i >= j; --i) {
      const auto ui = static_cast<std::size_t>(i), lo = static_cast<std::size_t>(i - j);
      column[ui] = mu[ui] == mu[lo] ? derivative_over_factorial(mu[ui], j) : (column[ui] - column[ui - 1]) / (mu[ui] - mu[lo]);
    }
  return column.back();
}

// int over the part of the tet (volume V, corner level-set values lambda, none zero) on side
// `side` (+1: lambda > 0) of prod_k phi_k^alpha_k dV, in closed form (see above). A tet wholly
// on one side is answered directly, V 6 alpha! / (|alpha| + 3)! or 0, without divided
// differences, which would only add round-off there.
inline double side_moment(const Eigen::Vector4d& lambda, double volume, const std::array<int, 4>& alpha, int side) {
  int total = 0;
  double moment = 6.0 * volume;
  for (int k = 0; k < 4; ++k) {
    total += alpha[static_cast<std::size_t>(k)];
    moment *= std::tgamma(alpha[static_cast<std::size_t>(k)] + 1.0);
  }
  moment /= std::tgamma(total + 4.0);
  const Eigen::Vector4d f = side * lambda;
  if (f.minCoeff() > 0.0) return moment;
  if (f.maxCoeff() < 0.0) return 0.0;
  std::vector<double> mu;
  for (int k = 0; k < 4; ++k)
    for (int r = 0; r <= alpha[static_cast<std::size_t>(k)]; ++r) mu.push_back(f[k]);
  return moment * positive_part_divided_difference(mu);
}

// int over the side `side` part of the tet of phi_i phi_j dV (i, j corners), and of phi_i dV.
inline double side_product_integral(const Eigen::Vector4d& lambda, double volume, int i, int j, int side) {
  std::array<int, 4> alpha{};
  ++alpha[static_cast<std::size_t>(i)];
  ++alpha[static_cast<std::size_t>(j)];
  return side_moment(lambda, volume, alpha, side);
}
inline double side_shape_integral(const Eigen::Vector4d& lambda, double volume, int i, int side) {
  std::array<int, 4> alpha{};
  ++alpha[static_cast<std::size_t>(i)];
  return side_moment(lambda, volume, alpha, side);
}

// The signed distance of x to the plane through `point` with normal `normal` (any length).
inline double plane_value(const Eigen::Vector3d& point, const Eigen::Vector3d& normal, const Eigen::Vector3d& x) {
  return normal.normalized().dot(x - point);
}

// Psi_side,i = (H_side - H_i) / 2 (eq. 44) for a node of sign H_i.
inline double psi_of(int side, int node_sign) { return 0.5 * (side - node_sign); }

} // namespace xfem_test
