#include "kerf/cut/height_field_surface.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace kerf {

TriangleSurface height_field_surface(const HeightField& h, double z_c, const Eigen::Vector2d& min, const Eigen::Vector2d& max,
                                     const Eigen::Vector2i& cells) {
  if (!h) throw std::invalid_argument("height_field_surface: the height function is empty");
  if ((cells.array() < 1).any()) throw std::invalid_argument("height_field_surface: every cell count must be at least 1");
  if (!((max - min).minCoeff() > 0.0)) throw std::invalid_argument("height_field_surface: max must exceed min in x and y");
  if (!std::isfinite(z_c)) throw std::invalid_argument("height_field_surface: z_c must be finite");
  const int nx = cells[0], ny = cells[1];
  const auto vertex = [&](int i, int j) { return i + (nx + 1) * j; };

  TriangleSurface surface;
  surface.vertices.resize(static_cast<Eigen::Index>(nx + 1) * (ny + 1), 3);
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      // The same expression as make_box_mesh(), so that a box mesh's layer has these x and y.
      const double x = min[0] + double(i) / nx * (max[0] - min[0]);
      const double y = min[1] + double(j) / ny * (max[1] - min[1]);
      const double height = h(x, y);
      if (!std::isfinite(height)) {
        std::ostringstream message;
        message << "height_field_surface: h(" << x << ", " << y << ") = " << height << " is not finite";
        throw std::invalid_argument(message.str());
      }
      surface.vertices.row(vertex(i, j)) << x, y, z_c + height;
    }

  surface.triangles.resize(2 * static_cast<Eigen::Index>(nx) * ny, 3);
  Eigen::Index f = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      surface.triangles.row(f++) << vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1);
      surface.triangles.row(f++) << vertex(i, j), vertex(i + 1, j + 1), vertex(i, j + 1);
    }
  return surface;
}

} // namespace kerf
