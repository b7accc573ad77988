#include "kerf/io/write_surface_obj.hpp"

#include "kerf/app/input_error.hpp"

#include <cstdio>
#include <fstream>

namespace kerf {

void write_surface_obj(const std::filesystem::path& file, const TriangleSurface& surface) {
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
  std::ofstream out(file);
  if (!out) throw InputError(file.string(), "write", "cannot open the file for writing");
  char line[128];
  for (Eigen::Index v = 0; v < surface.num_vertices(); ++v) {
    std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", surface.vertices(v, 0), surface.vertices(v, 1), surface.vertices(v, 2));
    out << line;
  }
  for (Eigen::Index f = 0; f < surface.num_triangles(); ++f)
    out << "f " << surface.triangles(f, 0) + 1 << ' ' << surface.triangles(f, 1) + 1 << ' ' << surface.triangles(f, 2) + 1 << '\n';
  if (!out) throw InputError(file.string(), "write", "writing failed (disk full?)");
}

} // namespace kerf
