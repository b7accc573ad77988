#include "kerf/mesh/read_surface.hpp"

#include "kerf/app/input_error.hpp"
#include "kerf/mesh/check_triangle_surface.hpp"
#include "mesh/file_bytes.hpp"
#include "mesh/surface_parsers.hpp"

#include <cmath>
#include <sstream>

namespace kerf {

TriangleSurface surface_from_lists(const std::vector<std::array<double, 3>>& vertices,
                                   const std::vector<std::array<int, 3>>& triangles) {
  TriangleSurface surface;
  surface.vertices.resize(static_cast<Eigen::Index>(vertices.size()), 3);
  for (std::size_t v = 0; v < vertices.size(); ++v)
    for (std::size_t c = 0; c < 3; ++c) surface.vertices(static_cast<Eigen::Index>(v), static_cast<Eigen::Index>(c)) = vertices[v][c];
  surface.triangles.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (std::size_t a = 0; a < 3; ++a) surface.triangles(static_cast<Eigen::Index>(t), static_cast<Eigen::Index>(a)) = triangles[t][a];
  return surface;
}

TriangleSurface read_surface(const std::filesystem::path& file, double scale, std::ostream* warnings) {
  const std::string name = file.string();
  if (!(std::isfinite(scale) && scale > 0.0)) {
    std::ostringstream value;
    value << scale;
    throw InputError(name, "scale", "expected a finite number > 0, got " + value.str());
  }
  const std::string extension = lower_extension(file);
  TriangleSurface surface;
  if (extension == ".obj") {
    surface = parse_obj(file_bytes(file, name), name);
  } else if (extension == ".stl") {
    surface = parse_stl(file_bytes(file, name), name);
  } else if (extension == ".off") {
    surface = parse_off(file_bytes(file, name), name);
  } else if (extension == ".vtp" || extension == ".vtu" || extension == ".vtk") {
    surface = read_vtk_triangles(file, warnings);
  } else {
    throw InputError(name, "extension",
                     "'" + file.extension().string() +
                         "' is not a surface format Kerf reads; use .obj, .stl (ASCII or binary), .off, "
                         ".vtp (VTK XML polydata), .vtu (VTK XML) or .vtk (VTK legacy)");
  }
  surface.vertices *= scale;
  const SurfaceCheck check = check_triangle_surface(surface, name);
  if (warnings && check.flipped_triangles > 0)
    *warnings << "warning: " << name << ": " << check.flipped_triangles << " of " << surface.num_triangles()
              << " triangles flipped to agree in orientation with their neighbours (the first triangle of each of the "
              << check.components << " connected components keeps its own)\n";
  return surface;
}

} // namespace kerf
