/// @file liver_shape.hpp
/// @brief A liver of our own: an implicit surface written in code, two smooth lobes flattened underneath.
///
/// Chapter 7 cuts an organ, and we want one that needs no file: a smooth function phi(x) that is
/// negative inside the liver, zero on its surface and positive outside. It is the smooth union of
/// two ellipsoids, a large right lobe and a smaller, thinner left lobe, smoothly intersected with
/// the half-space above a floor plane, which makes the flat visceral (under) side. The result is
/// about 0.20 x 0.15 x 0.10 m, centred near the origin, z up. Units are metres throughout.
///
/// Smoothness matters because Mesh_3 puts its surface vertices on phi = 0: a min() or max() would
/// leave a crease along which the mesher must either refine without end or cut corners. We blend
/// with the log-sum-exp minimum, smooth to every order (liver_phi below).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <functional>

namespace kerf {

/// One lobe: an ellipsoid with its centre and semi-axes along x, y, z (m).
struct LiverLobe {
  Eigen::Vector3d centre;
  Eigen::Vector3d semi_axes;
};

/// The right lobe, the bulk of the organ: wide (0.15 m in x and y) and high.
inline const LiverLobe liver_right_lobe{{0.025, 0.0, 0.0}, {0.075, 0.075, 0.06}};
/// The left lobe: smaller, thinner, reaching left and a little forward (+y), lifted so that its
/// underside meets the floor only where it joins the right lobe.
inline const LiverLobe liver_left_lobe{{-0.05, 0.015, 0.01}, {0.05, 0.05, 0.035}};
/// Width of the blend between the lobes (m): the smooth union lies up to k ln 2 = 8 mm outside
/// both lobes where they meet, which fills the notch between them with a saddle.
inline constexpr double liver_lobe_blend = 0.012;
/// Height of the floor plane (m): below it is outside. It flattens the underside of the right lobe.
inline constexpr double liver_floor_height = -0.04;
/// Width of the blend with the floor (m): the rim where the floor meets the dome is rounded over
/// about this distance instead of a sharp edge.
inline constexpr double liver_floor_blend = 0.006;

/// The lobe's function: the smallest semi-axis times (|D^-1 (x - c)| - 1), D the semi-axes.
/// It is zero on the ellipsoid and grows like a distance in metres near it (exactly the distance
/// on a sphere). It is smooth except at the lobe's centre, which lies far inside the liver.
double liver_lobe_phi(const LiverLobe& lobe, const Eigen::Vector3d& x);

/// The smooth minimum -k log(exp(-a/k) + exp(-b/k)) (log-sum-exp): smooth to every order, below
/// min(a, b) by at most k ln 2 (where a = b), and equal to min(a, b) within k e^(-|a-b|/k) away from it.
double smooth_minimum(double a, double b, double k);

/// The liver's implicit function phi(x), negative inside (m, roughly a distance near the surface):
/// smooth_maximum(smooth_minimum(phi_right, phi_left, k_lobes), z_floor - z, k_floor), with
/// smooth_maximum(a, b, k) = -smooth_minimum(-a, -b, k).
double liver_phi(const Eigen::Vector3d& x);

/// A box that contains every point with phi < 0: each lobe's box grown by the most the lobe blend
/// can add (k ln 2 in phi, i.e. the semi-axes scaled by 1 + k ln 2 / smallest semi-axis), cut at the
/// floor. It is within a few millimetres of the shape's own extent (the test measures how close).
Eigen::AlignedBox3d liver_bounding_box();

/// The box of every point where smooth_minimum(phi_a, phi_b, blend) < 0 and z > floor: each
/// lobe's box grown by the most the blend can add, cut at the floor (liver_bounding_box's, and
/// the wedge's, whose other terms only take away).
Eigen::AlignedBox3d blended_lobes_box(const LiverLobe& a, const LiverLobe& b, double blend, double floor);

/// The centre of liver_bounding_box(); phi is negative there (the mesher starts its rays from it).
Eigen::Vector3d liver_centre();

/// A radius around liver_centre() that holds the whole liver with a margin: 1.1 times the half
/// diagonal of liver_bounding_box(), so that phi > 0 on the sphere (Mesh_3 requires it).
double liver_bounding_radius();

/// The liver's volume (m^3) by counting the midpoints with phi < 0 of a grid of cubes of side
/// `cell` over liver_bounding_box(). With the default 2 mm cells (half a million evaluations) it
/// is within 0.5 % of the exact volume (0.09 % measured against 1 mm cells); the mesher only needs
/// it to choose a size.
double liver_volume(double cell = 0.002);

/// The volume (m^3) of {phi < 0} inside `box` by the same count: the midpoints with phi < 0 of a
/// grid of cubes of side about `cell` over the box (liver_volume is the lobes' call of it).
/// @throws std::invalid_argument for cell <= 0
double implicit_volume(const std::function<double(const Eigen::Vector3d&)>& phi, const Eigen::AlignedBox3d& box, double cell);

} // namespace kerf
