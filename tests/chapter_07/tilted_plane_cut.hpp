// The cut that tests/chapter_07's checks of the cut's walls and of its opening share: a tilted
// plane through the unit box, and the field that moves each side away from it by d along its
// normal (chapter 4's u_i and a_k), whose walls and jump are known in closed form.
#pragma once

#include "kerf/cut/rectangle_cut.hpp"

#include "support/cut_body.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace tilted_cut {

// The plane z = 0.43 + 0.17 (x - 0.5), as a rectangle far beyond the box, its normal up-ish.
// In the box it runs from z = 0.345 (x = 0) to z = 0.515 (x = 1), between the nodes' layers
// (multiples of 0.25 in the 4 x 4 x 4 box, 0.3875 and 0.4725 at x = 0.25 and 0.75): it crosses
// every column of tets and passes through no node. Inside the box it is a rectangle 1 m wide
// in y and sqrt(1 + 0.17^2) m long in x: that area.
inline const Eigen::Vector3d plane_point(0.5, 0.5, 0.43);
inline constexpr double plane_slope = 0.17;
inline double area_in_box() { return std::sqrt(1.0 + plane_slope * plane_slope); }

// The rectangle: 3 m by 3 m about the box, two triangles, most of them outside it.
inline kerf::TriangleSurface tilted_plane() {
  const Eigen::Vector3d along_x(3.0, 0.0, 3.0 * plane_slope);
  const Eigen::Vector3d corner = plane_point - 0.5 * along_x - Eigen::Vector3d(0.0, 1.5, 0.0);
  return kerf::rectangle_surface(kerf::RectangleCut(corner, along_x, Eigen::Vector3d(0.0, 3.0, 0.0)));
}

inline Eigen::Vector3d plane_normal() { return Eigen::Vector3d(-plane_slope, 0.0, 1.0).normalized(); }

// Signed distance of x from the plane (m), positive above (the side the normal points to).
inline double height(const Eigen::Vector3d& x) { return (x - plane_point).dot(plane_normal()); }

// Each side moved by d along the normal away from the plane: u_i its home side's value, a_k the
// other side's minus it (one enrichment per node the plane separates from the far side).
inline Eigen::VectorXd separated_sides(const support::CutBody& body, double d) {
  const Eigen::Index N = body.mesh.num_nodes();
  Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * body.model.num_dof_nodes());
  for (Eigen::Index i = 0; i < N; ++i) {
    const Eigen::Vector3d side = (height(body.mesh.nodes.row(i).transpose()) > 0.0 ? d : -d) * plane_normal();
    u.segment<3>(3 * i) = side;
    for (int k = body.enrichment.first_enrichment[static_cast<std::size_t>(i)]; k < body.enrichment.first_enrichment[static_cast<std::size_t>(i) + 1]; ++k)
      u.segment<3>(3 * (N + k)) = -2.0 * side;
  }
  return u;
}

} // namespace tilted_cut
