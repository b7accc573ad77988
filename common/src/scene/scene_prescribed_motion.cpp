#include "kerf/scene/scene_prescribed_motion.hpp"

#include "kerf/scene/displacement_file.hpp"
#include "kerf/scene/scene_mesh.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <stdexcept>
#include <string>

namespace kerf {

SmoothRamp smooth_ramp(double tau) {
  if (tau <= 0.0) return {0.0, 0.0, 0.0};
  if (tau >= 1.0) return {1.0, 0.0, 0.0};
  const double t2 = tau * tau;
  return {t2 * tau * (10.0 - 15.0 * tau + 6.0 * t2), 30.0 * t2 * (1.0 - tau) * (1.0 - tau), 60.0 * tau * (1.0 - tau) * (1.0 - 2.0 * tau)};
}

bool scene_dirichlet_moves(const Scene& scene) {
  return std::any_of(scene.dirichlet.begin(), scene.dirichlet.end(), [](const DirichletSpec& d) { return d.ramp_time > 0.0; });
}

PrescribedMotion scene_prescribed_motion(const Scene& scene, const TetMesh& mesh, Eigen::Index num_dof_nodes, double t) {
  PrescribedMotion motion{Eigen::VectorXd::Zero(3 * num_dof_nodes), Eigen::VectorXd::Zero(3 * num_dof_nodes),
                          Eigen::VectorXd::Zero(3 * num_dof_nodes)};
  for (std::size_t i = 0; i < scene.dirichlet.size(); ++i) {
    const DirichletSpec& spec = scene.dirichlet[i];
    if (spec.williams)
      throw std::logic_error("scene_prescribed_motion: dirichlet[" + std::to_string(i) +
                             "] is Williams's field, which chapter 5's static program alone prescribes");
    const std::vector<int> nodes = scene_region_nodes(scene, mesh, spec.region, "dirichlet[" + std::to_string(i) + "].region");
    // lambda(t) and its time derivatives.
    double lambda = 1.0, dlambda = 0.0, ddlambda = 0.0;
    if (spec.ramp_time > 0.0) {
      const SmoothRamp ramp = smooth_ramp(t / spec.ramp_time);
      lambda = ramp.s;
      dlambda = ramp.ds / spec.ramp_time;
      ddlambda = ramp.dds / (spec.ramp_time * spec.ramp_time);
    }
    const double theta = spec.has_rotation ? spec.degrees * 3.14159265358979323846 / 180.0 : 0.0;
    Eigen::Matrix3d W;
    W << 0.0, -spec.axis.z(), spec.axis.y(), spec.axis.z(), 0.0, -spec.axis.x(), -spec.axis.y(), spec.axis.x(), 0.0;
    const Eigen::Matrix3d Q = Eigen::AngleAxisd(lambda * theta, spec.axis).toRotationMatrix();
    if (spec.from_file) {
      // The file's values scaled by lambda(t): u = lambda u_file, v = lambda' u_file, a = lambda'' u_file.
      const std::vector<Eigen::Vector3d> values =
          displacements_from_file(spec.file, mesh, nodes, "dirichlet[" + std::to_string(i) + "] of " + scene.source.string());
      for (std::size_t k = 0; k < nodes.size(); ++k) {
        motion.u.segment<3>(3 * nodes[k]) = lambda * values[k];
        motion.v.segment<3>(3 * nodes[k]) = dlambda * values[k];
        motion.a.segment<3>(3 * nodes[k]) = ddlambda * values[k];
      }
      continue;
    }
    for (const int node : nodes) {
      const Eigen::Vector3d r = mesh.nodes.row(node).transpose() - spec.center;
      const Eigen::Vector3d p = (Q - Eigen::Matrix3d::Identity()) * r + lambda * spec.displacement;
      const Eigen::Vector3d dp = theta * (W * (Q * r)) + spec.displacement;
      const Eigen::Vector3d ddp = theta * theta * (W * (W * (Q * r)));
      motion.u.segment<3>(3 * node) = p;
      motion.v.segment<3>(3 * node) = dp * dlambda;
      motion.a.segment<3>(3 * node) = ddp * dlambda * dlambda + dp * ddlambda;
    }
  }
  return motion;
}

} // namespace kerf
