// Chapter 7 rebuilds its system at every change of topology and takes the gravity load as
// M e_g, the mass times a unit translation along g (u = g at every node, every enrichment 0),
// instead of a second pass over every piece's rule. That is the definition of the loads that go
// with each mass (dynamics/lumped_mass.hpp: "each phantom node pulled by its own mass"; for the
// consistent mass rho int N^T g, CutXfemModel::gravity_load). Here we check the identity against
// the library's own functions on a cut body, so that the shortcut cannot drift from them.
#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/dynamics/lumped_mass.hpp"
#include "kerf/fem/linear_material.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/quadrature/gauss_piece_rules.hpp"
#include "kerf/xfem/cut_xfem_mass.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"
#include "kerf/xfem/surface_enrichment.hpp"

#include <doctest/doctest.h>

TEST_CASE("the gravity load of every mass is that mass times a unit translation along g") {
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {0.03, 0.06, 0.2}, {3, 6, 10});
  // A slanted rectangle that ends inside the beam: split tets, pieces of all shapes, and tets the
  // front passes through (integrated whole, no enrichment).
  kerf::TriangleSurface cut;
  cut.vertices = Eigen::MatrixX3d{{-0.01, -0.01, 0.07}, {0.04, -0.01, 0.09}, {0.04, 0.045, 0.11}, {-0.01, 0.045, 0.09}};
  cut.triangles = Eigen::MatrixX3i{{0, 1, 2}, {0, 2, 3}};
  const kerf::CutSurfaces cuts({cut});
  const kerf::MeshPieces pieces = kerf::cut_mesh_into_pieces(mesh, cuts);
  const kerf::SurfaceEnrichment enrichment = kerf::make_surface_enrichment(mesh, pieces);
  const kerf::PieceRuleFunction rule = [](const Eigen::Matrix<double, 4, 3>&, const kerf::TetPieces& p, int piece, int degree) {
    return kerf::subtet_rule(p, piece, degree);
  };
  const kerf::LinearMaterial material{4000.0, 0.45, 1060.0};
  const kerf::CutXfemModel model(mesh, material, pieces, enrichment, rule);
  REQUIRE(enrichment.num_enrichments() > 0);
  const Eigen::Vector3d g(0.0, 0.0, -9.81);
  Eigen::VectorXd e_g = Eigen::VectorXd::Zero(3 * model.num_dof_nodes());
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) e_g.segment<3>(3 * v) = g;

  // Round-off: the loads are sums of about 20 products per entry, so a relative 1e-13 of the
  // largest entry holds with room (measured below 2e-16).
  const auto relative = [](const Eigen::VectorXd& a, const Eigen::VectorXd& b) { return (a - b).norm() / b.norm(); };
  const Eigen::SparseMatrix<double> consistent = kerf::assemble_cut_xfem_mass(model, material.density, rule);
  CHECK(relative(consistent * e_g, model.gravity_load(material.density, g)) < 1e-13);
  for (const kerf::LumpingScheme scheme : {kerf::LumpingScheme::virtual_tet, kerf::LumpingScheme::row_sum, kerf::LumpingScheme::hrz}) {
    const Eigen::SparseMatrix<double> lumped = kerf::lump_cut_xfem_mass(model, material.density, scheme, rule);
    const Eigen::VectorXd f = kerf::lumped_gravity_load(model, material.density, g, scheme, rule);
    CHECK(relative(lumped * e_g, f) < 1e-13);
    // And the enrichment rows carry load (the shortcut is not trivially the standard rows only).
    CHECK(f.tail(3 * enrichment.num_enrichments()).norm() > 1e-3 * f.norm());
  }
}
