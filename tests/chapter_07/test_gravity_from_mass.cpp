// Chapter 7 rebuilds its system at every change of topology and takes the gravity load as
// M e_g, the mass times a unit translation along g (u = g at every node, every enrichment 0),
// instead of a second pass over every piece's rule. That is the definition of the loads that go
// with each mass (dynamics/lumped_mass.hpp: "each phantom node pulled by its own mass"; for the
// consistent mass rho int N^T g, CutXfemModel::gravity_load). The first test checks the identity
// against the library's own functions on a cut body, so that the shortcut cannot drift from them.
// It cannot tell where a lumped mass puts a piece's weight: the second test weighs every piece of
// the default lumped mass against its exact mass and first moment from the cut geometry.
#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/dynamics/lumped_mass.hpp"
#include "kerf/fem/linear_material.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"
#include "kerf/quadrature/polyhedron_moments.hpp"
#include "kerf/quadrature/gauss_piece_rules.hpp"
#include "kerf/xfem/cut_xfem_mass.hpp"
#include "kerf/scene/scene_dynamic_mass.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"
#include "kerf/xfem/surface_enrichment.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace {

// The beam of both tests and the slanted rectangle that ends inside it: split tets, pieces of
// all shapes, and tets the front passes through (integrated whole, no enrichment).
kerf::TriangleSurface slanted_cut() {
  kerf::TriangleSurface cut;
  cut.vertices = Eigen::MatrixX3d{{-0.01, -0.01, 0.07}, {0.04, -0.01, 0.09}, {0.04, 0.045, 0.11}, {-0.01, 0.045, 0.09}};
  cut.triangles = Eigen::MatrixX3i{{0, 1, 2}, {0, 2, 3}};
  return cut;
}

kerf::PieceQuadratureRule subtets(const Eigen::Matrix<double, 4, 3>&, const kerf::TetPieces& p, int piece, int degree) {
  return kerf::subtet_rule(p, piece, degree);
}

// The tets of `mesh`, each with nodes of its own: no tet shares a node, so the phantom nodes of
// a tet's pieces are DOF nodes no other tet touches, and the lumped mass's entries on them are
// that tet's pieces' alone.
kerf::TetMesh with_own_nodes(const kerf::TetMesh& mesh) {
  kerf::TetMesh apart;
  apart.nodes.resize(mesh.num_tets() * mesh.nodes_per_tet(), 3);
  apart.tets.resize(mesh.num_tets(), mesh.nodes_per_tet());
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    for (int a = 0; a < mesh.nodes_per_tet(); ++a) {
      const auto v = static_cast<int>(t * mesh.nodes_per_tet() + a);
      apart.nodes.row(v) = mesh.nodes.row(mesh.tets(t, a));
      apart.tets(t, a) = v;
    }
  return apart;
}

// The scheme a scene's "lumped" names: chapter 7's default.
kerf::LumpingScheme scene_default_lumping() {
  kerf::Scene scene;
  scene.time.mass = "lumped";
  return *kerf::scene_lumping_scheme(scene);
}

} // namespace

TEST_CASE("the gravity load of every mass is that mass times a unit translation along g") {
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {0.03, 0.06, 0.2}, {3, 6, 10});
  const kerf::CutSurfaces cuts({slanted_cut()});
  const kerf::MeshPieces pieces = kerf::cut_mesh_into_pieces(mesh, cuts);
  const kerf::SurfaceEnrichment enrichment = kerf::make_surface_enrichment(mesh, pieces);
  const kerf::PieceRuleFunction rule = subtets;
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
  for (const kerf::LumpingScheme scheme :
       {scene_default_lumping(), kerf::LumpingScheme::virtual_tet, kerf::LumpingScheme::row_sum, kerf::LumpingScheme::hrz}) {
    const Eigen::SparseMatrix<double> lumped = kerf::lump_cut_xfem_mass(model, material.density, scheme, rule);
    const Eigen::VectorXd f = kerf::lumped_gravity_load(model, material.density, g, scheme, rule);
    CHECK(relative(lumped * e_g, f) < 1e-13);
    // And the enrichment rows carry load (the shortcut is not trivially the standard rows only).
    CHECK(f.tail(3 * enrichment.num_enrichments()).norm() > 1e-3 * f.norm());
  }
}

TEST_CASE("the default lumped mass gives every piece of a cut tet its exact mass and first moment, on Tet4 and Tet10") {
  // The lumped mass is diagonal in the phantom unknowns: piece p of tet t gets D_p,a at its
  // phantom node a (lumped_mass.hpp), which sits at the tet's node X_a. The piece's lumped mass
  // is sum_a D_p,a, its first moment sum_a D_p,a X_a: its weight acts at their ratio. Both are
  // compared with rho V_p and rho int_p x, integrated exactly over the piece's boundary polygons
  // (divergence theorem, polyhedron_moments.hpp), which never sees a shape function or a rule.
  //
  // Reading D_p,a off the assembled matrix: with every tet on nodes of its own, a tet cut in two
  // has at node a (DOF node i) one piece at home (phantom node i) and the other enriched (DOF
  // node k), and M_kk = D_other,a, M_ii = D_home,a + D_other,a.
  const kerf::LumpingScheme lumped = scene_default_lumping();
  const kerf::LinearMaterial material{4000.0, 0.45, 1060.0};
  const double rho = material.density;
  const kerf::TetMesh tet4 = with_own_nodes(kerf::make_box_mesh({0, 0, 0}, {0.03, 0.06, 0.2}, {3, 6, 10}));
  for (const kerf::TetMesh& mesh : {tet4, kerf::tet10_from_tet4(tet4)}) {
    const int n = mesh.nodes_per_tet();
    CAPTURE(n);
    const kerf::CutSurfaces cuts({slanted_cut()});
    const kerf::MeshPieces pieces = kerf::cut_mesh_into_pieces(mesh, cuts);
    const kerf::SurfaceEnrichment enrichment = kerf::make_surface_enrichment(mesh, pieces);
    const kerf::CutXfemModel model(mesh, material, pieces, enrichment, subtets);
    // The worst error over the pieces, of the mass over rho V_t and of the first moment over
    // rho V_t h_t (V_t the tet's volume, h_t its longest edge), and the smallest D_p,a over rho V_t.
    const auto weigh = [&](kerf::LumpingScheme scheme, double& mass_error, double& moment_error, double& smallest) {
      const Eigen::SparseMatrix<double> M = kerf::lump_cut_xfem_mass(model, rho, scheme, subtets);
      mass_error = moment_error = 0.0;
      smallest = 1.0;
      int weighed = 0;
      for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
        if (pieces.num_pieces(t) != 2) continue; // whole tets, and the front's tets: one piece each
        const kerf::TetPieces& cut = pieces.tets[static_cast<std::size_t>(pieces.entry[static_cast<std::size_t>(t)])];
        for (int p = 0; p < 2; ++p) {
          double mass = 0.0;
          Eigen::Vector3d moment = Eigen::Vector3d::Zero();
          for (int a = 0; a < n; ++a) {
            const int i = mesh.tets(t, a), k = model.phantom_node(t, p, a), other = model.phantom_node(t, 1 - p, a);
            REQUIRE((k == i) != (other == i)); // one piece at home, the other enriched
            const double D = k == i ? M.coeff(3 * i, 3 * i) - M.coeff(3 * other, 3 * other) : M.coeff(3 * k, 3 * k);
            mass += D;
            moment += D * mesh.nodes.row(i).transpose();
            smallest = std::min(smallest, D / (rho * cut.volume));
          }
          std::vector<std::vector<Eigen::Vector3d>> boundary;
          for (const kerf::PieceBoundaryPolygon& polygon : cut.pieces[static_cast<std::size_t>(p)].boundary) boundary.push_back(polygon.polygon);
          const Eigen::VectorXd exact = kerf::polyhedron_monomial_moments(boundary, 1); // V, int x, int y, int z
          mass_error = std::max(mass_error, std::abs(mass - rho * exact[0]) / (rho * cut.volume));
          moment_error = std::max(moment_error, (moment - rho * exact.tail<3>()).norm() / (rho * cut.volume * cut.diameter));
          ++weighed;
        }
      }
      return weighed;
    };
    double mass_error = 0.0, moment_error = 0.0, smallest = 0.0;
    const int weighed = weigh(lumped, mass_error, moment_error, smallest);
    MESSAGE("lumped: " << weighed << " pieces, mass error " << mass_error << ", first moment error " << moment_error
                       << ", smallest D / rho V_t " << smallest);
    CHECK(weighed > 100); // measured 154: the 77 tets the rectangle crosses whole
    // Sums of 4 or 10 products of integrals exact to round-off: measured 2e-15 (mass) and 9e-15
    // (first moment); the pieces include slivers of 1e-8 of their tet, which stay positive.
    CHECK(mass_error < 1e-12);
    CHECK(moment_error < 1e-12);
    CHECK(smallest > 0.0);
    // The virtual tet, the default before, weighs each piece right and puts the weight at its
    // tet's centroid: its first moments are off by a good part of the tet (measured 0.078 of
    // rho V_t h_t), which is what the check above sees.
    weigh(kerf::LumpingScheme::virtual_tet, mass_error, moment_error, smallest);
    MESSAGE("virtual_tet: mass error " << mass_error << ", first moment error " << moment_error);
    CHECK(mass_error < 1e-12);
    CHECK(moment_error > 0.05);
  }
}
