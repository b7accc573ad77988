// Cutting a whole mesh by triangle-mesh cuts (cut/mesh_pieces.hpp) and enriching its nodes on
// the one-ring (xfem/surface_enrichment.hpp): the same nodes as chapter 3 for a cut clean
// through, none at a front inside the mesh, two enrichments for a node that two cuts reach, a
// cut lying in mesh faces, and piece volumes that add up to every tet's.
#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"
#include "kerf/xfem/enrichment.hpp"
#include "kerf/xfem/surface_enrichment.hpp"

#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <set>
#include <vector>

namespace {

// The plane z = height as a rectangle reaching `reach` beyond the box [0, 1]^3 on every side
// in x and y, or ending at x = x_end.
kerf::RectangleCut horizontal_cut(double height, double x_end = 2.0) {
  return kerf::RectangleCut({-1.0, -1.0, height}, {x_end + 1.0, 0.0, 0.0}, {0.0, 3.0, 0.0});
}

std::set<int> enriched_nodes(const kerf::SurfaceEnrichment& e) {
  std::set<int> nodes(e.enrichment_node.begin(), e.enrichment_node.end());
  return nodes;
}

} // namespace

TEST_CASE("a plane cut clean through enriches the nodes chapter 3 enriches, once each") {
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {3, 3, 4});
  const kerf::RectangleCut cut = horizontal_cut(0.37);
  const kerf::Enrichment chapter3 = kerf::make_enrichment(mesh, cut);
  const kerf::CutSurfaces surfaces({kerf::rectangle_surface(cut)});
  const kerf::MeshPieces pieces = kerf::cut_mesh_into_pieces(mesh, surfaces);
  const kerf::SurfaceEnrichment enrichment = kerf::make_surface_enrichment(mesh, pieces);
  CHECK(pieces.count(kerf::SurfaceCutState::completely_cut) == chapter3.cut_tets);
  const std::set<int> expected(chapter3.enriched_nodes.begin(), chapter3.enriched_nodes.end());
  CHECK(enriched_nodes(enrichment) == expected);
  CHECK(enrichment.num_enrichments() == static_cast<Eigen::Index>(expected.size()));
  CHECK(enrichment.most_enrichments == 1);
  // Every piece is on the side of chapter 3's level set that its enrichment says: for a node
  // below (home below), psi = 1 exactly on pieces above.
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const int e = pieces.entry[static_cast<std::size_t>(t)];
    double volume = 0.0;
    for (int p = 0; p < pieces.num_pieces(t); ++p) {
      if (e >= 0) volume += pieces.tets[static_cast<std::size_t>(e)].pieces[static_cast<std::size_t>(p)].volume;
      for (int a = 0; a < 4; ++a) {
        const int node = mesh.tets(t, a);
        const int k = enrichment.active_enrichment(pieces, t, a, p);
        if (enrichment.enrichments_of(node) == 0) {
          CHECK(k == -1);
          continue;
        }
        // A point of the piece: the mean of its first cell's first face.
        Eigen::Vector3d x = mesh.nodes.row(mesh.tets(t, 0)).transpose();
        if (e >= 0) {
          const kerf::TetPieces& tp = pieces.tets[static_cast<std::size_t>(e)];
          const kerf::ConvexCell& cell = tp.cells[static_cast<std::size_t>(tp.pieces[static_cast<std::size_t>(p)].cells[0])];
          x.setZero();
          int count = 0;
          for (const kerf::CellFace& f : cell.faces)
            for (const Eigen::Vector3d& y : f.polygon) x += y, ++count;
          x /= count;
        } else {
          x = (mesh.nodes.row(mesh.tets(t, 0)) + mesh.nodes.row(mesh.tets(t, 1)) + mesh.nodes.row(mesh.tets(t, 2)) +
               mesh.nodes.row(mesh.tets(t, 3))).transpose() / 4.0;
        }
        const bool piece_above = x.z() > 0.37;
        const bool node_above = mesh.nodes(node, 2) > 0.37;
        CHECK((k >= 0) == (piece_above != node_above));
      }
    }
    if (e >= 0) CHECK(std::abs(volume - pieces.tets[static_cast<std::size_t>(e)].volume) <= 1e-15);
  }
}

TEST_CASE("a cut that ends inside the mesh enriches no node whose support its front crosses") {
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {4, 2, 4});
  const kerf::CutSurfaces surfaces({kerf::rectangle_surface(horizontal_cut(0.37, 0.6))});
  const kerf::MeshPieces pieces = kerf::cut_mesh_into_pieces(mesh, surfaces);
  const kerf::SurfaceEnrichment enrichment = kerf::make_surface_enrichment(mesh, pieces);
  CHECK(pieces.count(kerf::SurfaceCutState::partially_cut) > 0);
  CHECK(enrichment.num_enrichments() > 0);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    if (pieces.state(t) != kerf::SurfaceCutState::partially_cut) continue;
    for (int a = 0; a < 4; ++a) CHECK(enrichment.enrichments_of(mesh.tets(t, a)) == 0);
  }
  // Every enriched node lies where the cut is: its support must be crossed completely, so the
  // node is at most at the front x = 0.6 (here no node between 0.5 and 0.6 exists: cells of 0.25).
  for (const int i : enriched_nodes(enrichment)) CHECK(mesh.nodes(i, 0) <= 0.6);
}

TEST_CASE("a node that two cuts reach gets two enrichments") {
  // Cells of 0.5: the nodes of the middle layer z = 0.5 have supports z in [0, 1], which both
  // cuts z = 0.4 and z = 0.6 cross: three parts, two enrichments. The nodes at z = 0 and z = 1
  // see one cut each.
  for (const int order : {1, 2}) {
    CAPTURE(order);
    kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {2, 2, 2});
    if (order == 2) mesh = kerf::tet10_from_tet4(mesh);
    const kerf::CutSurfaces surfaces({kerf::rectangle_surface(horizontal_cut(0.4)), kerf::rectangle_surface(horizontal_cut(0.6))});
    const kerf::MeshPieces pieces = kerf::cut_mesh_into_pieces(mesh, surfaces);
    const kerf::SurfaceEnrichment enrichment = kerf::make_surface_enrichment(mesh, pieces);
    CHECK(enrichment.most_enrichments == 2);
    for (Eigen::Index i = 0; i < mesh.num_nodes(); ++i) {
      CAPTURE(mesh.nodes.row(i));
      // Corners and Tet10 mid-edge nodes alike: a node on the layer z = 0.5 (for a mid-edge
      // node, on a horizontal edge of it, whose tets lie in both cell layers) has a support
      // spanning z in [0, 1]; every other node's support is one cell layer, which one cut crosses.
      const int expected = std::abs(mesh.nodes(i, 2) - 0.5) < 1e-12 ? 2 : 1;
      CHECK(enrichment.enrichments_of(i) == expected);
    }
  }
}

TEST_CASE("a cut lying exactly in mesh faces separates the tets on either side") {
  // The plane z = 0.5 is a node layer of the mesh: no tet is cut, the tets along it are touched,
  // and exactly the nodes of the layer get one enrichment (their supports fall in two parts).
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {2, 2, 4});
  const kerf::CutSurfaces surfaces({kerf::rectangle_surface(horizontal_cut(0.5))});
  const kerf::MeshPieces pieces = kerf::cut_mesh_into_pieces(mesh, surfaces);
  const kerf::SurfaceEnrichment enrichment = kerf::make_surface_enrichment(mesh, pieces);
  CHECK(pieces.count(kerf::SurfaceCutState::completely_cut) == 0);
  CHECK(pieces.count(kerf::SurfaceCutState::touched) > 0);
  for (Eigen::Index i = 0; i < mesh.num_nodes(); ++i)
    CHECK(enrichment.enrichments_of(i) == (std::abs(mesh.nodes(i, 2) - 0.5) < 1e-12 ? 1 : 0));
}
