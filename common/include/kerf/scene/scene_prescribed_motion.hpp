/// @file scene_prescribed_motion.hpp
/// @brief The scene's Dirichlet conditions as a motion in time: u, v and a of every prescribed node, derivatives of one function.
#pragma once

#include "kerf/dynamics/nonlinear_newmark.hpp"
#include "kerf/mesh/tet_mesh.hpp"
#include "kerf/scene/scene.hpp"

#include <Eigen/Core>

namespace kerf {

/// The quintic "smootherstep" s(tau) = 10 tau^3 - 15 tau^4 + 6 tau^5 on [0, 1] (0 before, 1 after),
/// with its first two derivatives: s, s' and s'' vanish at tau = 0 and s', s'' at tau = 1, so a
/// clamp driven along it starts and stops without a jump in velocity or acceleration (a jump
/// in a would be an impulse-like load on the body at the ramp's ends).
struct SmoothRamp {
  double s = 0.0, ds = 0.0, dds = 0.0; ///< s(tau), ds/dtau, d^2 s / dtau^2
};
SmoothRamp smooth_ramp(double tau);

/// Whether any Dirichlet entry of `scene` moves in time (has a ramp_time > 0).
bool scene_dirichlet_moves(const Scene& scene);

/// The scene's Dirichlet conditions at time t (s) on a body with `num_dof_nodes` DOF nodes, the
/// first #V of them the mesh's nodes (PrescribedMotion, 3 num_dof_nodes each; zero on the free
/// DOFs and on the enriched DOFs, which a clamp holds at 0). An entry with ramp_time T follows its quasi-static path
/// (scene_dirichlet_nodes at load factor lambda: the translation times lambda, the rotation by
/// lambda times its angle) with lambda = s(t / T), so that, by the chain rule,
///
///   u = p(lambda),   v = p'(lambda) s' / T,   a = p''(lambda) s'^2 / T^2 + p'(lambda) s'' / T^2,
///
/// p(lambda) = (Q(lambda theta) - I)(X - c) + lambda d,  p' = theta W Q (X - c) + d,  p'' = theta^2 W^2 Q (X - c)
/// (W the cross-product matrix of the unit axis, theta in radians). An entry without a ramp is
/// held at lambda = 1 from t = 0 on (v = a = 0). A node listed twice takes the later entry, as
/// make_dof_map does. Regions are checked as scene_region_nodes does.
PrescribedMotion scene_prescribed_motion(const Scene& scene, const TetMesh& mesh, Eigen::Index num_dof_nodes, double t);

} // namespace kerf
