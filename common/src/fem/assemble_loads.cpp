#include "kerf/fem/assemble_loads.hpp"

#include "kerf/fem/positive_jacobian.hpp"
#include "kerf/fem/tet_loads.hpp"
#include "kerf/mesh/check_tet_mesh.hpp"

namespace kerf {

Eigen::VectorXd assemble_gravity(const TetMesh& mesh, double density, const Eigen::Vector3d& gravity) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * mesh.num_nodes());
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const double volume = signed_tet_volume(mesh, t);
    require_positive_jacobian(6.0 * volume, "assemble_gravity", t);
    const Eigen::VectorXd s = tet_shape_integrals(mesh.nodes_per_tet(), volume);
    for (int a = 0; a < mesh.nodes_per_tet(); ++a) f.segment<3>(3 * mesh.tets(t, a)) += density * s[a] * gravity;
  }
  return f;
}

RegionFaces faces_in_region(const TetMesh& mesh, const BoundaryFaces& boundary, const std::vector<char>& in_region) {
  RegionFaces region;
  for (Eigen::Index face = 0; face < boundary.faces.rows(); ++face) {
    bool inside = true;
    for (int c = 0; c < boundary.faces.cols(); ++c) inside = inside && in_region[static_cast<std::size_t>(boundary.faces(face, c))];
    if (!inside) continue;
    region.faces.push_back(face);
    region.area += face_area(mesh, boundary, face);
  }
  return region;
}

double add_uniform_traction(const TetMesh& mesh, const BoundaryFaces& boundary, const std::vector<char>& in_region,
                            const Eigen::Vector3d& total_force, Eigen::VectorXd& f) {
  const RegionFaces region = faces_in_region(mesh, boundary, in_region);
  if (region.area == 0.0) return 0.0;
  const Eigen::Vector3d traction = total_force / region.area;
  for (Eigen::Index face : region.faces) {
    const Eigen::VectorXd s = face_shape_integrals(static_cast<int>(boundary.faces.cols()), face_area(mesh, boundary, face));
    for (int c = 0; c < boundary.faces.cols(); ++c) f.segment<3>(3 * boundary.faces(face, c)) += s[c] * traction;
  }
  return region.area;
}

} // namespace kerf
