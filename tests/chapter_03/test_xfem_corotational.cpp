// Corotational XFEM (Schoch et al. eqs. 64-71): two pieces of a bar cut through, each turned
// rigidly by its own 60-degree rotation, carry no internal force and no corotated energy
// (while linear XFEM sees a large energy there), and the consistent tangent of
// XfemModel::assemble is the derivative of its forces.
#include "xfem_test_support.hpp"

#include "support/tangent_check.hpp"

#include "kerf/corotation/corotational_model.hpp"
#include "kerf/corotation/quasi_static_solver.hpp"
#include "kerf/cut/split_mesh_along_cut.hpp"
#include "kerf/fem/assemble_loads.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/xfem/xfem_model.hpp"

#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

using namespace xfem_test;

namespace {

const kerf::LinearMaterial material{300e3, 0.35, 1070.0};

// The [u; a] vector whose side values are side_above(X) above and side_below(X) below:
// u_i its own side's value, a_i = (other side's value - u_i) / Psi_other,i.
template <class Above, class Below>
Eigen::VectorXd two_sided(const kerf::XfemModel& model, const Above& side_above, const Below& side_below) {
  const kerf::TetMesh& mesh = model.mesh();
  Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * model.num_dof_nodes());
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) {
    const int sign = model.enrichment().node_sign[static_cast<std::size_t>(v)];
    const Eigen::Vector3d X = node(mesh, v);
    const Eigen::Vector3d own = sign > 0 ? side_above(X) : side_below(X), other = sign > 0 ? side_below(X) : side_above(X);
    u.segment<3>(3 * v) = own;
    if (const int a_node = enriched_dof_node(model, static_cast<int>(v)); a_node >= 0)
      u.segment<3>(3 * a_node) = (other - own) / kerf::shifted_enrichment(-sign, sign);
  }
  return u;
}

} // namespace

TEST_CASE("xfem corotational: two pieces turned rigidly by different 60-degree rotations carry no force") {
  const kerf::TetMesh mesh = beam({2, 3, 8});
  const kerf::Enrichment e = kerf::make_enrichment(mesh, plane_cut({0.015, 0.03, 0.1}, {0.3, 0.2, 1.0}));
  REQUIRE(e.front_nodes == 0); // cut clean through: every node of a cut tet is enriched
  const kerf::XfemModel model(mesh, material, e);
  const double angle = M_PI / 3.0;
  const Eigen::Matrix3d Q_a = Eigen::AngleAxisd(angle, Eigen::Vector3d(1, 2, 0.5).normalized()).toRotationMatrix();
  const Eigen::Matrix3d Q_b = Eigen::AngleAxisd(-angle, Eigen::Vector3d(-0.3, 0.4, 1).normalized()).toRotationMatrix();
  const Eigen::Vector3d c_a(0.05, -0.02, 0.1), c_b(-0.03, 0.01, -0.04);
  const auto above = [&](const Eigen::Vector3d& X) { return Eigen::Vector3d(Q_a * X + c_a - X); };
  const auto below = [&](const Eigen::Vector3d& X) { return Eigen::Vector3d(Q_b * X + c_b - X); };
  const Eigen::VectorXd u = two_sided(model, above, below);

  Eigen::VectorXd f;
  const kerf::CorotationStatistics stats =
      model.assemble(u, kerf::RotationMethod::automatic, kerf::CorotationalTangent::consistent, f, nullptr, nullptr);
  CHECK(stats.inverted_points == 0);
  // f_int = R K (R^T x - X) is a difference of forces of size |K X|: its round-off is about
  // eps |K X| (position_force_norm); 1e-10 of it is a wide margin that any wrong rotation
  // (errors of order |K X| sin 60 degrees) violates.
  const double relative_force = f.norm() / model.position_force_norm();
  const double corotated = model.energy(u, true), linear = model.energy(u, false);
  MESSAGE("rigid pieces: |f_int| / |K X| = " << relative_force << ", corotated energy " << corotated << " J, linear energy "
                                             << linear << " J");
  CHECK(relative_force <= 1e-10);
  // The linear energy is 1/2 d^T K d with d of order |X| (1 - cos 60): about 10 J. The
  // corotated one is the energy of round-off displacements, ~1e-30 J; 1e-12 of the linear
  // energy separates the two by many orders either way.
  CHECK(linear > 1e-3);
  CHECK(std::abs(corotated) <= 1e-12 * linear); // d = R^T c, a translation in the null space of K: round-off either sign

  // The same pieces with the SAME rotation: also force free, and linear XFEM still sees energy.
  const Eigen::VectorXd u_same = two_sided(model, above, [&](const Eigen::Vector3d& X) { return Eigen::Vector3d(Q_a * X + c_b - X); });
  model.assemble(u_same, kerf::RotationMethod::automatic, kerf::CorotationalTangent::consistent, f, nullptr, nullptr);
  CHECK(f.norm() <= 1e-10 * model.position_force_norm());
}

TEST_CASE("xfem corotational: the consistent tangent is the derivative of the internal forces") {
  // A small beam, a tilted half-depth cut whose front runs through elements (front nodes and
  // tets beyond the front take part), each side turned by its own 30 degrees and strained.
  const kerf::TetMesh mesh = beam({2, 2, 3});
  const kerf::Enrichment e = kerf::make_enrichment(mesh, kerf::RectangleCut({0, 0, 0.09}, {0.02, 0, 0.004}, {0, 0.06, 0}));
  REQUIRE(e.num_enriched() > 0);
  CHECK(e.front_nodes > 0);
  const kerf::XfemModel model(mesh, material, e);
  const Eigen::Matrix3d Q_a = Eigen::AngleAxisd(M_PI / 6, Eigen::Vector3d(0, 1, 0)).toRotationMatrix();
  const Eigen::Matrix3d Q_b = Eigen::AngleAxisd(-M_PI / 6, Eigen::Vector3d(1, 0, 0.2).normalized()).toRotationMatrix();
  Eigen::VectorXd u = two_sided(
      model, [&](const Eigen::Vector3d& X) { return Eigen::Vector3d(Q_a * X - X); },
      [&](const Eigen::Vector3d& X) { return Eigen::Vector3d(Q_b * X - X); });
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> strain(-0.003, 0.003); // 10% of the 0.03 m elements
  for (Eigen::Index i = 0; i < u.size(); ++i) u[i] += strain(rng);

  // Central differences with h = 1e-7 m: truncation (h / element size)^2 ~ 1e-11 relative,
  // round-off eps |K X| / h ~ 1e-16 * |K X| / 1e-7 ~ 1e-9 |K| (|X| ~ 0.1 m): well below 1e-6.
  const support::TangentErrors errors = support::tangent_errors(model, u, 1e-7);
  const double consistent_error = errors.consistent, warped_error = errors.warped;
  MESSAGE("tangent vs central differences (" << u.size() << " DOFs): consistent " << consistent_error << ", warped " << warped_error);
  CHECK(consistent_error < 1e-6);
  // The warped tangent drops the dR/dx terms, which are of the size of the stresses (strains
  // of a few per cent here): it must be off by far more than the consistent one.
  CHECK(warped_error > 1e-3);
  CHECK(warped_error > 1e3 * consistent_error);
}

TEST_CASE("xfem corotational: at rest the tangent is K^X, the linear energy is 1/2 u^T K^X u, and f_int is the energy's gradient") {
  const kerf::TetMesh mesh = beam({2, 2, 3});
  const kerf::Enrichment e = kerf::make_enrichment(mesh, kerf::RectangleCut({0, 0, 0.09}, {0.02, 0, 0.004}, {0, 0.06, 0}));
  const kerf::XfemModel model(mesh, material, e);
  const kerf::DofMap all_free = kerf::make_dof_map(model.num_dof_nodes(), {});
  kerf::SparseAssembler linear(model.assembly_slots(), all_free);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(all_free.num_free);
  model.assemble_linear_stiffness(linear, rhs);
  const Eigen::MatrixXd K_X(linear.matrix());
  Eigen::VectorXd f;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(3 * model.num_dof_nodes());
  const Eigen::MatrixXd K0 = support::assembled_tangent(model, zero, kerf::CorotationalTangent::consistent, f);
  // At X the rotation is I and the stress 0: the consistent tangent is K^X up to round-off.
  CHECK((K0 - K_X).cwiseAbs().maxCoeff() <= 1e-12 * K_X.cwiseAbs().maxCoeff());
  CHECK(f.norm() <= 1e-12 * model.position_force_norm());

  std::mt19937 rng(9);
  std::uniform_real_distribution<double> value(-0.003, 0.003);
  Eigen::VectorXd u(zero.size());
  for (Eigen::Index i = 0; i < u.size(); ++i) u[i] = value(rng);
  const double quadratic = 0.5 * u.dot(K_X * u);
  CHECK(std::abs(model.energy(u, false) - quadratic) <= 1e-12 * quadratic);

  // f_int = dE_corotated / du (the polar rotation makes R K (R^T x - X) the exact gradient).
  // Central differences with h = 1e-8 m: truncation (h / 0.03)^2 ~ 1e-13, round-off
  // eps E / h ~ 1e-16 * 1e-1 / 1e-8 ~ 1e-9 N against forces of ~1e1 N: 1e-6 relative is safe.
  model.assemble(u, kerf::RotationMethod::automatic, kerf::CorotationalTangent::consistent, f, nullptr, nullptr);
  const double h = 1e-8;
  Eigen::VectorXd gradient(u.size());
  for (Eigen::Index j = 0; j < u.size(); ++j) {
    Eigen::VectorXd u_plus = u, u_minus = u;
    u_plus[j] += h;
    u_minus[j] -= h;
    gradient[j] = (model.energy(u_plus, true) - model.energy(u_minus, true)) / (2 * h);
  }
  const double gradient_error = (gradient - f).norm() / f.norm();
  MESSAGE("f_int vs the corotated energy's gradient: relative difference " << gradient_error);
  CHECK(gradient_error < 1e-6);
}

TEST_CASE("xfem corotational: a large pull on a cut along a node layer is chapter 2's corotated split mesh") {
  // The demo's load case (the top edge x = 0 pulled up 0.02 m, the cut opening) on a mesh whose
  // node layer z = 0.1 carries the half-depth cut, plus gravity: corotational XFEM and chapter
  // 2's corotational FEM on the split mesh solve the same nonlinear problem.
  const kerf::TetMesh mesh = beam({2, 3, 8});
  const kerf::RectangleCut cut({0, 0, 0.1}, {0.015, 0, 0}, {0, 0.06, 0});
  const kerf::Enrichment e = kerf::make_enrichment(mesh, cut);
  const kerf::XfemModel model(mesh, material, e);
  const kerf::SplitMesh split = kerf::split_mesh_along_cut(mesh, cut, 1e-9);
  const Eigen::Vector3d g(0, 9.81, 0);
  const auto conditions = [](const kerf::TetMesh& m) {
    std::vector<kerf::DirichletNodes> c(2);
    c[1].displacement = {0, 0, 0.02};
    for (Eigen::Index v = 0; v < m.num_nodes(); ++v) {
      if (std::abs(m.nodes(v, 2)) < 1e-12) c[0].nodes.push_back(static_cast<int>(v));
      if (std::abs(m.nodes(v, 2) - beam_length) < 1e-12 && std::abs(m.nodes(v, 0)) < 1e-12) c[1].nodes.push_back(static_cast<int>(v));
    }
    return c;
  };
  kerf::QuasiStaticSettings settings;
  settings.load_steps = 5;
  settings.tolerance = 1e-11;
  const kerf::QuasiStaticResult xfem = kerf::solve_quasi_static(
      model, kerf::make_xfem_dof_map(model, conditions(mesh)), xfem_gravity(model, material.density * g), settings);
  const kerf::CorotationalModel fem(split.mesh, material);
  const kerf::QuasiStaticResult reference = kerf::solve_quasi_static(
      fem, kerf::make_dof_map(split.mesh.num_nodes(), conditions(split.mesh)),
      kerf::assemble_gravity(split.mesh, material.density, g), settings);
  CHECK(xfem.converged);
  CHECK(reference.converged);
  double worst = 0.0, opening = 0.0;
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v)
    worst = std::max(worst, (xfem.u.segment<3>(3 * v) - reference.u.segment<3>(3 * v)).cwiseAbs().maxCoeff());
  for (std::size_t k = 0; k < split.duplicate_of.size(); ++k) {
    const Eigen::Vector3d below = node_side_value(model, xfem.u, split.duplicate_of[k], -1);
    worst = std::max(worst, (below - reference.u.segment<3>(3 * (mesh.num_nodes() + static_cast<Eigen::Index>(k)))).cwiseAbs().maxCoeff());
    opening = std::max(opening, (xfem.u.segment<3>(3 * split.duplicate_of[k]) - below).norm());
  }
  // Both Newton iterations stop at a relative residual of 1e-11; with a condition number of
  // about 1e5 the solutions agree to ~1e-6 of 0.02 m at worst: 1e-7 m bounds it.
  MESSAGE("corotational XFEM vs corotated split mesh: max difference " << worst << " m, cut opening " << opening << " m, "
                                                                        << xfem.total_iterations << " / " << reference.total_iterations
                                                                        << " Newton iterations");
  CHECK(worst <= 1e-7);
  CHECK(opening > 1e-3);
}
