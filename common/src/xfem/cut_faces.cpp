#include "kerf/xfem/cut_faces.hpp"

#include <vector>

namespace kerf {

TriangleSurface cut_face_surface(const CutXfemModel& model, const Eigen::VectorXd& u) {
  const MeshPieces& pieces = model.pieces();
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;
  for (std::size_t e = 0; e < pieces.tets.size(); ++e) {
    const Eigen::Index t = pieces.entry_tet[e];
    if (!model.integrated_by_pieces(t)) continue;
    const TetPieces& tp = pieces.tets[e];
    for (int p = 0; p < tp.num_pieces(); ++p) {
      const Eigen::MatrixX3d w = model.phantom_displacements(u, t, p);
      const auto moved = [&](const Eigen::Vector3d& X) {
        Eigen::Vector3d value = w.transpose() * model.shape_values(t, X);
        for (const auto& [node, phi] : model.branch_values_at(t, p, X)) value += phi * u.segment<3>(3 * node);
        return Eigen::Vector3d(X + value);
      };
      for (const PieceBoundaryPolygon& polygon : tp.pieces[static_cast<std::size_t>(p)].boundary) {
        if (!polygon.on_cut || polygon.polygon.size() < 3) continue;
        const int first = static_cast<int>(vertices.size());
        for (const Eigen::Vector3d& X : polygon.polygon) vertices.push_back(moved(X));
        for (int c = 1; c + 1 < static_cast<int>(polygon.polygon.size()); ++c) triangles.emplace_back(first, first + c, first + c + 1);
      }
    }
  }
  TriangleSurface s;
  s.vertices.resize(static_cast<Eigen::Index>(vertices.size()), 3);
  for (std::size_t v = 0; v < vertices.size(); ++v) s.vertices.row(static_cast<Eigen::Index>(v)) = vertices[v].transpose();
  s.triangles.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  for (std::size_t f = 0; f < triangles.size(); ++f) s.triangles.row(static_cast<Eigen::Index>(f)) = triangles[f].transpose();
  return s;
}

} // namespace kerf
