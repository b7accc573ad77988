// Corotational XFEM with crack-tip functions: a tet with branch functions is
// turned by one rotation per piece, that of the piece's mean deformation gradient
// (corotated_piece.hpp). Checked against what must hold whatever the formulas inside:
// - on a plain Tet4's own four slots the piece formula IS chapter 2's point formula;
// - a rigid rotation of a strained slab (its branch coefficients turned with it) turns the
//   forces and keeps the energy, while linear XFEM feels ghost forces;
// - the consistent tangent is the derivative of the forces (central differences);
// - a slab with the Williams field on its boundary, turned by 0.5 rad, is solved by Newton into
//   the turned linear solution, to the size of the strain;
// - what does not combine with the functions (eqs. 81-82's lumped mass) is refused with a message.
#include "kerf/app/input_error.hpp"
#include "kerf/corotation/corotated_element.hpp"
#include "kerf/corotation/corotated_piece.hpp"
#include "kerf/corotation/quasi_static_solver.hpp"
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/dynamics/lumped_mass.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/fem/tet_shape_functions.hpp"
#include "kerf/fem/tet_stiffness.hpp"
#include "kerf/fracture/williams_field.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"
#include "kerf/scene/scene.hpp"
#include "kerf/xfem/cut_xfem_mass.hpp"

#include "support/cut_body.hpp"
#include "support/tangent_check.hpp"

#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

const kerf::LinearMaterial material{1.0e6, 0.3, 1000.0};

// The slab [-0.3, 0.3]^2 x [0, 0.2], 3 x 3 x cells_z cells, cut by y = 0, x < 0 through its
// thickness: the front x = y = 0 runs through the middle of a row of elements.
kerf::TetMesh slab(int order, int cells_z = 2) {
  const kerf::TetMesh tet4 = kerf::make_box_mesh({-0.3, -0.3, 0.0}, {0.3, 0.3, 0.2}, {3, 3, cells_z});
  return order == 1 ? tet4 : kerf::tet10_from_tet4(tet4);
}
kerf::TriangleSurface slab_crack() {
  return kerf::rectangle_surface(kerf::RectangleCut({-1.0, 0.0, -1.0}, {0.0, 0.0, 2.0}, {1.0, 0.0, 0.0}));
}
// The slab's body with cheap rules: every check here compares the model with itself turned, or
// with its own linear solution, so the quadrature's accuracy does not enter (sub-tets refined
// once of degree 3 on the front tets, degree 2 without grading on the blending tets).
support::TipBody slab_body(int order, int cells_z) {
  return support::TipBody(slab(order, cells_z), {slab_crack()}, material, kerf::TipEnrichmentRule::topological, 0.0,
                          kerf::FrontRule::refined_subtets, 2, 2, 0);
}
bool on_slab_boundary(const Eigen::Vector3d& x) {
  return std::abs(std::abs(x[0]) - 0.3) < 1e-12 || std::abs(std::abs(x[1]) - 0.3) < 1e-12 || x[2] < 1e-12 || x[2] > 0.2 - 1e-12;
}

// The state of the rigid rotation Q of the configuration u: every position X + u turned, every
// enrichment coefficient (sign and branch) turned.
Eigen::VectorXd turned(const kerf::CutXfemModel& model, const kerf::TetMesh& mesh, const Eigen::VectorXd& u, const Eigen::Matrix3d& Q) {
  Eigen::VectorXd v(u.size());
  for (Eigen::Index k = 0; k < model.num_dof_nodes(); ++k) {
    const Eigen::Vector3d q = u.segment<3>(3 * k);
    if (k < mesh.num_nodes()) {
      const Eigen::Vector3d X = mesh.nodes.row(k).transpose();
      v.segment<3>(3 * k) = Q * (X + q) - X;
    } else {
      v.segment<3>(3 * k) = Q * q;
    }
  }
  return v;
}

// Q applied to every 3-block.
Eigen::VectorXd turn_blocks(const Eigen::VectorXd& f, const Eigen::Matrix3d& Q) {
  Eigen::VectorXd g(f.size());
  for (Eigen::Index k = 0; 3 * k < f.size(); ++k) g.segment<3>(3 * k) = Q * f.segment<3>(3 * k);
  return g;
}

} // namespace

TEST_CASE("on a Tet4's own four slots one rotation per piece is chapter 2's corotated point: force and both tangents") {
  const Eigen::Matrix<double, 4, 3> X = (Eigen::Matrix<double, 4, 3>() << 0.01, -0.02, 0.0, 0.11, 0.01, 0.02, 0.02, 0.09, -0.01, 0.0, 0.03, 0.12).finished();
  Eigen::Matrix3d J;
  for (int c = 0; c < 3; ++c) J.col(c) = (X.row(c + 1) - X.row(0)).transpose();
  const Eigen::Matrix<double, 4, 3> G = kerf::tet4_shape_gradients() * J.inverse();
  const double V = std::abs(J.determinant()) / 6.0;
  Eigen::Matrix<double, 12, 12> K = Eigen::Matrix<double, 12, 12>::Zero();
  kerf::add_stiffness_integrand<4>(G, V, material.mu(), material.lambda(), K);
  // A 40-degree turn with strains of several per cent.
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  Eigen::Matrix<double, 4, 3> u;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> noise(-0.004, 0.004);
  for (int a = 0; a < 4; ++a) u.row(a) = (Q * X.row(a).transpose() - X.row(a).transpose()).transpose() + Eigen::RowVector3d(noise(rng), noise(rng), noise(rng));

  for (const auto kind : {kerf::CorotationalTangent::warped, kerf::CorotationalTangent::consistent}) {
    Eigen::Matrix<double, 12, 1> f_point = Eigen::Matrix<double, 12, 1>::Zero();
    Eigen::Matrix<double, 12, 12> K_point = Eigen::Matrix<double, 12, 12>::Zero();
    kerf::add_corotated_point<4>(K, G, X, u, V, material.mu(), material.lambda(), kerf::RotationMethod::automatic, kind, f_point, &K_point);
    Eigen::VectorXd f_piece = Eigen::VectorXd::Zero(12);
    Eigen::MatrixXd K_piece = Eigen::MatrixXd::Zero(12, 12);
    kerf::add_corotated_piece(Eigen::MatrixXd(K), Eigen::MatrixX3d(G), 4, Eigen::MatrixX3d(X), Eigen::MatrixX3d(u), V,
                              kerf::RotationMethod::automatic, kind, f_piece, &K_piece);
    // Two derivations of the same quantities: they agree to round-off (1e-12 of their size).
    CHECK((f_piece - f_point).norm() <= 1e-12 * f_point.norm());
    CHECK((K_piece - K_point).norm() <= 1e-12 * K_point.norm());
  }
}

TEST_CASE("a strained slab with branch tets turned rigidly: the corotated forces turn with it and the energy stays; linear XFEM's do not") {
  for (const int order : {1, 2}) {
    CAPTURE(order);
    const support::TipBody body = slab_body(order, 1);
    REQUIRE(body.branch.num_branch_nodes() > 0);
    const kerf::CutXfemModel& model = body.model;
    // A strained state: every DOF (standard, sign and branch) given a random value of 1e-3.
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> noise(-1e-3, 1e-3);
    Eigen::VectorXd u(3 * model.num_dof_nodes());
    for (Eigen::Index i = 0; i < u.size(); ++i) u[i] = noise(rng);
    const Eigen::Matrix3d Q = Eigen::AngleAxisd(0.9, Eigen::Vector3d(0.3, 1.0, -0.6).normalized()).toRotationMatrix();
    const Eigen::VectorXd u_turned = turned(model, body.mesh, u, Q);

    Eigen::VectorXd f, f_turned;
    model.assemble(u, kerf::RotationMethod::automatic, kerf::CorotationalTangent::warped, f, nullptr, nullptr);
    model.assemble(u_turned, kerf::RotationMethod::automatic, kerf::CorotationalTangent::warped, f_turned, nullptr, nullptr);
    const double force_error = (f_turned - turn_blocks(f, Q)).norm() / f.norm();
    const double energy = model.energy(u, true), energy_turned = model.energy(u_turned, true);
    // Linear XFEM on the same two states: K u_turned is not Q K u (ghost forces).
    const Eigen::MatrixXd K = support::assembled_tangent(model, Eigen::VectorXd::Zero(u.size()), kerf::CorotationalTangent::warped, f);
    model.assemble(u, kerf::RotationMethod::automatic, kerf::CorotationalTangent::warped, f, nullptr, nullptr);
    const double linear_error = (K * u_turned - turn_blocks(K * u, Q)).norm() / (K * u).norm();
    MESSAGE("order " << order << ": corotated |f(Qx) - Q f(x)| / |f| = " << force_error << ", energy " << energy << " -> " << energy_turned
                     << " J; linear " << linear_error);
    // f is a difference of forces of size |K X| (position_force_norm): its round-off is about
    // eps |K X|, 1e-16 * |K X| / |f| ~ 1e-13 here; a wrong rotation of any slot (the branch
    // ones included) is an error of order one.
    CHECK(force_error < 1e-9);
    CHECK(std::abs(energy_turned - energy) <= 1e-9 * energy);
    CHECK(linear_error > 0.1);
    // The linear energy of the branch tets is 1/2 u^T K u with the assembled K (to round-off).
    const double quadratic = 0.5 * u.dot(K * u);
    CHECK(std::abs(model.energy(u, false) - quadratic) <= 1e-12 * quadratic);

    // From rest, a rigid turn alone: no force at all.
    model.assemble(turned(model, body.mesh, Eigen::VectorXd::Zero(u.size()), Q), kerf::RotationMethod::automatic,
                   kerf::CorotationalTangent::warped, f, nullptr, nullptr);
    CHECK(f.norm() <= 1e-10 * model.position_force_norm());
  }
}

TEST_CASE("with branch tets the consistent tangent is the derivative of the corotated forces") {
  const support::TipBody body = slab_body(1, 1);
  const kerf::CutXfemModel& model = body.model;
  // Turned by 30 degrees and strained by about 1 % (random DOFs of 1e-3 on 0.2 m elements).
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> noise(-1e-3, 1e-3);
  Eigen::VectorXd u(3 * model.num_dof_nodes());
  for (Eigen::Index i = 0; i < u.size(); ++i) u[i] = noise(rng);
  u = turned(model, body.mesh, u, Eigen::AngleAxisd(M_PI / 6, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix());

  // Central differences with h = 1e-7 m: truncation (h / 0.2 m)^2 ~ 1e-13, round-off
  // eps |K X| / h ~ 1e-9 |K|; 1e-6 is far above both.
  const support::TangentErrors errors = support::tangent_errors(model, u, 1e-7);
  const double consistent_error = errors.consistent, warped_error = errors.warped;
  MESSAGE("tangent vs central differences (" << u.size() << " DOFs, " << body.branch.num_branch_nodes()
                                             << " branch nodes): consistent " << consistent_error << ", warped " << warped_error);
  CHECK(consistent_error < 1e-6);
  // The warped tangent misses the dR terms (of the size of the stresses): far off by comparison.
  CHECK(warped_error > 1e3 * consistent_error);
}

TEST_CASE("the Williams slab turned by 0.5 rad: Newton with corotated branch tets finds the turned linear solution") {
  const support::TipBody body = slab_body(1, 2);
  const kerf::CutXfemModel& model = body.model;
  // K_I = 100 Pa sqrt(m): displacements ~3e-5 m on the 0.6 m slab, strains ~1e-4.
  const kerf::StraightFrontFrame front = kerf::make_straight_front_frame({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  const kerf::StressIntensityFactors K{100.0, 0.0, 0.0};
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();

  // The boundary nodes' standard DOFs take the Williams field (the branch DOFs stay free), then
  // the same turned: x = Q (X + u_W) - X, reached along the turn's angle.
  std::vector<int> boundary;
  for (Eigen::Index v = 0; v < body.mesh.num_nodes(); ++v)
    if (on_slab_boundary(body.mesh.nodes.row(v).transpose())) boundary.push_back(static_cast<int>(v));
  const auto conditions_at = [&](double lambda) {
    const Eigen::Matrix3d Q_lambda = Eigen::AngleAxisd(0.5 * lambda, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    std::vector<kerf::DirichletNodes> conditions;
    for (const int v : boundary) {
      const Eigen::Vector3d X = body.mesh.nodes.row(v).transpose();
      conditions.push_back({{v}, Eigen::Vector3d(Q_lambda * (X + lambda * kerf::williams_displacement(front, K, material, X)) - X)});
    }
    return conditions;
  };
  const Eigen::Index dofs_total = 3 * model.num_dof_nodes();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(dofs_total);
  // The linear solution, unturned.
  std::vector<kerf::DirichletNodes> linear_conditions;
  for (const int v : boundary) {
    const Eigen::Vector3d X = body.mesh.nodes.row(v).transpose();
    linear_conditions.push_back({{v}, kerf::williams_displacement(front, K, material, X)});
  }
  const Eigen::VectorXd u_linear = kerf::solve_linear_cut_xfem(model, kerf::make_cut_xfem_dof_map(model, linear_conditions), zero, {});
  REQUIRE(u_linear.allFinite());

  const kerf::DofMap dofs = kerf::make_cut_xfem_dof_map(model, conditions_at(1.0));
  const kerf::PrescribedPath path = [&](double lambda) {
    Eigen::VectorXd u_c = Eigen::VectorXd::Zero(dofs_total);
    for (const kerf::DirichletNodes& c : conditions_at(lambda)) u_c.segment<3>(3 * c.nodes.front()) = c.displacement;
    return u_c;
  };
  kerf::QuasiStaticSettings settings;
  settings.load_steps = 4;
  const kerf::QuasiStaticResult result = kerf::solve_quasi_static(model, dofs, zero, settings, path);
  REQUIRE(result.converged);
  REQUIRE(result.u.allFinite());

  const Eigen::VectorXd expected = turned(model, body.mesh, u_linear, Q);
  double size = 0.0, error = 0.0;
  for (Eigen::Index k = 0; k < model.num_dof_nodes(); ++k) {
    size = std::max(size, u_linear.segment<3>(3 * k).norm());
    error = std::max(error, (result.u.segment<3>(3 * k) - expected.segment<3>(3 * k)).norm());
  }
  // The linear model solving the same turned problem, for contrast.
  const Eigen::VectorXd u_linear_turned = kerf::solve_linear_cut_xfem(model, dofs, zero, {});
  double linear_error = 0.0;
  for (Eigen::Index k = 0; k < model.num_dof_nodes(); ++k)
    linear_error = std::max(linear_error, (u_linear_turned.segment<3>(3 * k) - expected.segment<3>(3 * k)).norm());
  MESSAGE("turned Williams slab: corotated " << error / size << " of max |u| = " << size << " m, linear " << linear_error / size << "; "
                                             << result.total_iterations << " Newton iterations");
  // What is left is geometric nonlinearity, the corotated against the linear element at the
  // slab's strains (max |u| / element size ~ 1e-3): measured 1.2e-4 of max |u|; 1e-3 allows for
  // it. A wrong or missing rotation of the branch coefficients leaves an error of order one,
  // as the linear model shows (366 times max |u|, the turn itself).
  CHECK(error < 1e-3 * size);
  CHECK(linear_error > 0.3 * size);
}

TEST_CASE("with crack-tip functions eqs. 81-82 are refused with a message; the other masses and chapter 6's scenes take them") {
  const support::TipBody body = slab_body(1, 1);
  // Eqs. 81-82 give the branch DOFs no mass: asked for it, they throw rather than leave them
  // without inertia. The consistent and per-piece masses have the branch rows
  // (tests/dynamics/test_branch_mass.cpp checks them).
  CHECK_THROWS_WITH_AS(kerf::lump_cut_xfem_mass(body.model, 1000.0, kerf::LumpingScheme::schoch_eq_81_82, support::subtets),
                       doctest::Contains("crack-tip functions"), std::invalid_argument);
  CHECK_THROWS_WITH_AS(kerf::lumped_gravity_load(body.model, 1000.0, {0, 0, -9.81}, kerf::LumpingScheme::schoch_eq_81_82, support::subtets),
                       doctest::Contains("crack-tip functions"), std::invalid_argument);
  CHECK_NOTHROW(kerf::assemble_cut_xfem_mass(body.model, 1000.0, support::subtets));
  CHECK_NOTHROW(kerf::lump_cut_xfem_mass(body.model, 1000.0, kerf::LumpingScheme::row_sum, support::subtets));
  // A scene with "crack_tip": chapter 6 (dynamics and crack tips taught) takes it; a chapter
  // that does not teach crack tips refuses it in one line naming the file and the field.
  kerf::Scene scene;
  scene.source = "cut.json";
  scene.crack_tip.given = true;
  CHECK_NOTHROW(kerf::require_features(
      scene, kerf::SceneFeatures{.corotational = true, .cuts = true, .dynamics = true, .cut_quadrature = true, .crack_tip = true}));
  try {
    kerf::require_features(scene, kerf::SceneFeatures{.corotational = true, .cuts = true, .cut_quadrature = true});
    FAIL("chapter 4 accepted a crack_tip field");
  } catch (const kerf::InputError& error) {
    const std::string message = error.what();
    CHECK(message.find("cut.json") != std::string::npos);
    CHECK(message.find("crack_tip") != std::string::npos);
    CHECK(message.find("chapter 5") != std::string::npos);
    CHECK(message.find('\n') == std::string::npos);
  }
}
