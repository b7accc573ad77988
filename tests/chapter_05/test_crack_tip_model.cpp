// The XFEM model with crack-tip functions (chapter 5) against fields it must reproduce exactly:
// the plane-strain Williams fields of modes I and II, which the four branch functions span
// (derived here, not in the papers), on a patch whose nodes all carry them, and a hanging column under gravity, a
// quadratic field a Tet10 holds, whose branch coefficients are zero only if the branch rows of
// the body force are integrated (Paulus section 4.2 drops them).
#include "kerf/cut/crack_front.hpp"
#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/point_locator.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"
#include "kerf/xfem/branch_enrichment.hpp"
#include "kerf/xfem/branch_functions.hpp"
#include "kerf/xfem/branch_null_space.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"

#include "support/cut_body.hpp"
#include "support/tip_body.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace {

using support::TipBody;

// The slab [-0.3, 0.3]^2 x [0, 0.2] with the crack y = 0, x < 0 through its whole thickness: the
// straight front x = y = 0 along z runs through the middle of a row of elements (3 cells in x
// and y put the nodes at +-0.1, +-0.3). The rectangle's normal edge1 x edge2 is +y.
const Eigen::Vector3d slab_min(-0.3, -0.3, 0.0), slab_max(0.3, 0.3, 0.2);
kerf::TetMesh slab(int order) {
  const kerf::TetMesh tet4 = kerf::make_box_mesh(slab_min, slab_max, {3, 3, 2});
  return order == 1 ? tet4 : kerf::tet10_from_tet4(tet4);
}
kerf::TriangleSurface slab_crack() {
  return kerf::rectangle_surface(kerf::RectangleCut({-1.0, 0.0, -1.0}, {0.0, 0.0, 2.0}, {1.0, 0.0, 0.0}));
}

bool on_box_boundary(const Eigen::Vector3d& x, const Eigen::Vector3d& min, const Eigen::Vector3d& max) {
  for (int p = 0; p < 3; ++p)
    if (std::abs(x[p] - min[p]) < 1e-12 || std::abs(x[p] - max[p]) < 1e-12) return true;
  return false;
}

// The crack's own axes: a = x ahead, b = y the normal, the front along z through the origin.
// Williams's field about it is support::williams (tip_body.hpp), from the textbook formulas, not
// from the branch functions.
const support::StraightFront slab_front({0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, 1.0, 0.0});
Eigen::Vector3d williams(const Eigen::Vector3d& x, double K_I, double K_II, const kerf::LinearMaterial& material) {
  return support::williams(slab_front, K_I, K_II, material, x);
}

// The largest difference between the discrete field and `exact` at the nodes (standard DOFs,
// which are the field there: the shifted functions vanish at nodes) and at points strewn through
// the slab (the branch functions included), over the largest |exact| there.
double largest_relative_error(const TipBody& body, const Eigen::VectorXd& u, const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& exact,
                              const Eigen::Vector3d& min, const Eigen::Vector3d& max) {
  double error = 0.0, size = 0.0;
  for (Eigen::Index v = 0; v < body.mesh.num_nodes(); ++v) {
    const Eigen::Vector3d e = exact(body.mesh.nodes.row(v).transpose());
    error = std::max(error, (u.segment<3>(3 * v) - e).norm());
    size = std::max(size, e.norm());
  }
  const kerf::PointLocator locator(body.mesh);
  for (int i = 0; i < 7; ++i)
    for (int j = 0; j < 7; ++j) {
      // Off the crack plane and the nodes' planes, some close to the front.
      const Eigen::Vector3d x(min[0] + (max[0] - min[0]) * (i + 0.37) / 7.0, min[1] + (max[1] - min[1]) * (j + 0.41) / 7.0,
                              min[2] + 0.3 * (max[2] - min[2]));
      const kerf::PointLocation where = locator.locate(x);
      REQUIRE(where.tet >= 0);
      error = std::max(error, (body.model.displacement_at(u, where.tet, x) - exact(x)).norm());
    }
  return error / size;
}

} // namespace

TEST_CASE("a slab whose nodes all carry the branch functions reproduces the Williams fields of modes I and II") {
  const kerf::LinearMaterial material{1.0e6, 0.3, 1000.0};
  const Eigen::Vector3d min = slab_min, max = slab_max;
  struct Mode {
    const char* name;
    double K_I, K_II;
  };
  for (const int order : {1, 2})
    for (const Mode mode : {Mode{"I", 1.0e4, 0.0}, Mode{"II", 0.0, 1.0e4}, Mode{"mixed", 1.0e4, -0.6e4}}) {
      // The Tet10's front rule has 6^3 points per collapsed sub-tet: one mode is enough there.
      if (order == 2 && mode.K_II != 0.0) continue;
      CAPTURE(order);
      CAPTURE(mode.name);
      // A radius beyond the slab's diagonal: every node is branch enriched.
      const TipBody body(slab(order), {slab_crack()}, material, kerf::TipEnrichmentRule::geometric, 2.0);
      REQUIRE(body.branch.num_branch_nodes() == (order == 1 ? body.mesh.num_nodes() : 4 * 4 * 3));
      const auto exact = [&](const Eigen::Vector3d& x) { return williams(x, mode.K_I, mode.K_II, material); };

      // The field in the branch functions, u = sum_l F_l c_l (with the frame a = x,
      // b = y that the rectangle's normal gives).
      const std::array<Eigen::Vector3d, 4> c = support::williams_branch_coefficients(slab_front, mode.K_I, mode.K_II, material);
      const Eigen::Vector3d ex = Eigen::Vector3d::UnitX(), ey = Eigen::Vector3d::UnitY();
      // The frame the model measures from is that one (a test of the front's orientation).
      const kerf::FrontPolar polar = body.fronts.polar({-0.2, 0.05, 0.1});
      CHECK((polar.a - ex).norm() < 1e-12);
      CHECK((polar.b - ey).norm() < 1e-12);

      // Every DOF of a boundary node prescribed: u_i = u(x_i) and b_{i,l} = c_l. The interior
      // nodes' test functions vanish on the boundary and the crack faces are traction-free, so
      // the exact field satisfies every free equation: the discrete solution is the exact field
      // up to the quadrature error of those equations.
      std::vector<kerf::DirichletNodes> conditions;
      for (Eigen::Index v = 0; v < body.mesh.num_nodes(); ++v) {
        const Eigen::Vector3d x = body.mesh.nodes.row(v).transpose();
        if (!on_box_boundary(x, min, max)) continue;
        conditions.push_back({{static_cast<int>(v)}, exact(x)});
        // (On a Tet10 only the corners carry branch functions.)
        if (const int k = body.branch.branch_slot[static_cast<std::size_t>(v)]; k >= 0)
          for (int l = 0; l < 4; ++l) conditions.push_back({{static_cast<int>(body.model.branch_dof_node(k)) + l}, c[l]});
      }
      const kerf::DofMap dofs = kerf::make_cut_xfem_dof_map(body.model, conditions);
      const Eigen::VectorXd u =
          kerf::solve_linear_cut_xfem(body.model, dofs, Eigen::VectorXd::Zero(3 * body.model.num_dof_nodes()), kerf::SolverSettings{});
      REQUIRE(u.allFinite());
      const double error = largest_relative_error(body, u, exact, min, max);
      MESSAGE("order " << order << ", mode " << std::string(mode.name) << ": largest relative error " << error);
      // What is left is the quadrature error of the free equations (the branch integrands are
      // no polynomials): measured 1.3e-6 to 1.9e-6 on the Tet4, 1.8e-5 on the Tet10, and it falls
      // with the rules (blending_depth 1, 3, 4 gave 2.1e-5, 1.1e-6, 3.5e-7 on a 5 x 5 x 3 slab),
      // which a wrong frame, sign or shift would not do.
      CHECK(error < (order == 1 ? 1e-5 : 1e-4));
    }
}

TEST_CASE("without branch functions the same slab misses the Williams field by more than a percent") {
  // The test above can fail: chapter 4's rule alone (the cut ends at the last row of sign
  // nodes) cannot hold sqrt(r).
  const kerf::LinearMaterial material{1.0e6, 0.3, 1000.0};
  const Eigen::Vector3d min = slab_min, max = slab_max;
  const TipBody body(slab(1), {slab_crack()}, material, kerf::TipEnrichmentRule::topological, 0.0);
  const auto exact = [&](const Eigen::Vector3d& x) { return williams(x, 1.0e4, 0.0, material); };
  std::vector<kerf::DirichletNodes> conditions;
  for (Eigen::Index v = 0; v < body.mesh.num_nodes(); ++v) {
    const Eigen::Vector3d x = body.mesh.nodes.row(v).transpose();
    if (on_box_boundary(x, min, max)) conditions.push_back({{static_cast<int>(v)}, exact(x)});
  }
  // Topological enrichment with the boundary's branch DOFs at 0: the field near the front is
  // partly branch, but the boundary layer is plain Tet4.
  const kerf::DofMap dofs = kerf::make_cut_xfem_dof_map(body.model, conditions);
  const Eigen::VectorXd u =
      kerf::solve_linear_cut_xfem(body.model, dofs, Eigen::VectorXd::Zero(3 * body.model.num_dof_nodes()), kerf::SolverSettings{});
  CHECK(largest_relative_error(body, u, exact, min, max) > 1e-2);
}

TEST_CASE("a hanging column cut half-way: the Tet10 field is exact only with the branch rows of gravity") {
  // u = rho g / E (z^2 / 2 - L z + nu (x^2 + y^2) / 2) e_z - nu rho g / E (z - L) (x, y, 0) with
  // gravity -g e_z: sigma_zz = rho g (z - L) is the only stress, so the crack plane y = 0
  // (normal y) is traction-free and the field solves the cut problem. It is quadratic: a Tet10
  // holds it with every enrichment coefficient zero.
  const kerf::LinearMaterial material{3.0e5, 0.35, 1070.0};
  const double g = 9.81, L = 0.2, rho = material.density, E = material.young, nu = material.poisson;
  const Eigen::Vector3d min = slab_min, max = slab_max;
  const auto exact = [&](const Eigen::Vector3d& x) {
    const double s = rho * g / E;
    return Eigen::Vector3d(-nu * s * (x[2] - L) * x[0], -nu * s * (x[2] - L) * x[1],
                           s * (0.5 * x[2] * x[2] - L * x[2] + 0.5 * nu * (x[0] * x[0] + x[1] * x[1])));
  };
  const TipBody body(slab(2), {slab_crack()}, material, kerf::TipEnrichmentRule::geometric, 0.25);
  REQUIRE(body.branch.num_branch_nodes() > 0);
  std::vector<kerf::DirichletNodes> conditions;
  for (Eigen::Index v = 0; v < body.mesh.num_nodes(); ++v) {
    const Eigen::Vector3d x = body.mesh.nodes.row(v).transpose();
    if (on_box_boundary(x, min, max)) conditions.push_back({{static_cast<int>(v)}, exact(x)});
  }
  const kerf::DofMap dofs = kerf::make_cut_xfem_dof_map(body.model, conditions);
  const Eigen::VectorXd f = body.model.gravity_load(rho, {0.0, 0.0, -g});
  const Eigen::VectorXd u = kerf::solve_linear_cut_xfem(body.model, dofs, f, kerf::SolverSettings{});
  const double error = largest_relative_error(body, u, exact, min, max);
  MESSAGE("hanging column, branch rows of gravity integrated: largest relative error " << error);
  // The quadrature error of the branch rows (measured 9e-8; 3e-5 with 4 points per direction on
  // the front tets instead of the Tet10 default 6).
  CHECK(error < 1e-6);

  // Dropping them (Paulus's B_n = 0) leaves the branch DOFs loaded by the stiffness alone.
  Eigen::VectorXd dropped = f;
  const Eigen::Index first_branch = 3 * body.model.branch_dof_node(0);
  dropped.tail(dropped.size() - first_branch).setZero();
  const Eigen::VectorXd wrong = kerf::solve_linear_cut_xfem(body.model, dofs, dropped, kerf::SolverSettings{});
  const double dropped_error = largest_relative_error(body, wrong, exact, min, max);
  MESSAGE("hanging column, branch rows dropped: largest relative error " << dropped_error);
  CHECK(dropped_error > 1e3 * error);
}

TEST_CASE("Fries's correction: in a blending tet the field of the branch DOFs is sum_v lambda_v (R F - R(x_v) F(x_v)), its gradient that of central differences") {
  const kerf::LinearMaterial material(1.0e6, 0.3, 1000.0);
  const TipBody body(slab(1), {slab_crack()}, material, kerf::TipEnrichmentRule::topological, 0.0, kerf::FrontRule::collapsed, 3, 4, 0,
                     kerf::BlendingCorrection::corrected);
  REQUIRE(body.branch.num_ramp_nodes() > 0);
  // Every branch slot (I* and ramp) gets c_l for function l; nothing else moves.
  const std::array<Eigen::Vector3d, 4> c{Eigen::Vector3d(1.0, -0.5, 0.2), Eigen::Vector3d(-0.3, 0.8, 0.1), Eigen::Vector3d(0.4, 0.4, -0.6),
                                         Eigen::Vector3d(0.0, -1.0, 0.7)};
  Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * body.model.num_dof_nodes());
  for (int k = 0; k < body.branch.num_branch_nodes(); ++k)
    for (int l = 0; l < 4; ++l) u.segment<3>(3 * (body.model.branch_dof_node(k) + l)) = c[static_cast<std::size_t>(l)];
  // F from the fronts' polar coordinates and branch_function_values, R from the barycentric
  // coordinates of the tet's corners in I*: nothing of the model's own evaluation.
  const auto F_c = [&](const Eigen::Vector3d& x) {
    const kerf::FrontPolar p = body.fronts.polar(x);
    const Eigen::Vector4d F = kerf::branch_function_values(p.r, p.theta);
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int l = 0; l < 4; ++l) sum += F[l] * c[static_cast<std::size_t>(l)];
    return sum;
  };
  double value_error = 0.0, gradient_error = 0.0, size = 0.0, gradient_size = 0.0;
  int tets = 0;
  for (Eigen::Index t = 0; t < body.mesh.num_tets(); ++t) {
    // Uncut blending tets ahead of the front: F is smooth there, no side to decide.
    if (!body.branch.blending[static_cast<std::size_t>(t)] || body.pieces.entry[static_cast<std::size_t>(t)] >= 0) continue;
    const Eigen::Matrix<double, 4, 3> X = kerf::tet_corners(body.mesh, t);
    if (X.col(0).minCoeff() < 0.0) continue;
    ++tets;
    Eigen::Vector4d in_I_star;
    for (int a = 0; a < 4; ++a)
      in_I_star[a] = body.branch.kind[static_cast<std::size_t>(body.mesh.tets(t, a))] == kerf::NodeEnrichmentKind::branch ? 1.0 : 0.0;
    REQUIRE(in_I_star.sum() > 0.0);
    REQUIRE(in_I_star.sum() < 4.0);
    for (const Eigen::Vector4d& weights : {Eigen::Vector4d(0.1, 0.2, 0.3, 0.4), Eigen::Vector4d(0.55, 0.15, 0.05, 0.25), Eigen::Vector4d(0.25, 0.25, 0.25, 0.25)}) {
      const Eigen::Vector3d x = X.transpose() * weights;
      Eigen::Vector3d expected = in_I_star.dot(weights) * F_c(x);
      for (int a = 0; a < 4; ++a) expected -= weights[a] * in_I_star[a] * F_c(X.row(a).transpose());
      value_error = std::max(value_error, (body.model.displacement_at(u, t, x) - expected).norm());
      size = std::max(size, expected.norm());
      // Central differences with h = 1e-6 m (the tet is 0.1 m, F smooth at r > 0.01 m here).
      const double h = 1e-6;
      Eigen::Matrix3d numeric;
      for (int j = 0; j < 3; ++j)
        numeric.col(j) = (body.model.displacement_at(u, t, x + h * Eigen::Vector3d::Unit(j)) - body.model.displacement_at(u, t, x - h * Eigen::Vector3d::Unit(j))) / (2 * h);
      gradient_error = std::max(gradient_error, (body.model.displacement_gradient_at(u, t, x) - numeric).norm());
      gradient_size = std::max(gradient_size, numeric.norm());
    }
  }
  MESSAGE(tets << " blending tets: value error " << value_error / size << ", gradient error " << gradient_error / gradient_size << " (relative)");
  REQUIRE(tets > 0);
  // Both are round-off of one evaluation against another (values) and the central differences'
  // truncation (h / r)^2 ~ 1e-8 with round-off 1e-16 / h ~ 1e-10 (gradients).
  CHECK(value_error < 1e-12 * size);
  CHECK(gradient_error < 1e-6 * gradient_size);
}

TEST_CASE("Fries's correction on a straight front: the identities' six null vectors, and the two held DOFs that remove them without changing the field") {
  // Paulus's beam, coarse: the half-depth cut z = 0.1, x < 0.015 whose front crosses the middle of
  // elements, the end z = 0 clamped, gravity along x. The region of tets with branch functions is
  // interior (no Dirichlet condition reaches it), so the null vectors of branch_null_space.hpp are free.
  const kerf::LinearMaterial material{3.0e5, 0.35, 1070.0};
  const kerf::TriangleSurface cut = kerf::rectangle_surface(kerf::RectangleCut({0.0, 0.0, 0.1}, {0.015, 0.0, 0.0}, {0.0, 0.06, 0.0}));
  const TipBody body(kerf::make_box_mesh({0, 0, 0}, {0.03, 0.06, 0.2}, {3, 6, 9}), {cut}, material, kerf::TipEnrichmentRule::topological, 0.0,
                     kerf::FrontRule::collapsed, 3, 4, 0, kerf::BlendingCorrection::corrected);
  const std::vector<kerf::BranchNullVector> null = kerf::branch_null_vectors(body.model);
  REQUIRE(null.size() == 2);

  // K N = 0 for each vector and component, with every DOF free: the identities hold at every
  // quadrature point, so the residual is round-off of |K| |N| (measured below 1e-14).
  const Eigen::SparseMatrix<double> K = support::full_linear_stiffness(body.model);
  double K_norm = 0.0;
  for (int k = 0; k < K.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(K, k); it; ++it) K_norm = std::max(K_norm, std::abs(it.value()));
  for (const kerf::BranchNullVector& n : null)
    for (int component = 0; component < 3; ++component) {
      Eigen::VectorXd N = Eigen::VectorXd::Zero(K.cols());
      for (const auto& [dof_node, c] : n.coefficients) N[3 * dof_node + component] = c;
      const double residual = (K * N).norm() / (K_norm * N.norm());
      MESSAGE("|K N| / (max |K_ij| |N|) = " << residual);
      CHECK(residual < 1e-12);
    }

  // The clamped beam: make_cut_xfem_dof_map holds the two gauge DOF nodes, CHOLMOD factorises,
  // and the solution satisfies the equations of the held DOFs too (their rows of K u - f vanish),
  // which is what "the field space is unchanged" means: no equation was dropped.
  std::vector<kerf::DirichletNodes> clamp{{{}, Eigen::Vector3d::Zero()}};
  for (Eigen::Index v = 0; v < body.mesh.num_nodes(); ++v)
    if (body.mesh.nodes(v, 2) < 1e-12) clamp[0].nodes.push_back(static_cast<int>(v));
  const kerf::DofMap dofs = kerf::make_cut_xfem_dof_map(body.model, clamp);
  const std::vector<int> gauge = kerf::branch_gauge_dof_nodes(body.model, kerf::make_dof_map(body.model.num_dof_nodes(), clamp));
  CHECK(gauge.size() == 2);
  const Eigen::VectorXd f = body.model.gravity_load(material.density, {9.81, 0.0, 0.0});
  const Eigen::VectorXd u = kerf::solve_linear_cut_xfem(body.model, dofs, f, kerf::SolverSettings{});
  REQUIRE(u.allFinite());
  // The same prescriptions without the gauge: its rows are equations again.
  std::vector<kerf::DirichletNodes> without_gauge{{{}, Eigen::Vector3d::Zero()}};
  for (int d = 0; d < static_cast<int>(body.model.num_dof_nodes()); ++d)
    if (dofs.free_index[3 * static_cast<std::size_t>(d)] < 0 && std::find(gauge.begin(), gauge.end(), d) == gauge.end()) without_gauge[0].nodes.push_back(d);
  const kerf::DofMap ungauged = kerf::make_dof_map(body.model.num_dof_nodes(), without_gauge);
  kerf::SparseAssembler full(body.model.assembly_slots(), ungauged);
  Eigen::VectorXd lifted = Eigen::VectorXd::Zero(ungauged.num_free);
  body.model.assemble_linear_stiffness(full, lifted);
  const Eigen::VectorXd residual = full.matrix() * ungauged.restrict_to_free(u) - ungauged.restrict_to_free(f) - lifted;
  const double relative = residual.norm() / ungauged.restrict_to_free(f).norm();
  MESSAGE("corrected beam: " << body.branch.num_ramp_nodes() << " ramp nodes; residual of every equation, held gauge rows included, " << relative);
  CHECK(relative < 1e-9);
}
