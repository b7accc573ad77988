#include "fuzz_inputs.hpp"

#include "kerf/app/input_error.hpp"
#include "kerf/mesh/check_triangle_surface.hpp"
#include "kerf/mesh/read_mesh.hpp"
#include "kerf/mesh/read_surface.hpp"
#include "kerf/scene/scene.hpp"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <system_error>

namespace kerf::fuzz {
namespace {

namespace fs = std::filesystem;

/// Throws BrokenPromise with `what` unless `promise` holds.
void require(bool promise, const std::string& what) {
  if (!promise) throw BrokenPromise(what);
}

/// The checks every accepted mesh must pass, whatever its reader (see check_tet_mesh.hpp).
void check_accepted_mesh(const TetMesh& mesh) {
  require(mesh.num_nodes() > 0, "an accepted mesh has no nodes");
  require(mesh.num_tets() > 0, "an accepted mesh has no tetrahedra");
  require(mesh.nodes_per_tet() == 4 || mesh.nodes_per_tet() == 10,
          "an accepted mesh has " + std::to_string(mesh.nodes_per_tet()) + " nodes per tet");
  require(mesh.nodes.allFinite(), "an accepted mesh has a coordinate that is not finite");
  require(mesh.tets.minCoeff() >= 0 && mesh.tets.maxCoeff() < mesh.num_nodes(),
          "an accepted mesh has a node index outside [0, #V)");
}

/// The checks every accepted cut surface must pass (see triangle_surface.hpp): indices in
/// range, finite coordinates, and a surface already welded and oriented, which a second pass
/// of the check leaves as it is.
void check_accepted_surface(const TriangleSurface& surface) {
  require(surface.num_triangles() > 0, "an accepted surface has no triangles");
  require(surface.vertices.allFinite(), "an accepted surface has a coordinate that is not finite");
  require(surface.triangles.minCoeff() >= 0 && surface.triangles.maxCoeff() < surface.num_vertices(),
          "an accepted surface has a vertex index outside [0, #V)");
  TriangleSurface again = surface;
  const SurfaceCheck check = check_triangle_surface(again, "fuzz");
  require(check.merged_vertices == 0 && check.unused_vertices == 0 && check.flipped_triangles == 0,
          "an accepted surface changes when it is checked again");
  require(again.vertices == surface.vertices && again.triangles == surface.triangles,
          "an accepted surface changes when it is checked again");
}

/// The checks every accepted scene must pass: the ranges of the book's scene reference.
void check_accepted_scene(const Scene& scene) {
  require(scene.mesh.order == 1 || scene.mesh.order == 2, "an accepted scene has mesh.order " +
                                                              std::to_string(scene.mesh.order));
  require((scene.mesh.box_cells.array() >= 1).all() &&
              (scene.mesh.box_cells.array() <= 100000).all(),
          "an accepted scene has mesh.box.cells outside [1, 100000]");
  require(scene.mesh.box_min.allFinite() && scene.mesh.box_max.allFinite() &&
              std::isfinite(scene.mesh.scale) && scene.mesh.scale > 0.0,
          "an accepted scene has a mesh box or scale that is not finite and positive");
  require(scene.material.young > 0.0 && scene.material.poisson > -1.0 &&
              scene.material.poisson < 0.5 && scene.material.density >= 0.0,
          "an accepted scene has a material out of range");
  require(scene.gravity.allFinite(), "an accepted scene has a gravity that is not finite");
  for (const DirichletSpec& spec : scene.dirichlet) {
    require(spec.displacement.allFinite() && spec.center.allFinite() &&
                std::isfinite(spec.degrees) && std::abs(spec.axis.norm() - 1.0) < 1e-9,
            "an accepted scene has a Dirichlet condition that is not finite");
    for (const int node : spec.region.node_list)
      require(node >= 0, "an accepted scene has a negative node index in a region");
  }
  for (const TractionSpec& spec : scene.traction) {
    require(spec.total_force.allFinite(), "an accepted scene has a traction that is not finite");
    for (const int node : spec.region.node_list)
      require(node >= 0, "an accepted scene has a negative node index in a region");
  }
  for (const CutSpec& cut : scene.cuts)
    require(std::isfinite(cut.surface_scale) && cut.surface_scale > 0.0,
            "an accepted scene has a cut surface scale that is not finite and positive");
  require(scene.output_every >= 1, "an accepted scene has output.every < 1");
  require(scene.quasi_static.load_steps >= 1 && scene.quasi_static.max_iterations >= 1,
          "an accepted scene has quasi_static counts below 1");
  require(scene.solver.max_iterations >= 1, "an accepted scene has solver.max_iterations < 1");
  require(scene.time.integrator == "static" || (scene.time.steps >= 1 && scene.time.dt > 0.0),
          "an accepted scene has a dynamic integrator without steps");
}

/// A scratch file that holds the input for the length of one call, then goes away.
class ScratchFile {
public:
  ScratchFile(const FuzzedReader& reader, std::string_view bytes)
      : path_(fs::temp_directory_path() /
              ("kerf-fuzz-" + std::to_string(::getpid()) + "-" + reader.name + reader.extension)) {
    std::ofstream out(path_, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out) throw std::runtime_error("cannot write the scratch file " + path_.string());
  }
  ~ScratchFile() {
    std::error_code ignored;
    fs::remove(path_, ignored);
  }
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;

  const fs::path& path() const { return path_; }

private:
  fs::path path_;
};

} // namespace

std::vector<FuzzedReader> fuzzed_readers() {
  return {{"gmsh", ".msh"},          {"vtk", ".vtk"},          {"vtu", ".vtu"},
          {"medit", ".mesh"},        {"scene", ".json"},       {"surface_obj", ".obj"},
          {"surface_stl", ".stl"},   {"surface_off", ".off"},  {"surface_vtk", ".vtk"}};
}

FuzzedReader fuzzed_reader(std::string_view name) {
  for (const FuzzedReader& reader : fuzzed_readers())
    if (reader.name == name) return reader;
  throw std::invalid_argument("no fuzzed reader is called '" + std::string(name) + "'");
}

Verdict feed_to_reader(const FuzzedReader& reader, std::string_view bytes) {
  try {
    if (reader.name == "scene") {
      check_accepted_scene(parse_scene(std::string(bytes), "fuzz.json", "."));
    } else if (reader.name.rfind("surface_", 0) == 0) {
      const ScratchFile file(reader, bytes);
      check_accepted_surface(read_surface(file.path(), 1.0, nullptr));
    } else {
      const ScratchFile file(reader, bytes);
      check_accepted_mesh(read_mesh(file.path(), nullptr));
    }
    return Verdict::accepted;
  } catch (const InputError&) {
    return Verdict::rejected;
  }
}

} // namespace kerf::fuzz
