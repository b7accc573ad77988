/// @file scene_cuts.hpp
/// @brief The scene's cuts as triangle surfaces: rectangles as two triangles, surface files read and checked.
#pragma once

#include "kerf/mesh/triangle_surface.hpp"
#include "kerf/scene/scene.hpp"

#include <ostream>
#include <vector>

namespace kerf {

/// Every entry of the scene's "cuts", in order: a rectangle becomes the two triangles of
/// rectangle_surface() (a bad rectangle is an InputError naming "cuts[i].rectangle"), a surface
/// is read by read_surface() with its scale (a bad file is an InputError naming that file and
/// what is wrong in it; its warnings, such as merged vertices, go to `warnings`).
std::vector<TriangleSurface> scene_cut_surfaces(const Scene& scene, std::ostream* warnings);

} // namespace kerf
