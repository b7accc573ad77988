#include "kerf/cut/tet_pieces.hpp"

#include "cut/cell_face_planes.hpp"

#include <algorithm>

namespace kerf {

const char* to_string(SurfaceCutState state) {
  switch (state) {
  case SurfaceCutState::uncut: return "uncut";
  case SurfaceCutState::touched: return "touched";
  case SurfaceCutState::partially_cut: return "partially cut";
  case SurfaceCutState::completely_cut: return "completely cut";
  }
  return "unknown";
}

std::vector<int> pieces_containing(const TetPieces& pieces, const Eigen::Vector3d& x, double tolerance) {
  std::vector<int> found;
  const double snap = 1e-12 * pieces.diameter;
  for (std::size_t c = 0; c < pieces.cells.size(); ++c) {
    bool inside = true;
    for (const CellFace& face : pieces.cells[c].faces) {
      if (!has_area(face, snap)) continue;
      inside = inside && face_plane(face, tolerance)(x) <= 0.0;
    }
    const int p = pieces.cell_piece[c];
    if (inside && std::find(found.begin(), found.end(), p) == found.end()) found.push_back(p);
  }
  std::sort(found.begin(), found.end());
  return found;
}

} // namespace kerf
