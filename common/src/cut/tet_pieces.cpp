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
      // The area vector once for both questions; the first face x is outside of decides.
      const Eigen::Vector3d area_vector = polygon_area_vector(face.polygon);
      if (!has_area(face, area_vector, snap)) continue;
      if (face_plane(face, area_vector, tolerance)(x) > 0.0) {
        inside = false;
        break;
      }
    }
    const int p = pieces.cell_piece[c];
    if (inside && std::find(found.begin(), found.end(), p) == found.end()) found.push_back(p);
  }
  std::sort(found.begin(), found.end());
  return found;
}

} // namespace kerf
