#include "kerf/cut/mesh_pieces.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace kerf {

namespace {

// A polygon of a tet's face that belongs to one piece.
struct FacePolygon {
  int piece = 0;
  bool covered = false;
  std::vector<Eigen::Vector3d> polygon;
};

// The polygons into which tet t's cells divide its face opposite corner a.
std::vector<FacePolygon> face_polygons(const TetMesh& mesh, const MeshPieces& pieces, Eigen::Index t, int a) {
  const int e = pieces.entry[static_cast<std::size_t>(t)];
  if (e < 0) {
    std::vector<Eigen::Vector3d> triangle;
    for (int k = 0; k < 4; ++k)
      if (k != a) triangle.push_back(mesh.nodes.row(mesh.tets(t, k)).transpose());
    return {{0, false, triangle}};
  }
  const TetPieces& tet = pieces.tets[static_cast<std::size_t>(e)];
  std::vector<FacePolygon> found;
  for (std::size_t c = 0; c < tet.cells.size(); ++c)
    for (const CellFace& face : tet.cells[c].faces)
      if (face.neighbour < 0 && face.origin.kind == FaceOrigin::Kind::tet_face && face.origin.index == a)
        found.push_back({tet.cell_piece[c], face.covered, face.polygon});
  return found;
}

// The area in which two convex polygons of one plane overlap: `a` clipped to the inner side of
// every edge of `b` (Sutherland-Hodgman in the plane).
double overlap_area(std::vector<Eigen::Vector3d> a, const std::vector<Eigen::Vector3d>& b) {
  const Eigen::Vector3d n = polygon_area_vector(b).normalized();
  for (std::size_t k = 0; k < b.size() && a.size() >= 3; ++k) {
    const Eigen::Vector3d& p = b[k];
    const Eigen::Vector3d& q = b[(k + 1) % b.size()];
    const auto inside = [&](const Eigen::Vector3d& x) { return (q - p).cross(x - p).dot(n); };
    std::vector<Eigen::Vector3d> kept;
    for (std::size_t i = 0; i < a.size(); ++i) {
      const Eigen::Vector3d& x = a[i];
      const Eigen::Vector3d& y = a[(i + 1) % a.size()];
      const double sx = inside(x), sy = inside(y);
      if (sx >= 0.0) kept.push_back(x);
      if ((sx > 0.0 && sy < 0.0) || (sx < 0.0 && sy > 0.0)) kept.push_back(x + sx / (sx - sy) * (y - x));
    }
    a = std::move(kept);
  }
  return a.size() < 3 ? 0.0 : polygon_area_vector(a).norm();
}

} // namespace

std::vector<PieceGlue> MeshPieces::glued_across(Eigen::Index t, int a) const {
  const int e = entry[static_cast<std::size_t>(t)];
  if (e >= 0) return glues[static_cast<std::size_t>(e)][static_cast<std::size_t>(a)];
  const int s = neighbours.across(t, a);
  if (s < 0) return {};
  const int f = entry[static_cast<std::size_t>(s)];
  if (f < 0) return {{0, 0}};
  // Seen from the other side: swap the pair.
  std::vector<PieceGlue> theirs = glues[static_cast<std::size_t>(f)][static_cast<std::size_t>(neighbours.across_face(t, a))];
  for (PieceGlue& g : theirs) std::swap(g.piece_a, g.piece_b);
  return theirs;
}

MeshPieces cut_mesh_into_pieces(const TetMesh& mesh, const CutSurfaces& cuts) {
  MeshPieces result;
  result.neighbours = tet_neighbours(mesh);
  const Eigen::Index T = mesh.num_tets();
  result.entry.assign(static_cast<std::size_t>(T), -1);
  result.tets_per_surface.assign(static_cast<std::size_t>(cuts.num_surfaces()), 0);
  std::vector<Eigen::Index> last_tet(static_cast<std::size_t>(cuts.num_surfaces()), -1);
  for (Eigen::Index t = 0; t < T; ++t) {
    const Eigen::Matrix<double, 4, 3> X = tet_corners(mesh, t);
    const std::vector<CutTriangle> triangles = cuts.triangles_meeting_tet(X);
    if (triangles.empty()) continue;
    for (const CutTriangle& triangle : triangles) {
      const auto s = static_cast<std::size_t>(triangle.surface);
      if (last_tet[s] != t) ++result.tets_per_surface[s];
      last_tet[s] = t;
    }
    result.entry[static_cast<std::size_t>(t)] = static_cast<int>(result.tets.size());
    result.entry_tet.push_back(static_cast<int>(t));
    result.tets.push_back(split_tet_by_triangles(X, triangles));
  }
  for (Eigen::Index t = 0; t < T; ++t) ++result.state_counts[static_cast<std::size_t>(result.state(t))];

  // Glue across every face of a tet with an entry. Two polygons of the shared face, one from
  // each side, join their pieces when neither is covered by the cut and they overlap in more
  // than round-off (1e-10 of the face's area: the two sides divide the face differently, as
  // each was split by the planes that cross its own tet, so polygons that only share an edge
  // overlap in an area of the order of round-off times the face's).
  result.glues.resize(result.tets.size());
  for (std::size_t e = 0; e < result.tets.size(); ++e) {
    const Eigen::Index t = result.entry_tet[e];
    for (int a = 0; a < 4; ++a) {
      const int s = result.neighbours.across(t, a);
      if (s < 0) continue;
      const std::vector<FacePolygon> mine = face_polygons(mesh, result, t, a);
      const std::vector<FacePolygon> theirs = face_polygons(mesh, result, s, result.neighbours.across_face(t, a));
      double face_area = 0.0;
      for (const FacePolygon& p : mine) face_area += polygon_area_vector(p.polygon).norm();
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
          // The neighbour walks the face the other way round: reverse its polygon so that both
          // run counter-clockwise about the same normal.
          std::vector<Eigen::Vector3d> q_same_way(q.polygon.rbegin(), q.polygon.rend());
          if (overlap_area(p.polygon, q_same_way) > 1e-10 * face_area) glued.push_back(pair);
        }
      }
    }
  }
  return result;
}

} // namespace kerf
