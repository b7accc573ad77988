/* Kerf, chapter 7 study: the visual surface. A smooth surface of the
   liver several times finer than its tet mesh's boundary, embedded in the tets, so that the
   picture shows the organ and not the tets' facets (Gutierrez section 3.2, Koschier section 7).

   Build:   cmake --preset release && cmake --build --preset release --target 07_visual_surface_study

   Sample runs:
     07_visual_surface_study --quick --out output/visual_surface_study_quick
     xvfb-run -a 07_visual_surface_study --out figures/07_liver     (figures/07_liver/render_visual_surface.sh)

   Description: the liver of mesh/liver_shape.hpp meshed with 10k tets (make_liver_mesh); its
   visual surfaces by implicit_surface_mesh (mesh/implicit_surface_mesh.hpp) with triangles of
   6, 4 and 3 mm, each embedded in the tets (xfem/visual_surface.hpp). Two parts:
     sizes    visual_surface.csv (and the same on stdout): per size, the triangles and vertices,
              their ratio to the tet boundary's triangles, the enclosed volume against the tets',
              the largest |phi| at a vertex, the seconds to mesh and to embed, how many vertices
              lie outside every tet and the largest distance of one to its tet;
     picture  visual_surface.png: the 3 mm visual surface, smooth (vertex normals), beside the tet
              mesh's boundary drawn faceted, 0.24 m to its right;
     cut      visual_surface_cut.png: the liver cut through by the plane x = 0.01 m, each side
              moved 15 mm away from it (a prescribed XFEM field, no solve), the 3 mm visual
              surface following the pieces with the triangles across the cut dropped.
   The pictures are drawn through X: run them under xvfb-run. --quick skips them (it is a test,
   run without a display).
   --quick runs the 3000-tet liver and the 6 mm surface only. Times are of one run each on a
   machine that may be shared.

   Read chapter 7 first. */

#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/fem/linear_material.hpp"
#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/quadrature/gauss_piece_rules.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"
#include "kerf/xfem/surface_enrichment.hpp"
#include "kerf/mesh/implicit_surface_mesh.hpp"
#include "kerf/mesh/liver_mesh.hpp"
#include "kerf/mesh/liver_shape.hpp"
#include "kerf/render/surface_image.hpp"
#include "kerf/render/triangle_surface_polydata.hpp"
#include "kerf/render/write_png.hpp"
#include "kerf/xfem/visual_surface.hpp"
#include "measure.hpp" // bench/measure.hpp: the command line shared with the benchmarks

#include <vtkAppendPolyData.h>
#include <vtkNew.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <vector>

namespace visual_surface_study {

double seconds_since(kerf_measure::clock::time_point start) {
  return std::chrono::duration<double>(kerf_measure::clock::now() - start).count();
}

/// The volume enclosed by outward triangles, sum x0 . (x1 x x2) / 6 (divergence theorem).
double enclosed_volume(const kerf::TriangleSurface& s) {
  double volume = 0.0;
  for (Eigen::Index f = 0; f < s.num_triangles(); ++f) {
    const Eigen::Vector3d x0 = s.vertices.row(s.triangles(f, 0)), x1 = s.vertices.row(s.triangles(f, 1)),
                          x2 = s.vertices.row(s.triangles(f, 2));
    volume += x0.dot(x1.cross(x2)) / 6.0;
  }
  return volume;
}

} // namespace visual_surface_study

int main(int argc, char** argv) {
  using namespace visual_surface_study;
  const auto options = kerf_measure::parse_run_options(argc, argv, "07_visual_surface_study [--quick] [--out DIR] [--only sizes,picture,cut]",
                                                       "output/visual_surface_study", {"sizes", "picture", "cut"});
  if (!options) return 2;
  try {
    std::filesystem::create_directories(options->out);
    std::cout << "Kerf chapter 7 visual surface study" << (options->quick ? " (quick)" : "") << " on " << kerf_measure::cpu_model()
              << ", " << kerf_measure::now_text() << "\n";
    const int target = options->quick ? 3000 : 10000;
    auto start = kerf_measure::clock::now();
    const kerf::TetMesh mesh = kerf::make_liver_mesh(target);
    const double mesh_seconds = seconds_since(start);
    const kerf::TriangleSurface tet_boundary = kerf::boundary_surface(mesh);
    double tet_volume = 0.0;
    for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
      const Eigen::Matrix<double, 4, 3> X = kerf::tet_corners(mesh, t);
      tet_volume += (X.row(1) - X.row(0)).dot((X.row(2) - X.row(0)).cross(X.row(3) - X.row(0))) / 6.0;
    }
    std::printf("liver: %ld tets (target %d, %.2f s), boundary %ld triangles, volume %.6e m^3, Mesh_3 facet distance %.2f mm\n",
                static_cast<long>(mesh.num_tets()), target, mesh_seconds, static_cast<long>(tet_boundary.num_triangles()), tet_volume,
                1e3 * kerf::liver_mesh_sizing(target).facet_distance);

    if (options->runs("sizes")) {
      std::ofstream csv(options->out / "visual_surface.csv");
      csv << "size_mm,triangles,vertices,ratio_to_tet_boundary,volume_over_tets,max_abs_phi_m,mesh_seconds,embed_seconds,outside,"
             "largest_distance_mm\n";
      const std::vector<double> sizes = options->quick ? std::vector<double>{0.006} : std::vector<double>{0.006, 0.004, 0.003};
      for (const double h : sizes) {
        start = kerf_measure::clock::now();
        const kerf::TriangleSurface s =
            kerf::implicit_surface_mesh(kerf::liver_phi, kerf::liver_centre(), kerf::liver_bounding_radius(), kerf::implicit_surface_sizing(h));
        const double surface_seconds = seconds_since(start);
        start = kerf_measure::clock::now();
        const kerf::VisualSurface visual(mesh, s);
        const double embed_seconds = seconds_since(start);
        double max_phi = 0.0;
        for (Eigen::Index v = 0; v < s.num_vertices(); ++v) max_phi = std::max(max_phi, std::abs(kerf::liver_phi(s.vertices.row(v).transpose())));
        char line[512];
        std::snprintf(line, sizeof line, "%.1f,%ld,%ld,%.2f,%.4f,%.2e,%.3f,%.3f,%ld,%.3f", 1e3 * h, static_cast<long>(s.num_triangles()),
                      static_cast<long>(s.num_vertices()), static_cast<double>(s.num_triangles()) / tet_boundary.num_triangles(),
                      enclosed_volume(s) / tet_volume, max_phi, surface_seconds, embed_seconds, static_cast<long>(visual.num_outside()),
                      1e3 * visual.largest_distance());
        csv << line << '\n';
        std::cout << line << '\n';
      }
    }

    if (options->runs("picture") && !options->quick) {
      const kerf::TriangleSurface s =
          kerf::implicit_surface_mesh(kerf::liver_phi, kerf::liver_centre(), kerf::liver_bounding_radius(), kerf::implicit_surface_sizing(0.003));
      // The tets' boundary stands 0.24 m to the right (+x) of the visual surface: the liver is 0.2 m wide.
      kerf::TriangleSurface shifted = tet_boundary;
      shifted.vertices.col(0).array() += 0.24;
      vtkNew<vtkAppendPolyData> both;
      both->AddInputData(kerf::triangle_surface_polydata(s, kerf::Shading::smooth));
      both->AddInputData(kerf::triangle_surface_polydata(shifted, kerf::Shading::faceted));
      both->Update();
      kerf::PictureSettings settings;
      settings.colour_by = kerf::surface_label_name;
      settings.camera = {.azimuth = -80, .elevation = 35, .zoom = 1.8};
      settings.width = 1200;
      settings.height = 500;
      start = kerf_measure::clock::now();
      const vtkSmartPointer<vtkImageData> image = kerf::render_surface_image(*both->GetOutput(), settings);
      kerf::write_png(options->out / "visual_surface.png", *image);
      std::printf("wrote %s: %ld visual triangles (3 mm) beside %ld tet boundary triangles, %.2f s\n",
                  (options->out / "visual_surface.png").string().c_str(), static_cast<long>(s.num_triangles()),
                  static_cast<long>(tet_boundary.num_triangles()), seconds_since(start));
    }

    if (options->runs("cut") && !options->quick) {
      // The plane x = x_c, as two triangles far beyond the liver, normal +x: above is x > x_c.
      const double x_c = 0.01;
      kerf::TriangleSurface plane;
      plane.vertices = Eigen::MatrixX3d{{x_c, -1, -1}, {x_c, 1, -1}, {x_c, 1, 1}, {x_c, -1, 1}};
      plane.triangles = Eigen::MatrixX3i{{0, 1, 2}, {0, 2, 3}};
      start = kerf_measure::clock::now();
      const kerf::CutSurfaces cuts({plane});
      const kerf::MeshPieces pieces = kerf::cut_mesh_into_pieces(mesh, cuts);
      const kerf::SurfaceEnrichment enrichment = kerf::make_surface_enrichment(mesh, pieces);
      const kerf::LinearMaterial material{3000.0, 0.45, 1000.0};
      const kerf::CutXfemModel model(mesh, material, pieces, enrichment,
                                     [](const Eigen::Matrix<double, 4, 3>&, const kerf::TetPieces& p, int piece, int degree) {
                                       return kerf::subtet_rule(p, piece, degree);
                                     });
      // The field that is +15 mm in x beyond the plane and -15 mm before it: at every node u_i is
      // its home side's value and a_k the other side's minus it (chapter 4).
      const Eigen::Vector3d apart(0.015, 0, 0);
      const auto side_value = [&](const Eigen::Vector3d& x) -> Eigen::Vector3d { return x.x() > x_c ? apart : Eigen::Vector3d(-apart); };
      const Eigen::Index N = mesh.num_nodes();
      Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * model.num_dof_nodes());
      for (Eigen::Index i = 0; i < N; ++i) {
        const Eigen::Vector3d x = mesh.nodes.row(i).transpose();
        u.segment<3>(3 * i) = side_value(x);
        for (int k = enrichment.first_enrichment[static_cast<std::size_t>(i)]; k < enrichment.first_enrichment[static_cast<std::size_t>(i) + 1]; ++k)
          u.segment<3>(3 * (N + k)) = -2.0 * side_value(x);
      }
      const double model_seconds = seconds_since(start);
      const kerf::TriangleSurface s =
          kerf::implicit_surface_mesh(kerf::liver_phi, kerf::liver_centre(), kerf::liver_bounding_radius(), kerf::implicit_surface_sizing(0.003));
      const kerf::VisualSurface visual(mesh, s);
      start = kerf_measure::clock::now();
      const std::vector<int> keep = kerf::untorn_triangles(s, kerf::CutSurfaces({plane}));
      const kerf::TriangleSurface moved = kerf::keep_triangles(visual.deform(kerf::xfem_visual_displacement(model, u)), keep);
      const double frame_seconds = seconds_since(start);
      kerf::PictureSettings settings;
      settings.colour_by = kerf::surface_label_name;
      settings.camera = {.azimuth = -60, .elevation = 30, .zoom = 1.3};
      settings.width = 900;
      settings.height = 600;
      const vtkSmartPointer<vtkImageData> image =
          kerf::render_surface_image(*kerf::triangle_surface_polydata(moved, kerf::Shading::smooth), settings);
      kerf::write_png(options->out / "visual_surface_cut.png", *image);
      std::printf("wrote %s: cut model %.2f s, %ld of %ld visual triangles dropped across the cut, dropping and deforming %.3f s\n",
                  (options->out / "visual_surface_cut.png").string().c_str(), model_seconds,
                  static_cast<long>(s.num_triangles()) - static_cast<long>(keep.size()), static_cast<long>(s.num_triangles()), frame_seconds);
    }
  } catch (const std::exception& error) {
    std::cerr << "07_visual_surface_study: " << error.what() << '\n';
    return 1;
  }
  return 0;
}
