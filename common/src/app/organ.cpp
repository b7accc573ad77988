#include "kerf/app/organ.hpp"

#include "kerf/app/input_error.hpp"
#include "kerf/mesh/implicit_surface_mesh.hpp"
#include "kerf/mesh/liver_mesh.hpp"
#include "kerf/mesh/read_surface.hpp"
#include "kerf/mesh/tet_quality.hpp"
#include "kerf/scene/scene_mesh.hpp"

#include <chrono>
#include <cmath>
#include <iostream>
#include <sstream>

namespace kerf {

Organ::Organ(Scene& scene, std::optional<int> tets, std::ostream* warnings) {
  if (tets) {
    if (!scene.mesh.is_liver) throw InputError("command line", "--tets", "only for a scene whose mesh is the \"liver\"");
    if (*tets < liver_min_tets || *tets > liver_max_tets)
      throw InputError("command line", "--tets",
                       "expected a number of tets in [" + std::to_string(liver_min_tets) + ", " + std::to_string(liver_max_tets) + "]");
    scene.mesh.liver_tets = *tets;
  }
  const auto start = std::chrono::steady_clock::now();
  mesh = make_scene_mesh(scene, warnings);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  boundary = boundary_faces(mesh);
  neighbours = std::make_shared<const TetNeighbours>(tet_neighbours(mesh));
  locator = std::make_unique<PointLocator>(mesh);
  held = scene_held_nodes(scene, mesh, warnings);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const Eigen::Matrix<double, 4, 3> X = tet_corners(mesh, t);
    volume += std::abs((X.row(1) - X.row(0)).dot((X.row(2) - X.row(0)).cross(X.row(3) - X.row(0)))) / 6.0;
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) mean_edge += (X.row(a) - X.row(b)).norm();
  }
  mean_edge /= 6.0 * static_cast<double>(mesh.num_tets());
  const TetQualitySummary quality = tet_quality_summary(mesh);
  std::ostringstream line;
  line.precision(3);
  line << "mesh: " << mesh.num_nodes() << " nodes, " << mesh.num_tets() << (mesh.order() == 1 ? " Tet4" : " Tet10")
       << (scene.mesh.is_liver ? " (Mesh_3, " : " (read, ") << seconds << " s); quality: min dihedral angle " << quality.min_dihedral_angle
       << " deg, min radius ratio " << quality.min_radius_ratio << "; model " << scene.model;
  summary = line.str();
}

void require_blade_scene(const Scene& scene, const std::string& program, const std::string& step, bool interactive) {
  const std::string file = scene.source.string();
  if (!scene.cuts.empty())
    throw InputError(file, "cuts", program + "'s cuts are made by the \"blade\"; a fixed cut is chapter 6's (06_newmark)");
  if (scene.time.integrator != "newmark") throw InputError(file, "time.integrator", program + " steps with \"newmark\" (" + step + ")");
  if (!(scene.material.density > 0.0)) throw InputError(file, "material.density", "dynamics needs a positive density (kg/m^3)");
  if (!scene.blade.given && !interactive)
    throw InputError(file, "blade", "expected a \"blade\" field with its \"path\": " + program + " cuts with it");
}

TriangleSurface scene_visual_surface(const Scene& scene, const TetMesh& mesh) {
  if (!scene.render.surface.empty()) return read_surface(scene.render.surface, scene.render.surface_scale, &std::cerr);
  if (scene.mesh.is_liver) {
    const LiverDomain liver = liver_domain(scene.mesh.liver_shape);
    return implicit_surface_mesh(liver.phi, liver.centre, liver.radius, implicit_surface_sizing(scene.render.visual_size));
  }
  return boundary_surface(mesh);
}

} // namespace kerf
