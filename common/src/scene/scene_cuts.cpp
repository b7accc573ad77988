#include "kerf/scene/scene_cuts.hpp"

#include "kerf/app/input_error.hpp"
#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/mesh/read_surface.hpp"

#include <stdexcept>
#include <string>

namespace kerf {

std::vector<TriangleSurface> scene_cut_surfaces(const Scene& scene, std::ostream* warnings) {
  std::vector<TriangleSurface> surfaces;
  for (std::size_t i = 0; i < scene.cuts.size(); ++i) {
    const CutSpec& spec = scene.cuts[i];
    if (!spec.is_rectangle) {
      surfaces.push_back(read_surface(spec.surface, spec.surface_scale, warnings));
      continue;
    }
    try {
      surfaces.push_back(rectangle_surface(RectangleCut(spec.origin, spec.edge1, spec.edge2)));
    } catch (const std::invalid_argument& error) {
      throw InputError(scene.source.string(), "cuts[" + std::to_string(i) + "].rectangle", error.what());
    }
  }
  return surfaces;
}

} // namespace kerf
