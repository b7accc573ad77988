#include "kerf/mesh/tet_quality.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace kerf {

namespace {

/// The four faces' area-weighted outward normals (face opposite corner a in row a), for a tet of
/// either orientation: each normal is flipped, if needed, to point away from its opposite corner.
Eigen::Matrix<double, 4, 3> outward_face_normals(const Eigen::Matrix<double, 4, 3>& X) {
  Eigen::Matrix<double, 4, 3> N;
  for (int a = 0; a < 4; ++a) {
    const int* f = tet_outward_face_corners[a];
    const Eigen::Vector3d x0 = X.row(f[0]), x1 = X.row(f[1]), x2 = X.row(f[2]);
    Eigen::Vector3d n = 0.5 * (x1 - x0).cross(x2 - x0);
    if (n.dot(Eigen::Vector3d(X.row(a)) - x0) > 0.0) n = -n;
    N.row(a) = n.transpose();
  }
  return N;
}

} // namespace

double tet_min_dihedral_angle(const Eigen::Matrix<double, 4, 3>& X) {
  const Eigen::Matrix<double, 4, 3> N = outward_face_normals(X);
  double smallest = 180.0;
  for (int a = 0; a < 4; ++a)
    for (int b = a + 1; b < 4; ++b) {
      const double na = N.row(a).norm(), nb = N.row(b).norm();
      if (na == 0.0 || nb == 0.0) return 0.0;
      const double cos_normals = std::clamp(N.row(a).dot(N.row(b)) / (na * nb), -1.0, 1.0);
      smallest = std::min(smallest, 180.0 - std::acos(cos_normals) * 180.0 / std::numbers::pi);
    }
  return smallest;
}

double tet_radius_ratio(const Eigen::Matrix<double, 4, 3>& X) {
  const Eigen::Vector3d a = (X.row(1) - X.row(0)).transpose();
  const Eigen::Vector3d b = (X.row(2) - X.row(0)).transpose();
  const Eigen::Vector3d c = (X.row(3) - X.row(0)).transpose();
  const double six_volume = a.dot(b.cross(c));
  if (!(six_volume > 0.0)) return 0.0;
  const double area = outward_face_normals(X).rowwise().norm().sum();
  const double r_inscribed = 0.5 * six_volume / area; // 3 V / area
  const Eigen::Vector3d to_circumcentre =
      (a.squaredNorm() * b.cross(c) + b.squaredNorm() * c.cross(a) + c.squaredNorm() * a.cross(b)) / (2.0 * six_volume);
  return 3.0 * r_inscribed / to_circumcentre.norm();
}

TetQualitySummary tet_quality_summary(const TetMesh& mesh, double dihedral_threshold, double radius_ratio_threshold) {
  if (mesh.num_tets() == 0) throw std::invalid_argument("tet_quality_summary: the mesh has no tets");
  TetQualitySummary s;
  s.min_dihedral_angle = 180.0;
  s.min_radius_ratio = 1.0;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const Eigen::Matrix<double, 4, 3> X = tet_corners(mesh, t);
    const double angle = tet_min_dihedral_angle(X), ratio = tet_radius_ratio(X);
    s.min_dihedral_angle = std::min(s.min_dihedral_angle, angle);
    s.min_radius_ratio = std::min(s.min_radius_ratio, ratio);
    s.mean_min_dihedral_angle += angle;
    s.mean_radius_ratio += ratio;
    if (angle < dihedral_threshold) ++s.below_dihedral_threshold;
    if (ratio < radius_ratio_threshold) ++s.below_radius_ratio_threshold;
  }
  s.mean_min_dihedral_angle /= static_cast<double>(mesh.num_tets());
  s.mean_radius_ratio /= static_cast<double>(mesh.num_tets());
  return s;
}

} // namespace kerf
