#include "kerf/cut/convex_cell.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <utility>

namespace kerf {

ConvexCell tet_cell(const Eigen::Matrix<double, 4, 3>& X) {
  // Face f is opposite corner f. Its corners are the other three, ordered so that seen from
  // outside (from the side away from corner f) they run counter-clockwise.
  ConvexCell cell;
  for (int f = 0; f < 4; ++f) {
    std::vector<Eigen::Vector3d> polygon;
    for (int k = 0; k < 4; ++k)
      if (k != f) polygon.push_back(X.row(k).transpose());
    const Eigen::Vector3d n = (polygon[1] - polygon[0]).cross(polygon[2] - polygon[0]);
    if (n.dot(X.row(f).transpose() - polygon[0]) > 0.0) std::swap(polygon[1], polygon[2]);
    cell.faces.push_back({polygon, -1, {FaceOrigin::Kind::tet_face, f}, false, 0});
  }
  return cell;
}

void order_convex_polygon(std::vector<Eigen::Vector3d>& corners, const Eigen::Vector3d& normal) {
  if (corners.size() < 3) return;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& x : corners) centre += x;
  centre /= static_cast<double>(corners.size());
  // Two directions spanning the plane, (u, v, n) right-handed: angles about n increase
  // counter-clockwise seen from the side n points to.
  const Eigen::Vector3d n = normal.normalized();
  const Eigen::Vector3d u = n.unitOrthogonal();
  const Eigen::Vector3d v = n.cross(u);
  std::vector<std::pair<double, Eigen::Vector3d>> by_angle;
  by_angle.reserve(corners.size());
  for (const Eigen::Vector3d& x : corners) {
    const Eigen::Vector3d d = x - centre;
    by_angle.emplace_back(std::atan2(d.dot(v), d.dot(u)), x);
  }
  std::sort(by_angle.begin(), by_angle.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (std::size_t k = 0; k < corners.size(); ++k) corners[k] = by_angle[k].second;
}

Eigen::Vector3d polygon_area_vector(const std::vector<Eigen::Vector3d>& polygon) {
  // Relative to the first corner, to keep the round-off of far-away coordinates out.
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
    sum += (polygon[k] - polygon[0]).cross(polygon[k + 1] - polygon[0]);
  return 0.5 * sum;
}

double convex_cell_volume(const ConvexCell& cell) {
  // Relative to a corner of the cell (the divergence theorem holds about any origin), for the
  // same reason as above.
  if (cell.faces.empty()) return 0.0;
  const Eigen::Vector3d origin = cell.faces.front().polygon.front();
  double sum = 0.0;
  for (const CellFace& face : cell.faces) sum += (face.polygon.front() - origin).dot(polygon_area_vector(face.polygon));
  return sum / 3.0;
}

Eigen::Vector3d convex_cell_inner_point(const ConvexCell& cell) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int count = 0;
  for (const CellFace& face : cell.faces)
    for (const Eigen::Vector3d& y : face.polygon) sum += y, ++count;
  return count > 0 ? Eigen::Vector3d(sum / count) : sum;
}

std::vector<Eigen::Matrix<double, 4, 3>> convex_cell_tetrahedra(const ConvexCell& cell) {
  std::vector<Eigen::Matrix<double, 4, 3>> tets;
  if (cell.faces.empty()) return tets;
  const Eigen::Vector3d apex = cell.faces.front().polygon.front();
  for (const CellFace& face : cell.faces) {
    // A face through the apex adds nothing: its fan tets would be flat.
    if (std::find(face.polygon.begin(), face.polygon.end(), apex) != face.polygon.end()) continue;
    for (std::size_t k = 1; k + 1 < face.polygon.size(); ++k) {
      // The face runs counter-clockwise seen from outside, so its normal
      // n = (p_k - p0) x (p_k+1 - p0) points away from the apex, and (apex, p0, p_k, p_k+1)
      // is positively oriented: det[p0 - apex, p_k - apex, p_k+1 - apex] = (p0 - apex) . n > 0.
      Eigen::Matrix<double, 4, 3> T;
      T.row(0) = apex.transpose();
      T.row(1) = face.polygon[0].transpose();
      T.row(2) = face.polygon[k].transpose();
      T.row(3) = face.polygon[k + 1].transpose();
      tets.push_back(T);
    }
  }
  return tets;
}

} // namespace kerf
