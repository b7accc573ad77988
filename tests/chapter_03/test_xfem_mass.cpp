// The XFEM mass (Schoch et al. eqs. 76-82): cutting adds no mass (lumped u-part), a rigid
// translation of the whole body carries rho V |t|^2, and one of the piece above alone carries
// rho V_above |t|^2, with V_above known in closed form for a plane through the beam; the
// consistent mass entry by entry against eqs. 77-80 with the piece integrals in closed form,
// and on fields linear on each side against the exact kinetic integral; the lumped mass entry
// by entry against eqs. 81-82.
#include "xfem_test_support.hpp"

#include "kerf/xfem/xfem_mass.hpp"
#include "kerf/xfem/xfem_model.hpp"

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <array>
#include <string>
#include <vector>

using namespace xfem_test;

namespace {

const kerf::LinearMaterial material{300e3, 0.35, 1070.0};
constexpr double beam_volume = 0.03 * 0.06 * 0.2;

// The oblique plane of these tests: through the mid-section's centroid with normal (0.3, 0.2, 1).
const Eigen::Vector3d plane_point(0.015, 0.03, 0.1), plane_normal(0.3, 0.2, 1.0);

// The level set of the plane at the corners of tet t, computed here from the plane.
Eigen::Vector4d corner_values(const kerf::TetMesh& mesh, Eigen::Index t) {
  Eigen::Vector4d lambda;
  for (int a = 0; a < 4; ++a) lambda[a] = plane_value(plane_point, plane_normal, node(mesh, mesh.tets(t, a)));
  return lambda;
}

// The volume of tet t from its corners.
double tet_volume(const kerf::TetMesh& mesh, Eigen::Index t) {
  const Eigen::Matrix<double, 4, 3> X = corners(mesh, t);
  Eigen::Matrix3d J;
  for (int c = 0; c < 3; ++c) J.col(c) = (X.row(c + 1) - X.row(0)).transpose();
  return J.determinant() / 6.0;
}

// rho int |v|^2 over the part of the beam [0, 0.03] x [0, 0.06] x [0, 0.2] above (side +1) or
// below the plane, for the affine field v, exactly: the plane crosses only the long sides, at
// z_p(x, y) in [0.0895, 0.1105], so the part above is z in [z_p(x, y), 0.2]. In z the integral
// of |p + q z|^2 is done by hand; what remains is a cubic in (x, y) (z_p is linear), which the
// 3 x 3 Gauss-Legendre rule (exact to degree 5) integrates exactly.
double kinetic_integral(const AffineField& v, int side, double rho) {
  const double gauss[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)}, weight[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  const double a = 0.03, b = 0.06, length = 0.2;
  const Eigen::Vector3d n = plane_normal;
  double sum = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double x = 0.5 * a * (1.0 + gauss[i]), y = 0.5 * b * (1.0 + gauss[j]);
      const double z_plane = plane_point.z() - (n.x() * (x - plane_point.x()) + n.y() * (y - plane_point.y())) / n.z();
      const double z1 = side > 0 ? z_plane : 0.0, z2 = side > 0 ? length : z_plane;
      const Eigen::Vector3d p = v.c + v.G.leftCols<2>() * Eigen::Vector2d(x, y), q = v.G.col(2);
      const double inner = p.squaredNorm() * (z2 - z1) + p.dot(q) * (z2 * z2 - z1 * z1) + q.squaredNorm() * (z2 * z2 * z2 - z1 * z1 * z1) / 3.0;
      sum += weight[i] * weight[j] * 0.25 * a * b * inner;
    }
  return rho * sum;
}

// The [u; a] vector of the field that is `above` on the side above and `below` below: every
// node's u its own side's value, an enriched node's a (other - own) / Psi_other (eq. 66).
Eigen::VectorXd two_sided_field(const kerf::XfemModel& model, const AffineField& above, const AffineField& below) {
  const kerf::TetMesh& mesh = model.mesh();
  Eigen::VectorXd v = Eigen::VectorXd::Zero(3 * model.num_dof_nodes());
  for (Eigen::Index i = 0; i < mesh.num_nodes(); ++i) {
    const Eigen::Vector3d x = node(mesh, i);
    const int sign = plane_value(plane_point, plane_normal, x) > 0 ? +1 : -1;
    const Eigen::Vector3d own = sign > 0 ? above(x) : below(x), other = sign > 0 ? below(x) : above(x);
    v.segment<3>(3 * i) = own;
    if (const int a_node = enriched_dof_node(model, static_cast<int>(i)); a_node >= 0)
      v.segment<3>(3 * a_node) = (other - own) / psi_of(-sign, sign);
  }
  return v;
}

} // namespace

TEST_CASE("xfem mass: lumped and consistent masses of a beam cut obliquely through") {
  const kerf::TetMesh mesh = beam({2, 3, 8});
  // The plane passes through the centroid (0.015, 0.03, 0.1) of the mid cross-section and
  // crosses only the long sides of the beam (|dz| <= 0.011 over the section), so the part above
  // is a prism of the cross-section's area times the mean height 0.1: V_above = V / 2 exactly.
  const kerf::Enrichment e = kerf::make_enrichment(mesh, plane_cut({0.015, 0.03, 0.1}, {0.3, 0.2, 1.0}));
  REQUIRE(e.snapped_nodes == 0);
  REQUIRE(e.cut_tets > 0);
  const kerf::XfemModel model(mesh, material, e);
  const double rho = material.density;
  const auto n = static_cast<Eigen::Index>(3 * mesh.num_nodes());

  // Sums of a few hundred positive terms of similar size: round-off ~1e-15 relative; 1e-12.
  const Eigen::VectorXd lumped = kerf::xfem_lumped_mass(model, rho);
  for (int d = 0; d < 3; ++d) {
    double total = 0.0;
    for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) total += lumped[3 * v + d];
    CHECK(std::abs(total - rho * beam_volume) <= 1e-12 * rho * beam_volume);
  }
  CHECK(lumped.tail(lumped.size() - n).minCoeff() > 0.0); // every enriched DOF has mass (eq. 82)

  const Eigen::SparseMatrix<double> M = kerf::assemble_xfem_mass(model, rho);
  REQUIRE(M.rows() == 3 * model.num_dof_nodes());
  const Eigen::Vector3d t(0.3, -1.2, 0.7);

  // The whole body translated: u_i = t, a_i = 0.
  Eigen::VectorXd whole = Eigen::VectorXd::Zero(M.rows());
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) whole.segment<3>(3 * v) = t;
  const double whole_energy = whole.dot(M * whole);
  CHECK(std::abs(whole_energy - rho * beam_volume * t.squaredNorm()) <= 1e-12 * rho * beam_volume * t.squaredNorm());

  // The piece above translated, the piece below at rest: u_i = t above, 0 below; a_i = t for an
  // enriched node below (Psi_a = +1: t above, 0 on its own side) and a_i = t for one above
  // (Psi_b = -1: t - t = 0 below).
  Eigen::VectorXd above = Eigen::VectorXd::Zero(M.rows());
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) {
    if (e.node_sign[static_cast<std::size_t>(v)] > 0) above.segment<3>(3 * v) = t;
    if (const int a_node = enriched_dof_node(model, static_cast<int>(v)); a_node >= 0) above.segment<3>(3 * a_node) = t;
  }
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) { // every side value a node has is right
    const bool enriched = e.enriched_index[static_cast<std::size_t>(v)] >= 0;
    const int sign = e.node_sign[static_cast<std::size_t>(v)];
    if (sign > 0 || enriched) CHECK((node_side_value(model, above, static_cast<int>(v), +1) - t).norm() == 0.0);
    if (sign < 0 || enriched) CHECK(node_side_value(model, above, static_cast<int>(v), -1).norm() == 0.0);
  }
  double V_above = 0.0; // from the tets: the ones above, plus V_a of the cut ones
  for (Eigen::Index k = 0; k < mesh.num_tets(); ++k) V_above += e.fraction_above[static_cast<std::size_t>(k)] * model.element_volume(k);
  CHECK(std::abs(V_above - 0.5 * beam_volume) <= 1e-12 * beam_volume);
  const double above_energy = above.dot(M * above);
  MESSAGE("v^T M v: whole body " << whole_energy << " (rho V |t|^2 = " << rho * beam_volume * t.squaredNorm() << "), piece above "
                                 << above_energy << " (rho V/2 |t|^2 = " << 0.5 * rho * beam_volume * t.squaredNorm() << ")");
  CHECK(std::abs(above_energy - rho * 0.5 * beam_volume * t.squaredNorm()) <= 1e-12 * rho * beam_volume * t.squaredNorm());
  // The consistent mass is symmetric (both triangles are assembled).
  CHECK((Eigen::SparseMatrix<double>(M.transpose()) - M).norm() <= 1e-15 * M.norm());
}

TEST_CASE("xfem mass: consistent mass entry by entry (eqs. 77-80) and on fields linear on each side, lumped mass by eqs. 81-82") {
  const kerf::TetMesh mesh = beam({2, 3, 8});
  const kerf::Enrichment e = kerf::make_enrichment(mesh, plane_cut(plane_point, plane_normal));
  REQUIRE(e.snapped_nodes == 0);
  const kerf::XfemModel model(mesh, material, e);
  const double rho = material.density;
  const Eigen::Index N = mesh.num_nodes(), dof_nodes = model.num_dof_nodes();

  // Signs and enrichment decided here from the plane: no node lies on it (the closed forms
  // need nonzero corner values), H_i is the sign of the distance, and with a cut through the
  // whole body (no front) a node is enriched exactly when one of its tets has corners on both sides.
  std::vector<int> sign(static_cast<std::size_t>(N)), cut_node(static_cast<std::size_t>(N), 0);
  for (Eigen::Index i = 0; i < N; ++i) {
    const double value = plane_value(plane_point, plane_normal, node(mesh, i));
    REQUIRE(value != 0.0);
    sign[static_cast<std::size_t>(i)] = value > 0 ? +1 : -1;
    CHECK(e.node_sign[static_cast<std::size_t>(i)] == sign[static_cast<std::size_t>(i)]);
  }
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const Eigen::Vector4d lambda = corner_values(mesh, t);
    if (lambda.minCoeff() < 0.0 && lambda.maxCoeff() > 0.0)
      for (int a = 0; a < 4; ++a) cut_node[static_cast<std::size_t>(mesh.tets(t, a))] = 1;
  }
  for (Eigen::Index i = 0; i < N; ++i)
    CHECK((e.enriched_index[static_cast<std::size_t>(i)] >= 0) == (cut_node[static_cast<std::size_t>(i)] == 1));

  // The expected matrices, tet by tet. With m_s(i, j) = rho int_{T_s} Phi_i Phi_j dV in closed
  // form (side_product_integral) and Psi_s,i = (s - H_i) / 2, eqs. 77-80 read
  //   M^uu_ij = sum_s m_s(i, j),  M^ua_ij = sum_s m_s(i, j) Psi_s,j,  M^aa_ij = sum_s Psi_s,i m_s(i, j) Psi_s,j
  // (each times I_3). The lumped mass, eqs. 81-82: each corner gets m / 4 on u and
  // (V_a / V Psi_a,i^2 + V_b / V Psi_b,i^2) m / 4 on a, with m = rho V.
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(dof_nodes, dof_nodes); // the scalar matrix (one component)
  Eigen::VectorXd expected_lumped = Eigen::VectorXd::Zero(dof_nodes);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const Eigen::Vector4d lambda = corner_values(mesh, t);
    const double V = tet_volume(mesh, t);
    std::array<int, 4> u_row{}, a_row{};
    std::array<int, 4> H{};
    for (int i = 0; i < 4; ++i) {
      const int v = mesh.tets(t, i);
      u_row[static_cast<std::size_t>(i)] = v;
      a_row[static_cast<std::size_t>(i)] = enriched_dof_node(model, v);
      H[static_cast<std::size_t>(i)] = sign[static_cast<std::size_t>(v)];
    }
    const double fraction[2] = {side_moment(lambda, V, {}, +1) / V, side_moment(lambda, V, {}, -1) / V};
    for (int i = 0; i < 4; ++i) {
      const auto si = static_cast<std::size_t>(i);
      expected_lumped[u_row[si]] += rho * V / 4.0;
      if (a_row[si] >= 0)
        expected_lumped[a_row[si]] += rho * V / 4.0 *
                                       (fraction[0] * std::pow(psi_of(+1, H[si]), 2) + fraction[1] * std::pow(psi_of(-1, H[si]), 2));
      for (int j = 0; j < 4; ++j) {
        const auto sj = static_cast<std::size_t>(j);
        for (const int side : {+1, -1}) {
          const double m = rho * side_product_integral(lambda, V, i, j, side);
          const double psi_i = psi_of(side, H[si]), psi_j = psi_of(side, H[sj]);
          expected(u_row[si], u_row[sj]) += m;
          if (a_row[sj] >= 0) expected(u_row[si], a_row[sj]) += m * psi_j;
          if (a_row[si] >= 0) expected(a_row[si], u_row[sj]) += psi_i * m;
          if (a_row[si] >= 0 && a_row[sj] >= 0) expected(a_row[si], a_row[sj]) += psi_i * m * psi_j;
        }
      }
    }
  }

  // Consistent mass, entry by entry (all 3 components, zero coupling between components).
  const Eigen::MatrixXd M = Eigen::MatrixXd(kerf::assemble_xfem_mass(model, rho));
  REQUIRE(M.rows() == 3 * dof_nodes);
  Eigen::MatrixXd expected_full = Eigen::MatrixXd::Zero(3 * dof_nodes, 3 * dof_nodes);
  for (Eigen::Index i = 0; i < dof_nodes; ++i)
    for (Eigen::Index j = 0; j < dof_nodes; ++j)
      for (int d = 0; d < 3; ++d) expected_full(3 * i + d, 3 * j + d) = expected(i, j);
  // Both sides sum at most 2 x 24 terms per entry, each of relative round-off ~1e-15 (the
  // divided differences of a cut tet lose at most a factor (range / spacing of the corner
  // values)^n ~ 10^3 more); 1e-11 of the largest entry is far below any error in a piece
  // integral (a degree-1 rule would err by ~1e-2 relative on the cut tets).
  const double scale = expected_full.cwiseAbs().maxCoeff();
  const double consistent_error = (M - expected_full).cwiseAbs().maxCoeff() / scale;

  // The lumped mass, entry by entry (each component).
  const Eigen::VectorXd lumped = kerf::xfem_lumped_mass(model, rho);
  REQUIRE(lumped.size() == 3 * dof_nodes);
  double lumped_error = 0.0;
  for (Eigen::Index i = 0; i < dof_nodes; ++i)
    for (int d = 0; d < 3; ++d) lumped_error = std::max(lumped_error, std::abs(lumped[3 * i + d] - expected_lumped[i]) / expected_lumped.maxCoeff());
  for (Eigen::Index i = N; i < dof_nodes; ++i) CHECK(expected_lumped[i] > 0.0);

  // On fields linear on each side, different on both sides: v^T M v is the exact kinetic
  // integral rho int |v|^2 over both sides, computed without any mesh (kinetic_integral).
  // Velocities ~1 m/s with gradients ~10 /s over 0.2 m, so neither side is nearly constant.
  AffineField above{{0.3, -1.2, 0.7}, Eigen::Matrix3d::Zero()}, below{{-0.5, 0.4, 0.9}, Eigen::Matrix3d::Zero()};
  above.G << 5.0, -3.0, 8.0, 2.0, 7.0, -4.0, -6.0, 1.0, 9.0;
  below.G << -4.0, 6.0, -2.0, 3.0, -5.0, 7.0, 8.0, -1.0, -3.0;
  const AffineField rest{Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero()};
  struct Case {
    const char* what;
    AffineField a, b;
  };
  const Case cases[] = {{"both sides", above, below}, {"above only", above, rest}, {"below only", rest, below}};
  double worst_field = 0.0;
  for (const Case& c : cases) {
    const Eigen::VectorXd v = two_sided_field(model, c.a, c.b);
    const double computed = v.dot(M * v);
    const double exact = kinetic_integral(c.a, +1, rho) + kinetic_integral(c.b, -1, rho);
    MESSAGE("v^T M v, linear field " << std::string(c.what) << ": " << computed << " against the exact " << exact);
    worst_field = std::max(worst_field, std::abs(computed - exact) / exact);
  }
  MESSAGE("consistent mass vs eqs. 77-80 in closed form: " << consistent_error << " of the largest entry; lumped vs eqs. 81-82: "
                                                            << lumped_error << "; linear fields: worst relative error " << worst_field);
  CHECK(consistent_error <= 1e-11);
  CHECK(lumped_error <= 1e-12);
  // A sum of positive kinetic contributions, integrated exactly on both sides: 1e-12 relative.
  CHECK(worst_field <= 1e-12);
}
