/// @file liver_wedge.hpp
/// @brief A liver a surgeon would recognise: the two lobes of liver_shape.hpp made into a wedge,
///        with the sharp inferior border where the domed upper surface meets the visceral one.
///
/// Seen from the front a liver is a wedge: thick and rounded on the right, thinning to the left
/// lobe's tip. Its upper (diaphragmatic) surface is a dome; its under (visceral) surface faces down,
/// back and to the left; the two meet at the front in the inferior border, a sharp edge, notched
/// where the falciform ligament runs between the lobes. Chapter 7's liver (liver_shape.hpp) is the
/// dome alone, flattened underneath, so that it reads as a rounded blob.
///
/// We build the wedge from the same pieces (smooth minima and maxima of ellipsoids and planes, so
/// that Mesh_3 finds no crease to refine without end):
///
///   phi = smax( smax( smin(phi_right, phi_left, k_lobes), phi_visceral, k_border ),
///               z_floor - z, k_floor ),  then  smax(phi, -phi_notch, k_notch),
///
/// with smin the log-sum-exp minimum of liver_shape.hpp, smax(a, b, k) = -smin(-a, -b, k), phi_right
/// and phi_left two ellipsoids (liver_lobe_phi), phi_visceral the signed distance to a plane that
/// rises to the front and to the left (the visceral surface: below it is outside), the floor the
/// flat back of the right lobe where it lies on the kidney and is held, and phi_notch a thin
/// ellipsoid across the border between the lobes. The border's blend k_border is 2 mm: sharp at the
/// scale of a frame, round at the scale of a tet of the finest mesh Kerf makes of it. x points to
/// the patient's left (so that, seen from the front, the right lobe is on the viewer's left, as in
/// an atlas), y backwards, z up; metres.
#pragma once

#include "kerf/mesh/liver_shape.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace kerf {

/// The dome's right lobe: the bulk, tallest at the back (0.17 m wide, 0.16 deep, 0.11 high).
inline const LiverLobe liver_wedge_right_lobe{{-0.03, 0.012, -0.035}, {0.085, 0.08, 0.105}};
/// The dome's left lobe: long and flat, reaching the tip at x = 0.13 m.
inline const LiverLobe liver_wedge_left_lobe{{0.05, 0.005, -0.005}, {0.08, 0.065, 0.045}};

/// The visceral plane z = z0 + rise_front (y0 - y) + rise_left (x - x0): z0 at (x0, y0), rising to
/// the front and to the left (m and dimensionless slopes); below it is outside.
struct LiverVisceralPlane {
  double z0 = -0.045, x0 = -0.08, y0 = 0.06;
  double rise_front = 0.38, rise_left = 0.13;
};
inline constexpr LiverVisceralPlane liver_visceral_plane{};

/// The notch in the inferior border between the lobes: an ellipsoid, thin in x, across the border.
inline const LiverLobe liver_wedge_notch{{0.025, -0.078, 0.01}, {0.011, 0.03, 0.06}};

/// Blend widths (m): between the lobes, at the inferior border (sharp), at the floor, at the notch.
inline constexpr double liver_wedge_lobe_blend = 0.012;
inline constexpr double liver_wedge_border_blend = 0.002;
inline constexpr double liver_wedge_floor_blend = 0.006;
inline constexpr double liver_wedge_notch_blend = 0.004;
/// The floor (m): the flat back of the right lobe, below which is outside.
inline constexpr double liver_wedge_floor_height = -0.045;

/// The wedge liver's implicit function (the file's comment): negative inside, about a distance in
/// metres near the surface.
double liver_wedge_phi(const Eigen::Vector3d& x);

/// A box that holds every point with liver_wedge_phi < 0: the lobes' boxes grown by the most the
/// lobe blend can add, cut at the floor (the plane and the notch only take away).
Eigen::AlignedBox3d liver_wedge_bounding_box();

} // namespace kerf
