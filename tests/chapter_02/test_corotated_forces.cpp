// The corotated internal forces f_int = R K (R^T x - X) (eq. 40) on the test ladder: one tet,
// two tets, the beam, each as Tet4 and Tet10.
//
//  - Where they must be exact: any rigid motion, by any angle, gives zero force and zero
//    energy, while chapter 1's linear forces K u for the same motion do not vanish (the ghost
//    forces that chapter 2 exists to remove).
//  - Their derivative: the consistent tangent of CorotationalModel::assemble equals the
//    central finite difference of f_int; the warped tangent R K R^T (eq. 38) equals it only
//    where the stress is zero, and misses it by about the strain elsewhere.
#include "kerf/corotation/corotational_model.hpp"
#include "kerf/fem/assemble_stiffness.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace {

constexpr double pi = 3.14159265358979323846;

struct NamedMesh {
  std::string name;
  kerf::TetMesh mesh;
};

// The ladder: a skewed single tet, two tets sharing a face, the beam of the book (0.03 x 0.06
// x 0.2 m, a few cells); each also promoted to Tet10. Sizes are a few centimetres, like the beam.
std::vector<NamedMesh> test_ladder() {
  kerf::TetMesh one_tet;
  one_tet.nodes.resize(4, 3);
  one_tet.nodes << 0.0, 0.0, 0.0, 0.05, 0.01, 0.0, 0.01, 0.04, 0.005, 0.012, 0.008, 0.03;
  one_tet.tets.resize(1, 4);
  one_tet.tets << 0, 1, 2, 3;
  kerf::TetMesh two_tets;
  two_tets.nodes.resize(5, 3);
  two_tets.nodes << 0.0, 0.0, 0.0, 0.05, 0.01, 0.0, 0.01, 0.04, 0.005, 0.012, 0.008, 0.03, 0.03, 0.03, -0.03;
  two_tets.tets.resize(2, 4);
  two_tets.tets << 0, 1, 2, 3, 0, 2, 1, 4; // the second tet lies below the face (0, 1, 2)
  const kerf::TetMesh beam = kerf::make_box_mesh({0, 0, 0}, {0.03, 0.06, 0.2}, {1, 2, 4});
  std::vector<NamedMesh> ladder;
  for (const auto& [name, mesh] : {NamedMesh{"one tet", one_tet}, NamedMesh{"two tets", two_tets}, NamedMesh{"beam", beam}}) {
    ladder.push_back({name + " Tet4", mesh});
    ladder.push_back({name + " Tet10", kerf::tet10_from_tet4(mesh)});
  }
  return ladder;
}

Eigen::Matrix3d random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  return Eigen::Quaterniond(gauss(rng), gauss(rng), gauss(rng), gauss(rng)).normalized().toRotationMatrix();
}

Eigen::Vector3d random_unit_vector(std::mt19937& rng) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  return Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized();
}

// The displacement (3#V) of the motion x = A X + t: rigid when A is a rotation.
Eigen::VectorXd affine_displacement(const kerf::TetMesh& mesh, const Eigen::Matrix3d& A, const Eigen::Vector3d& t) {
  Eigen::VectorXd u(3 * mesh.num_nodes());
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) {
    const Eigen::Vector3d X = mesh.nodes.row(v).transpose();
    u.segment<3>(3 * v) = A * X + t - X;
  }
  return u;
}

Eigen::VectorXd internal_forces(const kerf::CorotationalModel& model, const Eigen::VectorXd& u, kerf::RotationMethod rotation) {
  Eigen::VectorXd f_int;
  model.assemble(u, rotation, kerf::CorotationalTangent::warped, f_int, nullptr, nullptr);
  return f_int;
}

// A dense 3#V x 3#V matrix assembled with no Dirichlet DOF, so the free DOFs are all DOFs in
// their natural order.
struct FullAssembly {
  kerf::DofMap dofs;
  kerf::SparseAssembler assembler;
  Eigen::VectorXd rhs;
  explicit FullAssembly(const kerf::TetMesh& mesh)
      : dofs(kerf::make_dof_map(mesh.num_nodes(), {})), assembler(mesh.tets, dofs), rhs(Eigen::VectorXd::Zero(dofs.num_free)) {}
};

Eigen::MatrixXd linear_stiffness(const kerf::TetMesh& mesh, const kerf::LinearMaterial& material) {
  FullAssembly full(mesh);
  kerf::assemble_linear_stiffness(mesh, material, full.assembler, full.rhs);
  return Eigen::MatrixXd(full.assembler.matrix());
}

Eigen::MatrixXd corotated_tangent(const kerf::CorotationalModel& model, const Eigen::VectorXd& u, kerf::CorotationalTangent tangent) {
  FullAssembly full(model.mesh());
  Eigen::VectorXd f_int;
  model.assemble(u, kerf::RotationMethod::svd, tangent, f_int, &full.assembler, &full.rhs);
  return Eigen::MatrixXd(full.assembler.matrix());
}

// Column j is (f_int(u + h e_j) - f_int(u - h e_j)) / 2h.
Eigen::MatrixXd finite_difference_tangent(const kerf::CorotationalModel& model, const Eigen::VectorXd& u, double h) {
  Eigen::MatrixXd K(u.size(), u.size());
  for (Eigen::Index j = 0; j < u.size(); ++j) {
    Eigen::VectorXd plus = u, minus = u;
    plus[j] += h;
    minus[j] -= h;
    K.col(j) = (internal_forces(model, plus, kerf::RotationMethod::svd) - internal_forces(model, minus, kerf::RotationMethod::svd)) / (2.0 * h);
  }
  return K;
}

double relative_max_difference(const Eigen::MatrixXd& A, const Eigen::MatrixXd& reference) {
  return (A - reference).cwiseAbs().maxCoeff() / reference.cwiseAbs().maxCoeff();
}

} // namespace

TEST_CASE("rigid motions: zero corotated force and energy, but linear ghost forces, on the Tet4 and Tet10 ladder") {
  const kerf::LinearMaterial material{300e3, 0.35, 1070};
  std::mt19937 rng(40);
  std::uniform_real_distribution<double> translation(-0.1, 0.1);
  for (const NamedMesh& item : test_ladder()) {
    CAPTURE(item.name);
    const kerf::CorotationalModel model(item.mesh, material);
    const Eigen::MatrixXd K = linear_stiffness(item.mesh, material);
    // The scales: the force and the energy of a unit strain. With x = 2X, F = 2I and R = I,
    // so f_int is exactly the linear K X, and the energy 1/2 X^T K X.
    const Eigen::VectorXd unit_strain = affine_displacement(item.mesh, 2.0 * Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
    const double force_scale = internal_forces(model, unit_strain, kerf::RotationMethod::svd).norm();
    const double energy_scale = model.energy(unit_strain, kerf::RotationMethod::svd);
    REQUIRE(force_scale > 0.0);
    REQUIRE((K * unit_strain).norm() == kerf_test::relative(force_scale, 1e-12));

    // Quarter and half turns about random axes (180 degrees is where R = -I + 2 a a^T and the
    // small-rotation idea is as wrong as it gets), then random rotations.
    std::vector<Eigen::Matrix3d> rotations;
    std::vector<bool> large;
    for (double degrees : {90.0, 180.0, -90.0})
      for (int k = 0; k < 3; ++k) {
        rotations.push_back(Eigen::AngleAxisd(degrees * pi / 180.0, random_unit_vector(rng)).toRotationMatrix());
        large.push_back(true);
      }
    for (int k = 0; k < 20; ++k) {
      rotations.push_back(random_rotation(rng));
      large.push_back(false);
    }
    double worst_force = 0.0, worst_energy = 0.0, smallest_ghost = 1e300;
    for (std::size_t k = 0; k < rotations.size(); ++k) {
      const Eigen::Vector3d t(translation(rng), translation(rng), translation(rng));
      const Eigen::VectorXd u = affine_displacement(item.mesh, rotations[k], t);
      for (const kerf::RotationMethod method : {kerf::RotationMethod::higham, kerf::RotationMethod::svd}) {
        worst_force = std::max(worst_force, internal_forces(model, u, method).norm() / force_scale);
        worst_energy = std::max(worst_energy, std::abs(model.energy(u, method)) / energy_scale);
      }
      if (large[k]) smallest_ghost = std::min(smallest_ghost, (K * u).norm() / force_scale);
    }
    MESSAGE(item.name << ": rigid motion |f_int| / |K X| <= " << worst_force << ", energy / (X^T K X / 2) <= " << worst_energy
                      << "; linear |K u| / |K X| >= " << smallest_ghost << " at 90 and 180 degrees");
    // R is the exact rotation to a few ulps, so R^T x - X is X's round-off (1e-16 of the
    // positions, translations included) and f = R K (R^T x - X) is ~1e-15 of |K X|; 1e-10 leaves
    // room for the cancellation in R^T x - X when |t| is several times the body.
    CHECK(worst_force < 1e-10);
    // The energy is quadratic in those round-off differences (or linear in them times a
    // translation that K annihilates up to round-off): 1e-12 is generous.
    CHECK(worst_energy < 1e-12);
    // Linear elasticity sees u = (Q - I) X + t as the strain sym(Q - I) = (cos(theta) - 1)(...):
    // of order one at 90 degrees, so its forces are of the order of the unit-strain forces.
    CHECK(smallest_ghost > 1e-2);
  }
}

TEST_CASE("the consistent tangent is the derivative of f_int; the warped one only at zero stress") {
  const kerf::LinearMaterial material{300e3, 0.35, 1070};
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (const int order : {1, 2}) {
    CAPTURE(order);
    kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {0.03, 0.06, 0.2}, {1, 2, 3});
    if (order == 2) mesh = kerf::tet10_from_tet4(mesh);
    const kerf::CorotationalModel model(mesh, material);
    // A large rotation (70 degrees about a random axis) and a translation, applied to
    // (a) the undeformed beam and (b) the beam with a random homogeneous strain E of 5% plus a
    // random nodal perturbation of 1% of a cell, so that every element has its own R and S.
    const Eigen::Matrix3d Q = Eigen::AngleAxisd(70.0 * pi / 180.0, random_unit_vector(rng)).toRotationMatrix();
    const Eigen::Vector3d t(0.01, -0.02, 0.03);
    Eigen::Matrix3d E;
    for (int i = 0; i < 9; ++i) E(i) = unit(rng);
    E = 0.05 * (E + E.transpose()) / (E + E.transpose()).cwiseAbs().maxCoeff();
    Eigen::VectorXd u_rigid = affine_displacement(mesh, Q, t), u_strained = affine_displacement(mesh, Q * (Eigen::Matrix3d::Identity() + E), t);
    for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v)
      u_strained.segment<3>(3 * v) += Q * Eigen::Vector3d(unit(rng), unit(rng), unit(rng)) * 0.01 * 0.015;

    // h = 1e-6 m against cells of 1.5-7 cm: the truncation error of the central difference is
    // (h / cell)^2 / 6 ~ 1e-10 of the tangent (each derivative of R costs one 1 / cell); its
    // round-off is 1e-16 |K| |x| / h ~ 1e-16 * 0.3 m / 1e-6 m ~ 3e-11 of |K|. We allow 1e-6.
    const double h = 1e-6;
    for (const bool strained : {false, true}) {
      CAPTURE(strained);
      const Eigen::VectorXd& u = strained ? u_strained : u_rigid;
      const Eigen::MatrixXd K_fd = finite_difference_tangent(model, u, h);
      const Eigen::MatrixXd K_consistent = corotated_tangent(model, u, kerf::CorotationalTangent::consistent);
      const Eigen::MatrixXd K_warped = corotated_tangent(model, u, kerf::CorotationalTangent::warped);
      const double consistent_error = relative_max_difference(K_consistent, K_fd);
      const double warped_error = relative_max_difference(K_warped, K_fd);
      const double asymmetry = relative_max_difference(K_consistent, K_consistent.transpose());
      MESSAGE("order " << order << std::string(strained ? ", 5% strain" : ", zero strain") << " under a 70 degree rotation: |K_consistent - K_fd| "
                       << consistent_error << ", |K_warped - K_fd| " << warped_error << ", asymmetry of K_consistent " << asymmetry
                       << " (relative to max |K_fd|)");
      CHECK(consistent_error < 1e-6);
      // For the polar rotation f_int is the gradient of the corotated energy, so its Jacobian
      // is symmetric; the assembled one is, to round-off.
      CHECK(asymmetry < 1e-12);
      if (!strained) {
        // Zero stress: the dR/dx terms multiply sigma and (S W - W S) with S = I, both zero.
        CHECK(warped_error < 1e-6);
      } else {
        // The dR/dx terms scale with the stress, sigma ~ E * strain: the warped tangent misses
        // the derivative by about the strain (5%), clearly more than the FD error, and less
        // than the stiffness itself.
        CHECK(warped_error > 1e-3);
        CHECK(warped_error < 0.2);
      }
    }
  }
}
