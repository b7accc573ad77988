#include "kerf/cut/mesh_pieces.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <stdexcept>
#include <cmath>
#include <limits>

namespace kerf {

namespace {

// A polygon of a tet's face that belongs to one piece (pointing into the tet's cells, or to
// the tet's own face for a tet without an entry).
struct FacePolygon {
  int piece = 0;
  bool covered = false;
  const std::vector<Eigen::Vector3d>* polygon = nullptr;
};

// The polygons into which tet t's cells divide its face opposite corner a, appended to `found`
// (cleared first). `whole` receives the face itself for a tet without an entry.
void face_polygons(const TetMesh& mesh, const MeshPieces& pieces, Eigen::Index t, int a, std::vector<Eigen::Vector3d>& whole,
                   std::vector<FacePolygon>& found) {
  found.clear();
  const int e = pieces.entry[static_cast<std::size_t>(t)];
  if (e < 0) {
    whole.clear();
    for (int k = 0; k < 4; ++k)
      if (k != a) whole.push_back(mesh.nodes.row(mesh.tets(t, k)).transpose());
    found.push_back({0, false, &whole});
    return;
  }
  const TetPieces& tet = pieces.tets[static_cast<std::size_t>(e)];
  for (std::size_t c = 0; c < tet.cells.size(); ++c)
    for (const CellFace& face : tet.cells[c].faces)
      if (face.neighbour < 0 && face.origin.kind == FaceOrigin::Kind::tet_face && face.origin.index == a)
        found.push_back({tet.cell_piece[c], face.covered, &face.polygon});
}

// The area in which two convex polygons of one plane overlap: `a` clipped to the inner side of
// every edge of `b` (Sutherland-Hodgman in the plane). `b` may run either way round: its own
// area vector says which side of its edges is inside. `work` and `kept` are scratch space,
// kept by the caller so that the many small clippings of a cut allocate nothing.
double overlap_area(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b, std::vector<Eigen::Vector3d>& work,
                    std::vector<Eigen::Vector3d>& kept) {
  const Eigen::Vector3d n = polygon_area_vector(b).normalized();
  work = a;
  for (std::size_t k = 0; k < b.size() && work.size() >= 3; ++k) {
    const Eigen::Vector3d& p = b[k];
    const Eigen::Vector3d& q = b[(k + 1) % b.size()];
    const auto inside = [&](const Eigen::Vector3d& x) { return (q - p).cross(x - p).dot(n); };
    kept.clear();
    for (std::size_t i = 0; i < work.size(); ++i) {
      const Eigen::Vector3d& x = work[i];
      const Eigen::Vector3d& y = work[(i + 1) % work.size()];
      const double sx = inside(x), sy = inside(y);
      if (sx >= 0.0) kept.push_back(x);
      if ((sx > 0.0 && sy < 0.0) || (sx < 0.0 && sy > 0.0)) kept.push_back(x + sx / (sx - sy) * (y - x));
    }
    std::swap(work, kept);
  }
  return work.size() < 3 ? 0.0 : polygon_area_vector(work).norm();
}

// Whether the line of one edge of convex polygon `a` has all of `b` on its outer side, up to
// `slack` (m): then a and b overlap at most in a strip of that width along the line. Either
// polygon may run either way round (a's own area vector tells inside from outside).
bool edge_separates(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b, double slack) {
  const Eigen::Vector3d n = polygon_area_vector(a).normalized();
  for (std::size_t k = 0; k < a.size(); ++k) {
    const Eigen::Vector3d& p = a[k];
    const Eigen::Vector3d inward = n.cross(a[(k + 1) % a.size()] - p).normalized();
    if (std::all_of(b.begin(), b.end(), [&](const Eigen::Vector3d& x) { return inward.dot(x - p) <= slack; })) return true;
  }
  return false;
}

// Whether two polygons have exactly the same corners (in any order).
bool same_corners(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b) {
  if (a.size() != b.size() || a.size() < 3) return false;
  return std::all_of(a.begin(), a.end(), [&](const Eigen::Vector3d& x) { return std::find(b.begin(), b.end(), x) != b.end(); });
}

} // namespace

std::vector<PieceGlue> MeshPieces::glued_across(Eigen::Index t, int a) const {
  const int e = entry[static_cast<std::size_t>(t)];
  if (e >= 0) return glues[static_cast<std::size_t>(e)][static_cast<std::size_t>(a)];
  const int s = neighbours->across(t, a);
  if (s < 0) return {};
  const int f = entry[static_cast<std::size_t>(s)];
  if (f < 0) return {{0, 0}};
  // Seen from the other side: swap the pair.
  std::vector<PieceGlue> theirs = glues[static_cast<std::size_t>(f)][static_cast<std::size_t>(neighbours->across_face(t, a))];
  for (PieceGlue& g : theirs) std::swap(g.piece_a, g.piece_b);
  return theirs;
}

MeshPieces cut_mesh_into_pieces(const TetMesh& mesh, const CutSurfaces& cuts) {
  return cut_mesh_into_pieces(mesh, cuts, std::make_shared<const TetNeighbours>(tet_neighbours(mesh)));
}

namespace {

// The pieces of every tet, from `pieces_of(t, X)` (nullptr: no cut triangle meets it; pieces a
// previous MeshPieces holds are shared with it, not copied), then the
// counts and the glue: the two steps of cut_mesh_into_pieces and recut_mesh_into_pieces. The
// glue across face a of tet t is `glue_of(t, a)`'s where that is not nullptr (the face's two
// tets kept their pieces), else found from the face's polygons.
template <class PiecesOf, class GlueOf>
MeshPieces pieces_and_glue(const TetMesh& mesh, const CutSurfaces& cuts, std::shared_ptr<const TetNeighbours> neighbours, PiecesOf pieces_of,
                           GlueOf glue_of);

// Whether two lists of cut triangles are the same triangles, in the same order: the same
// surface, number and corners (a tet split by the one list is split by the other alike).
bool same_triangles(const std::vector<CutTriangle>& a, const std::vector<CutTriangle>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (a[k].surface != b[k].surface || a[k].triangle != b[k].triangle || a[k].corners != b[k].corners) return false;
  return true;
}

// No glue known beforehand.
const std::vector<PieceGlue>* no_glue(Eigen::Index, int) { return nullptr; }

} // namespace

MeshPieces cut_mesh_into_pieces(const TetMesh& mesh, const CutSurfaces& cuts, std::shared_ptr<const TetNeighbours> neighbours) {
  MeshPieces result = pieces_and_glue(mesh, cuts, std::move(neighbours), [&](Eigen::Index, const Eigen::Matrix<double, 4, 3>& X) -> std::shared_ptr<const TetPieces> {
    const std::vector<CutTriangle> triangles = cuts.triangles_meeting_tet(X);
    if (triangles.empty()) return nullptr;
    return std::make_shared<const TetPieces>(split_tet_by_triangles(X, triangles));
  }, no_glue);
  result.kept_from_previous.assign(static_cast<std::size_t>(mesh.num_tets()), 0);
  return result;
}

MeshPieces recut_mesh_into_pieces(const TetMesh& mesh, const CutSurfaces& cuts, const MeshPieces& previous, const Eigen::AlignedBox3d& changed) {
  if (previous.entry.size() != static_cast<std::size_t>(mesh.num_tets()))
    throw std::invalid_argument("recut_mesh_into_pieces: the previous pieces are of another mesh");
  // The box a little larger than asked: a triangle's box and a tet's are compared in doubles,
  // and a triangle that touches a tet only at a corner must not be missed by round-off.
  Eigen::AlignedBox3d grown = changed;
  if (!grown.isEmpty()) {
    const double margin = 1e-9 * std::max(1.0, grown.diagonal().norm());
    grown.min().array() -= margin;
    grown.max().array() += margin;
  }
  std::vector<unsigned char> kept(static_cast<std::size_t>(mesh.num_tets()), 0);
  const auto previous_pieces = [&](int e) { return e < 0 ? nullptr : previous.tets.share(static_cast<std::size_t>(e)); };
  MeshPieces result = pieces_and_glue(mesh, cuts, previous.neighbours, [&](Eigen::Index t, const Eigen::Matrix<double, 4, 3>& X) -> std::shared_ptr<const TetPieces> {
    const Eigen::AlignedBox3d box(X.colwise().minCoeff().transpose(), X.colwise().maxCoeff().transpose());
    if (!box.intersects(grown)) {
      kept[static_cast<std::size_t>(t)] = 1;
      return previous_pieces(previous.entry[static_cast<std::size_t>(t)]);
    }
    // In the box, the tet may meet an added triangle; if it meets the triangles it met before and
    // no other (most tets there: the box of a sweep is wide), its pieces are still the previous.
    const std::vector<CutTriangle> triangles = cuts.triangles_meeting_tet(X);
    const int e = previous.entry[static_cast<std::size_t>(t)];
    if (e < 0 ? triangles.empty() : same_triangles(previous.tets[static_cast<std::size_t>(e)].triangles, triangles)) {
      kept[static_cast<std::size_t>(t)] = 1;
      return previous_pieces(e);
    }
    if (triangles.empty()) return nullptr;
    return std::make_shared<const TetPieces>(split_tet_by_triangles(X, triangles));
  }, [&](Eigen::Index t, int a) -> const std::vector<PieceGlue>* {
    // Both tets of the face kept their pieces: so does the face, and its glue is the previous one.
    const int s = previous.neighbours->across(t, a);
    const int e = previous.entry[static_cast<std::size_t>(t)];
    if (e < 0 || !kept[static_cast<std::size_t>(t)] || !kept[static_cast<std::size_t>(s)]) return nullptr;
    return &previous.glues[static_cast<std::size_t>(e)][static_cast<std::size_t>(a)];
  });
  result.kept_from_previous = std::move(kept);
  return result;
}

namespace {

template <class PiecesOf, class GlueOf>
MeshPieces pieces_and_glue(const TetMesh& mesh, const CutSurfaces& cuts, std::shared_ptr<const TetNeighbours> neighbours, PiecesOf pieces_of,
                           GlueOf glue_of) {
  MeshPieces result;
  result.neighbours = std::move(neighbours);
  const Eigen::Index T = mesh.num_tets();
  result.entry.assign(static_cast<std::size_t>(T), -1);
  result.tets_per_surface.assign(static_cast<std::size_t>(cuts.num_surfaces()), 0);
  std::vector<Eigen::Index> last_tet(static_cast<std::size_t>(cuts.num_surfaces()), -1);
  for (Eigen::Index t = 0; t < T; ++t) {
    const Eigen::Matrix<double, 4, 3> X = tet_corners(mesh, t);
    std::shared_ptr<const TetPieces> split = pieces_of(t, X);
    if (!split) continue;
    for (const CutTriangle& triangle : split->triangles) {
      const auto s = static_cast<std::size_t>(triangle.surface);
      if (last_tet[s] != t) ++result.tets_per_surface[s];
      last_tet[s] = t;
    }
    result.entry[static_cast<std::size_t>(t)] = static_cast<int>(result.tets.size());
    result.entry_tet.push_back(static_cast<int>(t));
    result.tets.push_back(std::move(split));
  }
  for (Eigen::Index t = 0; t < T; ++t) ++result.state_counts[static_cast<std::size_t>(result.state(t))];

  // Glue across every face of a tet with an entry. Two polygons of the shared face, one from
  // each side, join their pieces when neither is covered by the cut and they overlap in more
  // than round-off (1e-10 of the face's area: the two sides divide the face differently, as
  // each was split by the planes that cross its own tet, so polygons that only share an edge
  // overlap in an area of the order of round-off times the face's).
  result.glues.resize(result.tets.size());
  std::vector<FacePolygon> mine, theirs;
  std::vector<Eigen::Vector3d> my_face, their_face, work, kept;
  for (std::size_t e = 0; e < result.tets.size(); ++e) {
    const Eigen::Index t = result.entry_tet[e];
    for (int a = 0; a < 4; ++a) {
      const int s = result.neighbours->across(t, a);
      if (s < 0) continue;
      if (const std::vector<PieceGlue>* known = glue_of(t, a)) {
        result.glues[e][static_cast<std::size_t>(a)] = *known;
        continue;
      }
      face_polygons(mesh, result, t, a, my_face, mine);
      face_polygons(mesh, result, s, result.neighbours->across_face(t, a), their_face, theirs);
      double face_area = 0.0;
      for (const FacePolygon& p : mine) face_area += polygon_area_vector(*p.polygon).norm();
      // Two polygons an edge line separates to within `slack` overlap at most in a strip of that
      // width across the face, of area below 1e-11 of the face's: under the 1e-10 asked below.
      double diameter = 0.0;
      for (const FacePolygon& p : mine)
        for (const Eigen::Vector3d& x : *p.polygon) diameter = std::max(diameter, (x - mine.front().polygon->front()).norm());
      const double slack = 1e-11 * face_area / std::max(2.0 * diameter, std::numeric_limits<double>::min());
      std::vector<PieceGlue>& glued = result.glues[e][static_cast<std::size_t>(a)];
      for (const FacePolygon& p : mine) {
        if (p.covered) continue;
        for (const FacePolygon& q : theirs) {
          if (q.covered) continue;
          const PieceGlue pair{p.piece, q.piece};
          const bool known = std::any_of(glued.begin(), glued.end(), [&](const PieceGlue& g) {
            return g.piece_a == pair.piece_a && g.piece_b == pair.piece_b;
          });
          if (known) continue;
          // Most faces are divided alike on both sides (the same planes crossed both tets, and a
          // crossing on a shared edge is bitwise the same double from either side): the same
          // corners, walked the other way round, overlap in the whole polygon; polygons on the two sides of
          // a line across the face are told apart by that line. Otherwise clip; the neighbour
          // walks the face the other way round, and overlap_area reads the inside of q's edges
          // from q's own orientation, so no reversed copy is needed.
          if (same_corners(*p.polygon, *q.polygon)) {
            // The overlap is the polygon itself; the same threshold as for a clipped overlap.
            if (polygon_area_vector(*p.polygon).norm() > 1e-10 * face_area) glued.push_back(pair);
            continue;
          }
          if (edge_separates(*p.polygon, *q.polygon, slack) || edge_separates(*q.polygon, *p.polygon, slack)) continue;
          if (overlap_area(*p.polygon, *q.polygon, work, kept) > 1e-10 * face_area) glued.push_back(pair);
        }
      }
    }
  }
  return result;
}

} // namespace

} // namespace kerf
