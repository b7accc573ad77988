/* Kerf, chapter 7 study: the liver of our own, meshed by CGAL's Mesh_3 from its implicit surface
   How many tets we get for the number asked, how long it takes, how
   good the tets are and how close the volume is; and what Mesh_3's optimisers buy at what cost.

   Build:   cmake --preset release && cmake --build --preset release --target 07_liver_mesh_study

   Sample runs:
     07_liver_mesh_study --quick --out output/liver_mesh_study_quick
     07_liver_mesh_study --out figures/07_liver --only targets,optimisers

   Description: the liver is the smooth union of two ellipsoid lobes cut smoothly by a floor
   plane (mesh/liver_shape.hpp), about 0.20 x 0.15 x 0.10 m; make_liver_mesh (mesh/liver_mesh.hpp)
   chooses Mesh_3's bounds from the target count. Two parts, each a CSV file in --out:
     targets     liver_mesh.csv: for 2k, 5k, 10k, 20k, 50k and 100k target tets with the default
                 optimisation (perturb and exude, sliver bound 15 degrees): tets, vertices, the
                 seconds of one make_liver_mesh call, the smallest and mean (per-tet smallest)
                 dihedral angle, the smallest and mean radius ratio, and the volume's error
                 against a midpoint count of phi < 0 on 0.5 mm cubes (0.02 % accurate);
     optimisers  liver_optimisers.csv: 10k target tets with none, perturb, exude, both, then ODT or
                 Lloyd (10 iterations) before both, and sliver bounds 12, 15, 18, 20 degrees;
     picture     liver_mesh.vtu: the 10k mesh (2k with --quick) with each tet's smallest
                 dihedral angle and radius ratio as cell arrays and a zero 'displacement', for
                 ParaView or render_pieces (figures/07_liver/render_liver.sh draws it).
   Times are of one run each on a machine that may be shared: they say how the cost grows, not
   what it is to the millisecond. --quick runs 2k targets and two optimiser rows; it is a test.

   Read chapter 7 first. */

#include "kerf/io/write_vtu.hpp"
#include "kerf/mesh/liver_mesh.hpp"
#include "kerf/mesh/liver_shape.hpp"
#include "kerf/mesh/check_tet_mesh.hpp"
#include "kerf/mesh/tet_quality.hpp"
#include "measure.hpp" // bench/measure.hpp: the command line shared with the benchmarks

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

namespace liver_mesh_study {

/// One mesh and what we measured of it.
struct Row {
  std::string label;
  int target = 0;
  Eigen::Index tets = 0, vertices = 0;
  double seconds = 0.0, volume_error = 0.0;
  kerf::TetQualitySummary quality;
};

Row measure(const std::string& label, int target, const kerf::ImplicitMeshOptimisation& optimisation, double reference_volume) {
  Row row;
  row.label = label;
  row.target = target;
  const auto start = kerf_measure::clock::now();
  const kerf::TetMesh mesh = kerf::make_liver_mesh(target, kerf::LiverShape::lobes, optimisation);
  row.seconds = std::chrono::duration<double>(kerf_measure::clock::now() - start).count();
  row.tets = mesh.num_tets();
  row.vertices = mesh.num_nodes();
  double volume = 0.0;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) volume += kerf::signed_tet_volume(mesh, t);
  row.volume_error = (volume - reference_volume) / reference_volume;
  row.quality = kerf::tet_quality_summary(mesh);
  return row;
}

void write_header(std::ostream& csv) {
  csv << "label,target,tets,vertices,seconds,min_dihedral_deg,mean_min_dihedral_deg,min_radius_ratio,mean_radius_ratio,"
         "tets_below_10deg,volume_error\n";
}

void write_row(std::ostream& csv, const Row& r) {
  csv << r.label << ',' << r.target << ',' << r.tets << ',' << r.vertices << ',' << r.seconds << ',' << r.quality.min_dihedral_angle << ','
      << r.quality.mean_min_dihedral_angle << ',' << r.quality.min_radius_ratio << ',' << r.quality.mean_radius_ratio << ','
      << r.quality.below_dihedral_threshold << ',' << r.volume_error << std::endl;
  std::printf("%-16s %7d %7ld %6ld %7.2f s  dihedral min %5.2f mean %5.2f  radius ratio min %.3f mean %.3f  volume %+.2f %%\n",
              r.label.c_str(), r.target, static_cast<long>(r.tets), static_cast<long>(r.vertices), r.seconds, r.quality.min_dihedral_angle,
              r.quality.mean_min_dihedral_angle, r.quality.min_radius_ratio, r.quality.mean_radius_ratio, 100.0 * r.volume_error);
}

} // namespace liver_mesh_study

int main(int argc, char** argv) {
  const auto options = kerf_measure::parse_run_options(argc, argv, "07_liver_mesh_study [--quick] [--out DIR] [--only targets,optimisers,picture]",
                                                       "output/liver_mesh_study", {"targets", "optimisers", "picture"});
  if (!options) return 2;
  try {
    namespace ls = liver_mesh_study;
    std::filesystem::create_directories(options->out);
    std::cout << "Kerf chapter 7 liver mesh study" << (options->quick ? " (quick)" : "") << " on " << kerf_measure::cpu_model() << ", "
              << kerf_measure::now_text() << "\n";
    const double reference_volume = kerf::liver_volume(options->quick ? 0.001 : 0.0005);
    std::printf("liver volume %.6e m^3 (midpoint count of %.1f mm cubes)\n", reference_volume, options->quick ? 1.0 : 0.5);
    std::printf("%-16s %7s %7s %6s\n", "label", "target", "tets", "verts");

    if (options->runs("targets")) {
      std::ofstream csv(options->out / "liver_mesh.csv");
      csv.precision(10);
      ls::write_header(csv);
      const std::vector<int> targets = options->quick ? std::vector<int>{2000} : std::vector<int>{2000, 5000, 10000, 20000, 50000, 100000};
      for (const int target : targets) ls::write_row(csv, ls::measure("default", target, {}, reference_volume));
    }

    if (options->runs("optimisers")) {
      std::ofstream csv(options->out / "liver_optimisers.csv");
      csv.precision(10);
      ls::write_header(csv);
      const int target = options->quick ? 2000 : 10000;
      const auto variant = [](int odt, int lloyd, bool perturb, bool exude, double bound) {
        kerf::ImplicitMeshOptimisation o;
        o.odt_iterations = odt;
        o.lloyd_iterations = lloyd;
        o.perturb = perturb;
        o.exude = exude;
        o.sliver_bound = bound;
        return o;
      };
      std::vector<std::pair<std::string, kerf::ImplicitMeshOptimisation>> variants{{"none", variant(0, 0, false, false, 15)},
                                                                                    {"perturb+exude", variant(0, 0, true, true, 15)}};
      if (!options->quick) {
        variants.insert(variants.end(), {{"perturb", variant(0, 0, true, false, 15)},
                                         {"exude", variant(0, 0, false, true, 15)},
                                         {"odt10+both", variant(10, 0, true, true, 15)},
                                         {"lloyd10+both", variant(0, 10, true, true, 15)},
                                         {"both bound 12", variant(0, 0, true, true, 12)},
                                         {"both bound 18", variant(0, 0, true, true, 18)},
                                         {"both bound 20", variant(0, 0, true, true, 20)}});
      }
      for (const auto& [label, o] : variants) ls::write_row(csv, ls::measure(label, target, o, reference_volume));
    }

    if (options->runs("picture")) {
      const kerf::TetMesh mesh = kerf::make_liver_mesh(options->quick ? 2000 : 10000);
      Eigen::MatrixXd angle(mesh.num_tets(), 1), ratio(mesh.num_tets(), 1);
      for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
        angle(t, 0) = kerf::tet_min_dihedral_angle(kerf::tet_corners(mesh, t));
        ratio(t, 0) = kerf::tet_radius_ratio(kerf::tet_corners(mesh, t));
      }
      const std::filesystem::path file = options->out / "liver_mesh.vtu";
      kerf::write_vtu(file, mesh, {{"displacement", Eigen::MatrixXd::Zero(mesh.num_nodes(), 3)}},
                      {{"min_dihedral_angle", angle}, {"radius_ratio", ratio}});
      std::cout << "wrote " << file.string() << " (" << mesh.num_tets() << " tets)\n";
    }
  } catch (const std::exception& error) {
    std::cerr << "07_liver_mesh_study: " << error.what() << '\n';
    return 1;
  }
  return 0;
}
