// CutXfemModel::energy, which chapter 6's energy account uses for the elastic energy: its
// gradient is assemble()'s internal force (finite differences), it vanishes on a rigid motion of
// every piece, and with R = I it is 1/2 u^T K u with the linear stiffness.
#include "dynamics/cut_body.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <random>

namespace {

const kerf::LinearMaterial material{300e3, 0.35, 1070.0};

// A 2 x 2 x 2 block of the unit cube cut clean through by a tilted plane (Tet4 or Tet10).
cut_body::CutBody cut_block(int order) {
  kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {2, 2, 2});
  if (order == 2) mesh = kerf::tet10_from_tet4(mesh);
  return cut_body::CutBody(std::move(mesh), {cut_body::plane_surface({0.2, -0.1, 1}, 0.55, {0.5, 0.5, 0.5}, 3.0)}, material);
}

Eigen::VectorXd random_vector(Eigen::Index size, double scale, unsigned seed) {
  std::mt19937 engine(seed);
  std::uniform_real_distribution<double> uniform(-scale, scale);
  Eigen::VectorXd x(size);
  for (Eigen::Index i = 0; i < size; ++i) x[i] = uniform(engine);
  return x;
}

} // namespace

TEST_CASE("the corotated energy of a cut body has assemble()'s internal force as its gradient") {
  for (const int order : {1, 2}) {
    CAPTURE(order);
    const cut_body::CutBody body = cut_block(order);
    REQUIRE(body.enrichment.num_enrichments() > 0);
    // A large deformation: a rotation by 0.6 rad of the whole field, plus a random strain of 5 %.
    const Eigen::Matrix3d Q = Eigen::AngleAxisd(0.6, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    const Eigen::VectorXd rotation = body.piecewise_field([](const Eigen::Vector3d& x) { return x.z() + 0.2 * x.x() - 0.1 * x.y() < 0.55 ? -1 : 1; },
                                                          [&](const Eigen::Vector3d& x, int) { return Eigen::Vector3d((Q - Eigen::Matrix3d::Identity()) * x); });
    const Eigen::VectorXd u = rotation + random_vector(rotation.size(), 0.05 / 2, 7);
    Eigen::VectorXd f_int;
    body.model.assemble(u, kerf::RotationMethod::automatic, kerf::CorotationalTangent::warped, f_int, nullptr, nullptr);
    // Central differences along a random direction d: (W(u + h d) - W(u - h d)) / 2h = f . d + O(h^2).
    // With h = 1e-6 the truncation (h^2 |W'''| ~ 1e-12 E) and the round-off (eps W / h ~ 1e-10 W)
    // are both far below 1e-6 of f . d.
    const Eigen::VectorXd d = random_vector(u.size(), 1.0, 11);
    const double h = 1e-6;
    const double fd = (body.model.energy(u + h * d, true) - body.model.energy(u - h * d, true)) / (2 * h);
    CHECK(fd == kerf_test::relative(f_int.dot(d), 1e-6));
    CHECK(body.model.energy(u, true) > 0.0);
  }
}

TEST_CASE("the corotated energy of a rigid motion of every piece is zero, and the linear energy is 1/2 u^T K u") {
  const cut_body::CutBody body = cut_block(1);
  const auto side = [](const Eigen::Vector3d& x) { return x.z() + 0.2 * x.x() - 0.1 * x.y() < 0.55 ? -1 : 1; };
  // The two parts turned by different rotations (the cut opens), each part rigid.
  const Eigen::Matrix3d Q_below = Eigen::AngleAxisd(0.9, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Matrix3d Q_above = Eigen::AngleAxisd(-1.3, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  const Eigen::VectorXd rigid = body.piecewise_field(side, [&](const Eigen::Vector3d& x, int s) {
    const Eigen::Matrix3d& Q = s < 0 ? Q_below : Q_above;
    return Eigen::Vector3d((Q - Eigen::Matrix3d::Identity()) * x + Eigen::Vector3d(0.1, s * 0.3, 0));
  });
  // Zero up to the round-off of R^T x - X on unit-sized elements: eps^2 E V, far below 1e-20 J.
  CHECK(body.model.energy(rigid, true) <= 1e-18);
  // The linear energy of the same field is not zero: the linear model feels rotations as strain.
  const Eigen::SparseMatrix<double> K = body.stiffness();
  const double linear = body.model.energy(rigid, false);
  CHECK(linear > 1e3);
  // Two summations of the same element integrals: round-off only.
  CHECK(linear == kerf_test::relative(0.5 * rigid.dot(K * rigid), 1e-12));
}
