// recut_mesh_into_pieces (cut/mesh_pieces.hpp): after a cut grows, only the tets near the added
// triangles are cut again. The claim is that the result IS cut_mesh_into_pieces's: the same
// entries, pieces, volumes, states, counts and glue, bit for bit, so every later step (enrichment,
// model) sees no difference. We grow a blade's sheet quad by quad (cut/cut_sheet.hpp) through a
// box mesh and compare after every quad, including quads that end on mesh nodes and faces.
#include "kerf/cut/cut_sheet.hpp"
#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/tet_neighbours.hpp"

#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <memory>
#include <vector>

namespace {

// Everything the two constructions must agree on, field by field.
void check_same_pieces(const kerf::MeshPieces& recut, const kerf::MeshPieces& full) {
  REQUIRE(recut.entry == full.entry);
  CHECK(recut.entry_tet == full.entry_tet);
  CHECK(recut.state_counts == full.state_counts);
  CHECK(recut.tets_per_surface == full.tets_per_surface);
  REQUIRE(recut.tets.size() == full.tets.size());
  for (std::size_t e = 0; e < full.tets.size(); ++e) {
    const kerf::TetPieces& a = recut.tets[e];
    const kerf::TetPieces& b = full.tets[e];
    CHECK(a.state == b.state);
    REQUIRE(a.num_pieces() == b.num_pieces());
    for (int p = 0; p < a.num_pieces(); ++p)
      CHECK(a.pieces[static_cast<std::size_t>(p)].volume == b.pieces[static_cast<std::size_t>(p)].volume);
    CHECK(a.triangles.size() == b.triangles.size());
    CHECK(a.corner_pieces == b.corner_pieces);
    for (int face = 0; face < 4; ++face) {
      const std::vector<kerf::PieceGlue>& ga = recut.glues[e][static_cast<std::size_t>(face)];
      const std::vector<kerf::PieceGlue>& gb = full.glues[e][static_cast<std::size_t>(face)];
      REQUIRE(ga.size() == gb.size());
      for (std::size_t g = 0; g < ga.size(); ++g) {
        CHECK(ga[g].piece_a == gb[g].piece_a);
        CHECK(ga[g].piece_b == gb[g].piece_b);
      }
    }
  }
}

} // namespace

TEST_CASE("recut_mesh_into_pieces equals cutting the whole mesh again, quad after quad") {
  // 4 x 4 x 4 cells of 0.25: the blade's edge is upright, from z = 1.2 down to z = 0.5 (a cut
  // half-way deep), in the plane y = 0.5 (a plane of mesh nodes and faces: the degenerate case)
  // or y = 0.37 (through the tets), and moves along -x by 0.125 per quad, so quads end on node
  // planes (x = 0.75, 0.5, ...) every other step.
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {4, 4, 4});
  const auto neighbours = std::make_shared<const kerf::TetNeighbours>(kerf::tet_neighbours(mesh));
  for (const double y : {0.37, 0.5}) {
    CAPTURE(y);
    kerf::CutSheet sheet(0.1);
    sheet.offer({{1.2, y, 1.2}, {1.2, y, 0.5}});
    kerf::MeshPieces previous = kerf::cut_mesh_into_pieces(mesh, kerf::CutSurfaces({}), neighbours);
    int split_tets = 0;
    for (int k = 1; k <= 9; ++k) {
      CAPTURE(k);
      const double x = 1.2 - 0.125 * k;
      const std::vector<kerf::SweptTriangle> added = sheet.offer({{x, y, 1.2}, {x, y, 0.5}});
      REQUIRE(added.size() == 2);
      Eigen::AlignedBox3d changed;
      for (const kerf::SweptTriangle& triangle : added)
        for (const Eigen::Vector3d& corner : triangle) changed.extend(corner);
      const kerf::CutSurfaces cuts({sheet.surface()});
      const kerf::MeshPieces recut = kerf::recut_mesh_into_pieces(mesh, cuts, previous, changed);
      const kerf::MeshPieces full = kerf::cut_mesh_into_pieces(mesh, cuts, neighbours);
      check_same_pieces(recut, full);
      split_tets = full.count(kerf::SurfaceCutState::completely_cut);
      previous = recut;
    }
    // The comparison must have had something to compare: the sheet splits tets (measured 48 at
    // y = 0.37; in the plane of faces y = 0.5 it splits none, and separates tets along faces).
    if (y == 0.37) CHECK(split_tets > 20);
  }
}

TEST_CASE("recut_mesh_into_pieces with nothing added keeps every piece, and refuses another mesh's pieces") {
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {3, 3, 3});
  kerf::CutSheet sheet(0.1);
  sheet.offer({{1.2, 0.4, 1.2}, {1.2, 0.4, 0.3}});
  sheet.offer({{0.3, 0.4, 1.2}, {0.3, 0.4, 0.3}});
  const kerf::CutSurfaces cuts({sheet.surface()});
  const kerf::MeshPieces full = kerf::cut_mesh_into_pieces(mesh, cuts);
  check_same_pieces(kerf::recut_mesh_into_pieces(mesh, cuts, full, Eigen::AlignedBox3d()), full);
  const kerf::TetMesh other = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {2, 2, 2});
  CHECK_THROWS_AS(kerf::recut_mesh_into_pieces(other, cuts, full, Eigen::AlignedBox3d()), std::invalid_argument);
}
