/// @file implicit_surface_mesh.hpp
/// @brief A fine, closed triangle surface of phi(x) = 0, oriented outward: the surface a picture shows.
///
/// Chapter 7 draws the liver with a surface several times finer than its tet mesh's boundary
/// (Gutierrez section 3.2, Koschier section 7: the visual mesh is embedded in the simulation
/// mesh and moved with it), so that the picture shows the organ's smooth shape, not the tets'
/// facets. We make it with the same mesher as the tets (mesh_implicit_domain.hpp): Mesh_3 with a
/// fine facet size and no bound on the cells' size, of which we keep only the boundary. This
/// reuses the tested, seeded mesher (the same surface every call) and needs no second CGAL
/// package; the few tets it makes inside are thrown away.
#pragma once

#include "kerf/mesh/triangle_surface.hpp"

#include <Eigen/Core>
#include <functional>

namespace kerf {

/// Mesh_3's surface bounds from one target size h (m): facet_size = h (the radius of a
/// triangle's surface Delaunay ball, so edges are about h long), facet_distance = h / 10 (how far
/// a triangle's circumcentre may lie from phi = 0: the chord error on a curve of radius R is about
/// h^2 / (8 R), below h / 10 wherever R > 1.25 h), facet_angle = 30 degrees (the largest bound
/// Mesh_3 promises to reach: the smoothest shading).
struct ImplicitSurfaceSizing {
  double facet_size = 0.004;
  double facet_distance = 0.0004;
  double facet_angle = 30.0;
};

/// The sizing for a target edge length h: {h, h / 10, 30}.
ImplicitSurfaceSizing implicit_surface_sizing(double h);

/// The closed surface phi = 0 of the region phi(x) < 0, as triangles oriented outward
/// ((x1 - x0) x (x2 - x0) points to phi > 0).
///
/// Every vertex lies on phi = 0 up to Mesh_3's bisection, 1e-6 of the bounding sphere's
/// diameter (mesh_implicit_domain.cpp); every edge is shared by exactly two triangles that
/// traverse it in opposite directions (the boundary of a set of tets; the test checks that it
/// is a manifold on the liver and the sphere). Vertices are numbered in the order the triangles
/// first use them. The same surface every call (Mesh_3's generators are seeded).
///
/// @param phi             the implicit function, negative inside, positive on the bounding sphere
/// @param centre          the centre of the bounding sphere, a point with phi < 0 (m)
/// @param bounding_radius the radius of a sphere around centre that contains the region (m)
/// @param sizing          the surface bounds
/// @throws std::invalid_argument, std::runtime_error as mesh_implicit_domain does
TriangleSurface implicit_surface_mesh(const std::function<double(const Eigen::Vector3d&)>& phi, const Eigen::Vector3d& centre,
                                      double bounding_radius, const ImplicitSurfaceSizing& sizing);

} // namespace kerf
