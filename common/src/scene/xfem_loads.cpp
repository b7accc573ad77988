#include "kerf/scene/xfem_loads.hpp"

#include <Eigen/Dense>

#include "kerf/app/input_error.hpp"
#include "kerf/cut/clip_tet.hpp"
#include "kerf/fem/assemble_loads.hpp"
#include "kerf/scene/scene_mesh.hpp"

#include <cmath>
#include <string>
#include <vector>

namespace kerf {

namespace {

/// The part of triangle `corners` where side * Lambda >= 0, Lambda linear with corner values
/// `lambda`: a convex polygon, walked around the triangle (empty if the side has no area).
std::vector<Eigen::Vector3d> clip_triangle(const std::array<Eigen::Vector3d, 3>& corners, const Eigen::Vector3d& lambda, int side) {
  std::vector<Eigen::Vector3d> polygon;
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3;
    if (side * lambda[a] >= 0.0) polygon.push_back(corners[static_cast<std::size_t>(a)]);
    if (lambda[a] * lambda[b] < 0.0) {
      const double s = lambda[a] / (lambda[a] - lambda[b]);
      polygon.push_back(corners[static_cast<std::size_t>(a)] + s * (corners[static_cast<std::size_t>(b)] - corners[static_cast<std::size_t>(a)]));
    }
  }
  return polygon;
}

/// Adds the enriched rows sum_side Psi_side,i * piece_load_i of tet t to f.
void add_enriched_rows(const XfemModel& model, Eigen::Index t, const Eigen::Matrix<double, 4, 3>& load_above,
                       const Eigen::Matrix<double, 4, 3>& load_below, Eigen::VectorXd& f) {
  const Eigen::Vector4d psi_above = model.psi(t, +1), psi_below = model.psi(t, -1);
  for (int a = 0; a < 4; ++a) {
    const int a_node = model.assembly_slots()(t, 4 + a);
    if (a_node < 0) continue;
    f.segment<3>(3 * a_node) += (psi_above[a] * load_above.row(a) + psi_below[a] * load_below.row(a)).transpose();
  }
}

} // namespace

Eigen::Vector4d piece_shape_integrals(const XfemModel& model, Eigen::Index t, int side) {
  const Enrichment& e = model.enrichment();
  const auto k = static_cast<std::size_t>(t);
  const TetSide tet_side = e.tet_side[k];
  if (tet_side != TetSide::cut) return Eigen::Vector4d::Constant(e.piece_fraction(t, side) * model.element_volume(t) / 4.0);
  Eigen::Vector4d integral = Eigen::Vector4d::Zero();
  for (const Eigen::Matrix<double, 4, 3>& sub : side > 0 ? e.pieces[k].above : e.pieces[k].below) {
    const Eigen::Vector3d centroid = sub.colwise().mean().transpose();
    integral += std::abs(signed_tet_volume(sub)) * model.shape_values(t, centroid);
  }
  return integral;
}

Eigen::VectorXd xfem_scene_loads(const Scene& scene, const XfemModel& model, const BoundaryFaces& boundary) {
  const TetMesh& mesh = model.mesh();
  const Enrichment& e = model.enrichment();
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * model.num_dof_nodes());
  f.head(3 * mesh.num_nodes()) = scene_external_loads(scene, mesh, boundary);

  // Gravity's enriched rows, piece by piece.
  const Eigen::Vector3d body_force = scene.material.density * scene.gravity;
  if (body_force.squaredNorm() > 0.0)
    for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
      if (!model.has_enriched_corner(t)) continue;
      add_enriched_rows(model, t, piece_shape_integrals(model, t, +1) * body_force.transpose(),
                        piece_shape_integrals(model, t, -1) * body_force.transpose(), f);
    }

  // Tractions' enriched rows: the same uniform t as chapter 1, over the pieces of each face.
  for (std::size_t i = 0; i < scene.traction.size(); ++i) {
    const std::string field = "traction[" + std::to_string(i) + "].region";
    std::vector<char> in_region(static_cast<std::size_t>(mesh.num_nodes()), 0);
    for (int v : scene_region_nodes(scene, mesh, scene.traction[i].region, field)) in_region[static_cast<std::size_t>(v)] = 1;
    const RegionFaces region = faces_in_region(mesh, boundary, in_region);
    if (region.area == 0.0) throw InputError(scene.source.string(), field, "no boundary face has all its nodes in the region");
    const Eigen::Vector3d traction = scene.traction[i].total_force / region.area;
    for (const Eigen::Index face : region.faces) {
      const Eigen::Index t = boundary.tet[static_cast<std::size_t>(face)];
      if (!model.has_enriched_corner(t)) continue;
      std::array<Eigen::Vector3d, 3> corners;
      Eigen::Vector3d lambda;
      for (int c = 0; c < 3; ++c) {
        corners[static_cast<std::size_t>(c)] = mesh.nodes.row(boundary.faces(face, c)).transpose();
        lambda[c] = e.level_set.lambda[boundary.faces(face, c)];
      }
      Eigen::Matrix<double, 4, 3> load[2] = {Eigen::Matrix<double, 4, 3>::Zero(), Eigen::Matrix<double, 4, 3>::Zero()};
      for (const int side : {+1, -1}) {
        std::vector<Eigen::Vector3d> polygon;
        const TetSide tet_side = e.tet_side[static_cast<std::size_t>(t)];
        if (tet_side == TetSide::cut)
          polygon = clip_triangle(corners, lambda, side);
        else if (e.piece_fraction(t, side) > 0.0)
          polygon.assign(corners.begin(), corners.end());
        // Fan triangles; Phi_i is linear, so its value at a triangle's centroid times the area is exact.
        for (std::size_t p = 1; p + 1 < polygon.size(); ++p) {
          const double piece_area = 0.5 * (polygon[p] - polygon[0]).cross(polygon[p + 1] - polygon[0]).norm();
          const Eigen::Vector3d centroid = (polygon[0] + polygon[p] + polygon[p + 1]) / 3.0;
          load[side > 0 ? 0 : 1] += piece_area * model.shape_values(t, centroid) * traction.transpose();
        }
      }
      add_enriched_rows(model, t, load[0], load[1], f);
    }
  }
  return f;
}

} // namespace kerf
