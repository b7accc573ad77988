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

MeshPieces scene_mesh_pieces(const Scene& scene, const TetMesh& mesh, const CutSurfaces& cuts, std::ostream* warnings) {
  MeshPieces pieces = cut_mesh_into_pieces(mesh, cuts);
  for (int s = 0; s < cuts.num_surfaces(); ++s)
    if (warnings && pieces.tets_per_surface[static_cast<std::size_t>(s)] == 0)
      *warnings << "warning: " << scene.source.string() << ": cuts[" << s << "]: the surface does not meet the mesh; it cuts nothing\n";
  return pieces;
}

} // namespace kerf
