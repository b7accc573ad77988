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
  const bool cached = pieces.cell_planes.size() == pieces.cells.size();
  std::vector<Plane> planes;
  for (std::size_t c = 0; c < pieces.cells.size(); ++c) {
    if (!cached) planes = cell_face_planes(pieces.cells[c], snap);
    // The first face plane x lies beyond decides that it is outside the cell.
    const std::vector<Plane>& faces = cached ? pieces.cell_planes[c] : planes;
    const bool inside = std::none_of(faces.begin(), faces.end(), [&](const Plane& face) { return face.evaluate(x) > tolerance; });
    const int p = pieces.cell_piece[c];
    if (inside && std::find(found.begin(), found.end(), p) == found.end()) found.push_back(p);
  }
  std::sort(found.begin(), found.end());
  return found;
}

} // namespace kerf
