// The consistent mass of a Tet10 body cut by a kinked surface (xfem/cut_xfem_mass.hpp): the
// total mass, the mass and the first moment of each part the cut separates, exact with a rule of
// degree 4 on the pieces and visibly not with one of degree 2.
#include "chapter_04/ridge_cut.hpp"
#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"
#include "kerf/xfem/cut_xfem_mass.hpp"
#include "kerf/quadrature/gauss_piece_rules.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"
#include "kerf/xfem/surface_enrichment.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <vector>

namespace {

const kerf::LinearMaterial material{1000.0, 0.3, 1200.0};

using ridge_cut::point_in_piece;

} // namespace

TEST_CASE("the Tet10 XFEM mass gives each part of a cut body its mass and first moment exactly") {
  const kerf::TetMesh mesh = kerf::tet10_from_tet4(kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {3, 3, 3}));
  const kerf::CutSurfaces cuts({ridge_cut::surface()});
  const kerf::MeshPieces pieces = kerf::cut_mesh_into_pieces(mesh, cuts);
  const kerf::SurfaceEnrichment enrichment = kerf::make_surface_enrichment(mesh, pieces);
  const kerf::CutXfemModel model(mesh, material, pieces, enrichment, [](const auto&, const auto& p, int piece, int degree) {
    return kerf::subtet_rule(p, piece, degree);
  });
  // The DOFs of the field that is f(x) on the part below the ridge and g(x) above.
  const auto field = [&](const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& below,
                         const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& above) {
    Eigen::VectorXd v = Eigen::VectorXd::Zero(3 * model.num_dof_nodes());
    const Eigen::Index N = mesh.num_nodes();
    for (int pass = 0; pass < 2; ++pass)
      for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
        for (int p = 0; p < model.num_integrated_pieces(t); ++p) {
          const Eigen::Vector3d y = point_in_piece(mesh, pieces, t, p);
          const bool is_above = ridge_cut::side_of(y) > 0;
          for (int a = 0; a < 10; ++a) {
            const int node = model.phantom_node(t, p, a);
            const Eigen::Vector3d x = mesh.nodes.row(mesh.tets(t, a)).transpose();
            const Eigen::Vector3d value = is_above ? above(x) : below(x);
            if (pass == 0 && node < N) v.segment<3>(3 * node) = value;
            if (pass == 1 && node >= N) v.segment<3>(3 * node) = value - v.segment<3>(3 * mesh.tets(t, a));
          }
        }
    return v;
  };
  const auto zero = [](const Eigen::Vector3d&) { return Eigen::Vector3d::Zero().eval(); };
  const auto unit_x = [](const Eigen::Vector3d&) { return Eigen::Vector3d::UnitX().eval(); };
  const auto x_field = [](const Eigen::Vector3d& x) { return Eigen::Vector3d(x.x(), 0.0, 0.0); };

  // Volumes and moments of the part below the ridge, in closed form (y and z integrate out):
  // V = int h dx = 0.45 + 0.1 / 2 = 0.5, int x dV = int x h dx = 0.45 / 2 + 0.1 / 4 = 0.25, and
  // int x^4 dV = int x^4 h dx = 0.45 / 5 + 0.1 (1/192 + 57/960) = 0.0964583...
  const double rho = material.density;
  const double x4_below = 0.45 / 5.0 + 0.1 * (1.0 / 192.0 + 57.0 / 960.0);
  const auto x2_field = [](const Eigen::Vector3d& x) { return Eigen::Vector3d(x.x() * x.x(), 0.0, 0.0); };
  for (const int degree : {4, 2}) {
    CAPTURE(degree);
    const Eigen::SparseMatrix<double> M = kerf::assemble_cut_xfem_mass(
        model, rho, [degree](const auto&, const auto& p, int piece, int) { return kerf::subtet_rule(p, piece, degree); });
    const Eigen::VectorXd all = field(unit_x, unit_x), below = field(unit_x, zero), above = field(zero, unit_x);
    // Masses and first moments are integrals of degree 2 or less on a Tet10 piece
    // (sum_b N_b = 1, and a Tet10 reproduces x exactly): both rules get them.
    CHECK(all.dot(M * all) == kerf_test::relative(rho, 1e-12));
    CHECK(below.dot(M * below) == kerf_test::relative(0.5 * rho, 1e-12));
    CHECK(above.dot(M * above) == kerf_test::relative(0.5 * rho, 1e-12));
    CHECK(std::abs(below.dot(M * above)) <= 1e-12 * rho);
    CHECK(below.dot(M * field(x_field, zero)) == kerf_test::relative(0.25 * rho, 1e-12));
    // The kinetic energy of the quadratic field x^2 e_x on the lower part: rho int x^4, degree 4.
    const Eigen::VectorXd quadratic = field(x2_field, zero);
    const double energy = quadratic.dot(M * quadratic);
    if (degree == 4) CHECK(energy == kerf_test::relative(rho * x4_below, 1e-12));
    else CHECK(std::abs(energy - rho * x4_below) > 1e-7 * rho * x4_below);
  }
}
