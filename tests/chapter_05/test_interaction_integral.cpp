// The interaction integral in domain form (fracture/interaction_integral.hpp), fed Williams's
// exact gradients on tet meshes of a slab around a straight front that runs through the middle
// of elements. With the exact field the integral's only errors are the quadrature's over the
// ring where q falls (the field is smooth there, q is C1 at the ring's edges) and none from the
// front itself (q is flat around it), so K must come out close to its value and closer as the
// mesh refines; these tests measure how close, for modes I, II and III and mixed mode, and check
// that the answer does not depend on the domain's radii.
#include "kerf/fracture/interaction_integral.hpp"

#include "kerf/cut/split_mesh_along_cut.hpp"
#include "kerf/fem/displacement_gradient.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/solve_linear_static.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

namespace {

const kerf::LinearMaterial material{300e3, 0.35, 1070};

// The slab [-1, 1] x [-1, 1] x [0, 0.5] (m) with n x n x n/4 cells, and a front along z through
// (0.0137, -0.0071): off every node plane of the ladder, so it crosses elements in their middle.
kerf::TetMesh slab(int n) { return kerf::make_box_mesh({-1, -1, 0}, {1, 1, 0.5}, Eigen::Vector3i(n, n, std::max(1, n / 4))); }

// The front's frame: a turned by `angle` about z from +x (the cut lies behind, at x_a < 0).
kerf::StraightFrontFrame front(double angle) {
  const Eigen::Vector3d a(std::cos(angle), std::sin(angle), 0.0), b(-std::sin(angle), std::cos(angle), 0.0);
  return kerf::make_straight_front_frame({0.0137, -0.0071, 0.0}, a, b);
}

kerf::InteractionDomain domain(const kerf::StraightFrontFrame& f, double inner, double outer) {
  kerf::InteractionDomain d;
  d.front = f;
  d.front_begin = 0.0;
  d.front_end = 0.5;
  d.end_ramp = 0.1;
  d.inner_radius = inner;
  d.outer_radius = outer;
  return d;
}

// K of the exact Williams field with factors K on `mesh`, relative error of each mode against the
// largest of the three.
Eigen::Vector3d relative_errors(const kerf::TetMesh& mesh, const kerf::InteractionDomain& d, const kerf::StressIntensityFactors& K) {
  const auto exact_gradient = [&](Eigen::Index, const Eigen::Vector3d& x) { return kerf::williams_displacement_gradient(d.front, K, material, x); };
  const kerf::StressIntensityFactors measured = kerf::interaction_integral_sifs(mesh, exact_gradient, material, d);
  const double scale = std::max({std::abs(K.K_I), std::abs(K.K_II), std::abs(K.K_III)});
  return Eigen::Vector3d(measured.K_I - K.K_I, measured.K_II - K.K_II, measured.K_III - K.K_III).cwiseAbs() / scale;
}

} // namespace

TEST_CASE("K of the exact field within 2e-5 on the finest mesh, modes I, II and mixed, the error falling as the mesh refines") {
  // The front turned by 0.5 rad from the mesh's axes, so that the cut's plane crosses the tets
  // obliquely. Measured, relative errors of (K_I, K_II, K_III) on 8, 16, 32 cells:
  //   mode I:  (1.9e-4, 5.0e-5, 5.4e-5), (5.5e-5, 7.1e-6, 3.6e-4), (1.1e-6, 3.7e-7, 1.6e-6)
  //   mode II: (5.0e-5, 2.3e-4, 3.9e-4), (7.1e-6, 5.2e-5, 1.1e-4), (3.7e-7, 1.8e-6, 1.3e-4).
  // K_I and K_II keep the Gauss rule's error over the ring where q falls: the field is smooth
  // there, q's third derivative jumps at the ring's edges (cylinders no cell follows), and the
  // ring is 1.6 elements wide on the coarsest mesh. The cross-talk into K_III keeps the error of
  // the integrand's 1/r next to the front in w's ramps, on cells refined twice towards it.
  const kerf::StraightFrontFrame f = front(0.5);
  const kerf::InteractionDomain d = domain(f, 0.2, 0.6);
  const kerf::StressIntensityFactors cases[] = {{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}};
  for (const kerf::StressIntensityFactors& K : cases) {
    std::vector<Eigen::Vector3d> errors;
    for (const int n : {8, 16, 32}) errors.push_back(relative_errors(slab(n), d, K));
    MESSAGE("K_I " << K.K_I << ", K_II " << K.K_II << ": relative errors of K_I, K_II, K_III on 8, 16, 32 cells: " << errors[0].transpose()
                   << " / " << errors[1].transpose() << " / " << errors[2].transpose());
    CAPTURE(K.K_I);
    CAPTURE(K.K_II);
    // Kerf's target is 1 % on the finest mesh for an FE field; with the exact field the
    // integral itself must do far better: K_I and K_II within 2e-5 (10 times the measured) and
    // 4 times better than on the coarse mesh (measured 100 times), K_III within 3e-4.
    CHECK(errors[2].head<2>().maxCoeff() <= 2e-5);
    CHECK(errors[2].head<2>().maxCoeff() <= errors[0].head<2>().maxCoeff() / 4);
    CHECK(errors[2][2] <= 3e-4);
  }
  // Mixed mode on the finest mesh: each factor within the same bounds.
  const Eigen::Vector3d mixed = relative_errors(slab(32), d, {1.0, -0.6, 0.0});
  MESSAGE("K_I 1, K_II -0.6: relative errors of K_I, K_II, K_III on 32 cells: " << mixed.transpose());
  CHECK(mixed.head<2>().maxCoeff() <= 2e-5);
  CHECK(mixed[2] <= 3e-4);
}

TEST_CASE("K does not depend on the domain's radii") {
  const kerf::StraightFrontFrame f = front(0.5);
  const kerf::TetMesh mesh = slab(16);
  const kerf::StressIntensityFactors K{1.0, -0.6, 0.0};
  for (const auto& [inner, outer] : {std::pair{0.1, 0.4}, std::pair{0.2, 0.6}, std::pair{0.3, 0.8}, std::pair{0.0, 0.5}}) {
    CAPTURE(inner);
    CAPTURE(outer);
    const Eigen::Vector3d errors = relative_errors(mesh, domain(f, inner, outer), K);
    MESSAGE("radii " << inner << ", " << outer << ": relative errors of K_I, K_II, K_III " << errors.transpose());
    // On 16 cells (h = 0.125 m) each domain gives the exact K up to its quadrature error:
    // K_I and K_II within 2e-4 (measured at most 7.9e-5, on the narrowest ring (0.1, 0.4), 2.4
    // elements wide), K_III within 1e-3 (measured 3.0e-4 for every domain: it comes from the
    // front, inside every ring). The domain with inner radius 0, whose q falls from the front
    // itself so that the cells along the front see the 1/r integrand, is as good as the others.
    CHECK(errors.head<2>().maxCoeff() <= 2e-4);
    CHECK(errors[2] <= 1e-3);
  }
}

TEST_CASE("mode III: K_III within 2e-5 on the finest mesh and falling, its cross-talk within 5e-4") {
  // Mode III has the in-plane stresses sigma_ac, sigma_bc, so its integrand along the front
  // (the c-term sigma_ic du2_i/dx_a + sigma2_ic du_i/dx_a, which w's ramps weight) reaches the
  // front's 1/r: the case that needs the cells refined towards the front and w's breaks as cell
  // faces. Measured: K_III error 2.1e-4 and 3.7e-7 on 8 and 32 cells; K_II (cross-talk) 5.9e-4
  // and 1.9e-4, K_I 8.3e-5 and 2.5e-6.
  const kerf::InteractionDomain d = domain(front(0.5), 0.2, 0.6);
  const Eigen::Vector3d coarse = relative_errors(slab(8), d, {0.0, 0.0, 1.0});
  const Eigen::Vector3d fine = relative_errors(slab(32), d, {0.0, 0.0, 1.0});
  MESSAGE("mode III, relative errors of K_I, K_II, K_III on 8 and 32 cells: " << coarse.transpose() << " / " << fine.transpose());
  CHECK(fine[2] <= 2e-5);
  CHECK(fine[2] <= coarse[2] / 4);
  CHECK(fine.maxCoeff() <= 5e-4);
}

TEST_CASE("the weight q: its gradient matches finite differences, and L_q is the integral of w along the front") {
  kerf::InteractionDomain d = domain(front(0.5), 0.2, 0.6);
  for (const Eigen::Vector3d& y : {Eigen::Vector3d(0.3, 0.1, 0.05), Eigen::Vector3d(-0.25, -0.2, 0.47), Eigen::Vector3d(0.1, 0.1, 0.25),
                                  Eigen::Vector3d(-0.05, 0.5, 0.42)}) {
    const Eigen::Vector3d x = d.front.origin + d.front.R * y;
    Eigen::Vector3d gradient, unused;
    d.weight(x, gradient);
    Eigen::Vector3d fd;
    const double h = 1e-6;
    for (int j = 0; j < 3; ++j)
      fd[j] = (d.weight(x + h * Eigen::Vector3d::Unit(j), unused) - d.weight(x - h * Eigen::Vector3d::Unit(j), unused)) / (2 * h);
    CAPTURE(y.transpose());
    // q is a product of quintics in r and in x_c: central differences err by h^2 times its third
    // derivatives (~1e3 here), 1e-9, and round-off 1e-16 / h = 1e-10.
    CHECK((gradient - fd).norm() <= 1e-8);
  }
  // w along the front (r = 0) by the midpoint rule with 10^5 points: error ~ 1e-10.
  double integral = 0.0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3d unused;
    integral += d.weight(d.front.origin + d.front.R.col(2) * ((i + 0.5) / n * 0.5), unused) * 0.5 / n;
  }
  CHECK(integral == kerf_test::relative(d.weighted_front_length(), 1e-9));
}

TEST_CASE("a domain that reaches the mesh's boundary, and a domain out of range, are refused") {
  const kerf::TetMesh mesh = slab(4);
  const auto zero = [](Eigen::Index, const Eigen::Vector3d&) { return Eigen::Matrix3d::Zero().eval(); };
  // Outer radius 1.2 m: the ring crosses the slab's sides at x, y = +-1.
  CHECK_THROWS_WITH_AS(kerf::interaction_integral_sifs(mesh, zero, material, domain(front(0.0), 0.2, 1.2)),
                       doctest::Contains("reaches the mesh's boundary"), std::invalid_argument);
  // A segment longer than the slab (0.5 m): w > 0 on its face z = 0.5.
  kerf::InteractionDomain long_segment = domain(front(0.0), 0.2, 0.6);
  long_segment.front_end = 0.7;
  CHECK_THROWS_WITH_AS(kerf::interaction_integral_sifs(mesh, zero, material, long_segment), doctest::Contains("reaches the mesh's boundary"),
                       std::invalid_argument);
  kerf::InteractionDomain bad = domain(front(0.0), 0.6, 0.2);
  CHECK_THROWS_WITH_AS(kerf::interaction_integral_sifs(mesh, zero, material, bad), doctest::Contains("outer_radius"), std::invalid_argument);
  bad = domain(front(0.0), 0.2, 0.6);
  bad.end_ramp = 0.3;
  CHECK_THROWS_WITH_AS(kerf::interaction_integral_sifs(mesh, zero, material, bad), doctest::Contains("end_ramp"), std::invalid_argument);
  // A field with no strain has no K (and the domain that fits is accepted).
  const kerf::StressIntensityFactors none = kerf::interaction_integral_sifs(mesh, zero, material, domain(front(0.0), 0.2, 0.6));
  CHECK(none.K_I == 0.0);
  CHECK(none.K_II == 0.0);
  CHECK(none.K_III == 0.0);
}

namespace {

// Williams's field with factors K prescribed at every node on the boundary of the slab
// [-1, 1] x [-1, 1] x [0, 0.25] (Tet10, n x n x 2 cells), cracked along y = 0 for x < 0 by a
// mesh that conforms to the crack (split_mesh_along_cut: the nodes on the crack doubled), solved
// by plain FEM; then K by the interaction integral of the FE gradient.
kerf::StressIntensityFactors fe_sifs(int n, const kerf::StressIntensityFactors& K, double& unknowns) {
  const kerf::TetMesh box = kerf::tet10_from_tet4(kerf::make_box_mesh({-1, -1, 0}, {1, 1, 0.25}, Eigen::Vector3i(n, n, 2)));
  const kerf::RectangleCut crack({-1.5, 0.0, -0.1}, {0.0, 0.0, 0.45}, {1.5, 0.0, 0.0}); // normal +y, front x = 0
  const kerf::SplitMesh split = kerf::split_mesh_along_cut(box, crack, 1e-9);
  const kerf::TetMesh& mesh = split.mesh;
  const kerf::StraightFrontFrame f = kerf::make_straight_front_frame({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  // A node on the crack takes the value of its own side: the duplicates are the tets below (theta = -pi).
  std::vector<kerf::DirichletNodes> conditions;
  const auto original_nodes = static_cast<Eigen::Index>(box.num_nodes());
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) {
    const Eigen::Vector3d x = mesh.nodes.row(v).transpose();
    if ((x.head<2>().cwiseAbs().maxCoeff() < 1 - 1e-12) && x[2] > 1e-12 && x[2] < 0.25 - 1e-12) continue;
    const Eigen::Vector3d side = v >= original_nodes ? Eigen::Vector3d(x[0], -1e-300, x[2]) : x;
    conditions.push_back({{static_cast<int>(v)}, kerf::williams_displacement(f, K, material, side)});
  }
  const kerf::DofMap dofs = kerf::make_dof_map(mesh.num_nodes(), conditions);
  unknowns = dofs.num_free;
  const Eigen::VectorXd u = kerf::solve_linear_static(mesh, material, dofs, Eigen::VectorXd::Zero(3 * mesh.num_nodes()), kerf::SolverSettings{});
  kerf::InteractionDomain d;
  d.front = f;
  d.front_begin = 0.0;
  d.front_end = 0.25;
  d.end_ramp = 0.1;
  d.inner_radius = 0.2;
  d.outer_radius = 0.6;
  const auto fe_gradient = [&](Eigen::Index t, const Eigen::Vector3d& x) { return kerf::displacement_gradient_at(mesh, u, t, x); };
  return kerf::interaction_integral_sifs(mesh, fe_gradient, material, d);
}

} // namespace

TEST_CASE("an FE field: Williams's field on the boundary of a cracked Tet10 slab, K by the interaction integral of the FE gradient") {
  // The end-to-end use the chapter needs, with plain FEM on a mesh that conforms to the crack
  // instead of XFEM: the callback is the FE gradient (displacement_gradient_at). The FE field
  // misses the sqrt(r) singularity, and on a uniform mesh this pollutes the whole field, so K
  // converges like h (measured, relative error of K_I in mode I: 15 %, 8.4 %, 4.2 % on 8, 16,
  // 32 cells; the same for K_II in mode II). The integral itself errs by 1e-4 (tests above):
  // these are the FE field's errors, which the chapter's branch functions are to remove.
  for (const kerf::StressIntensityFactors K : {kerf::StressIntensityFactors{1.0, 0.0, 0.0}, kerf::StressIntensityFactors{0.0, 1.0, 0.0}}) {
    double unknowns_8 = 0, unknowns_16 = 0;
    const kerf::StressIntensityFactors coarse = fe_sifs(8, K, unknowns_8), fine = fe_sifs(16, K, unknowns_16);
    const auto error = [&](const kerf::StressIntensityFactors& m) -> Eigen::Vector3d {
      return Eigen::Vector3d(m.K_I - K.K_I, m.K_II - K.K_II, m.K_III - K.K_III).cwiseAbs();
    };
    MESSAGE("FE field, K_I " << K.K_I << ", K_II " << K.K_II << ": errors of K_I, K_II, K_III with " << unknowns_8 << " unknowns "
                             << error(coarse).transpose() << ", with " << unknowns_16 << " unknowns " << error(fine).transpose());
    const int mode = K.K_I != 0.0 ? 0 : 1;
    CAPTURE(mode);
    // The measured 8.5 % on 16 cells, with room for 10 %; the rate h: the error at least 1.6
    // times smaller on the finer mesh (measured 1.8); each other factor (cross-talk) below 5 %
    // (measured at most 2.8 %).
    CHECK(error(fine)[mode] <= 0.10);
    CHECK(error(fine)[mode] <= error(coarse)[mode] / 1.6);
    for (int other = 0; other < 3; ++other)
      if (other != mode) CHECK(error(fine)[other] <= 0.05);
  }
}

TEST_CASE("the FE gradient of a linear field is its matrix, Tet4 and Tet10, inside and outside the tet") {
  Eigen::Matrix3d A;
  A << 1.0, 2.0, -3.0, 0.5, -0.7, 0.1, -0.2, 0.3, 0.6;
  for (const int order : {1, 2}) {
    kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 2, 3}, Eigen::Vector3i(2, 2, 2));
    if (order == 2) mesh = kerf::tet10_from_tet4(mesh);
    Eigen::VectorXd u(3 * mesh.num_nodes());
    for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) u.segment<3>(3 * v) = A * mesh.nodes.row(v).transpose() + Eigen::Vector3d(1, 2, 3);
    const std::vector<Eigen::Vector3d> points{{0.3, 0.4, 0.5}, {0.9, 1.9, 2.9}};
    for (const Eigen::Index t : {Eigen::Index{0}, mesh.num_tets() - 1})
      for (const Eigen::Vector3d& x : points) CHECK((kerf::displacement_gradient_at(mesh, u, t, x) - A).norm() <= 1e-13 * A.norm());
  }
}
