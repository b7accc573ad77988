/* Kerf, chapter 7 study: what one frame of Gutierrez and Ramos's semi-progressive cut costs on the
   liver (cut/semi_progressive_cut.hpp): the time of one add_swept_triangles call while a blade
   crosses the 10k-tet liver in steps of 1 mm, and how that time changes with the step.

   Build:   cmake --preset release && cmake --build --preset release --target 07_blade_sweep_study

   Sample runs:
     07_blade_sweep_study --quick --out output/blade_sweep_study_quick
     07_blade_sweep_study --out figures/07_liver

   Description: the liver of mesh/liver_mesh.hpp (10k target tets; 2k with --quick). The blade's
   edge is a segment 0.16 m long, tilted 11 degrees from the vertical in the y-z plane, through
   y = 0.01 m, z = 0.01 m; it translates along x from x = -0.115 m to x = 0.115 m, in and out of
   the organ (0.20 m long in x), as a BladePath of two keyframes 2.3 s apart (0.1 m/s). Each frame
   takes the edge at the next time, sweeps swept_quad (two triangles) from the previous edge, and
   hands it to one add_swept_triangles call, which we time alone (steady clock). For steps of
   0.5, 1, 2 and 5 mm a fresh cut is swept 7 times and each call keeps its shortest time; one
   line per step in blade_sweep.csv: calls, mean, median, 95th percentile and largest of those
   times, the edges and tets crossed in all, the most tets crossed by one call. At the end the crossed tets are compared with chapter 4's exact
   clipping (cut_mesh_into_pieces) of the whole swept rectangle: they must be the same set.
   Times are best of 7 on a machine that may be shared: they say how the cost grows, not what it
   is to the microsecond.

   Read chapter 7 first. */

#include "kerf/cut/blade_path.hpp"
#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/cut/semi_progressive_cut.hpp"
#include "kerf/cut/swept_quad.hpp"
#include "kerf/mesh/liver_mesh.hpp"
#include "measure.hpp" // bench/measure.hpp: the command line shared with the benchmarks

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <numeric>
#include <set>
#include <vector>

namespace blade_sweep_study {

/// The blade of the description: a tilted edge translating along x at 0.1 m/s.
kerf::BladePath liver_blade_path() {
  const double tilt = 11.0 * M_PI / 180.0;
  const Eigen::Vector3d direction(0.0, std::sin(tilt), std::cos(tilt)); // perpendicular to the motion (1, 0, 0)
  const Eigen::Vector3d middle(-0.115, 0.01, 0.01);
  const kerf::BladeEdge start{middle - 0.08 * direction, middle + 0.08 * direction};
  const Eigen::Vector3d travel(0.23, 0.0, 0.0);
  return kerf::BladePath({{0.0, start}, {2.3, {start.start + travel, start.end + travel}}});
}

/// One sweep and what we measured of it.
struct Row {
  double step_mm = 0.0;
  int calls = 0;
  double mean_us = 0.0, median_us = 0.0, p95_us = 0.0, max_us = 0.0;
  int edges_crossed = 0, tets_crossed = 0, most_tets_in_one_call = 0;
  std::set<int> crossed;
};

/// Sweeps a fresh cut across the liver `repeats` times and keeps, for each call, its shortest time:
/// every sweep makes the same calls on the same state, so the minimum is the call's cost and the
/// rest is the shared machine (single runs showed 0.5-1.3 ms spikes on calls that take 30 us).
Row sweep(const kerf::TetMesh& mesh, const kerf::BladePath& path, double step_mm, int repeats) {
  const double speed = 0.1; // m/s, the path's
  const double dt = step_mm * 1e-3 / speed;
  const int frames = static_cast<int>(std::ceil(path.duration() / dt - 1e-9));
  std::vector<double> seconds(static_cast<std::size_t>(frames), std::numeric_limits<double>::infinity());
  Row row;
  row.step_mm = step_mm;
  for (int repeat = 0; repeat < repeats; ++repeat) {
    kerf::SemiProgressiveCut cut(mesh);
    kerf::BladeEdge previous = path.edge_at(path.start_time());
    for (int k = 1; k <= frames; ++k) {
      const kerf::BladeEdge edge = path.edge_at(std::min(path.start_time() + k * dt, path.end_time()));
      const std::vector<kerf::SweptTriangle> sheet = kerf::swept_quad(previous, edge);
      const auto start = kerf_measure::clock::now();
      const std::vector<int> crossed = cut.add_swept_triangles(sheet);
      double& best = seconds[static_cast<std::size_t>(k - 1)];
      best = std::min(best, std::chrono::duration<double>(kerf_measure::clock::now() - start).count());
      row.most_tets_in_one_call = std::max(row.most_tets_in_one_call, static_cast<int>(crossed.size()));
      previous = edge;
    }
    row.edges_crossed = cut.num_crossed_edges_total();
    row.tets_crossed = static_cast<int>(cut.crossed_tets().size());
    row.crossed = std::set<int>(cut.crossed_tets().begin(), cut.crossed_tets().end());
  }
  row.calls = frames;
  row.mean_us = 1e6 * std::accumulate(seconds.begin(), seconds.end(), 0.0) / row.calls;
  std::sort(seconds.begin(), seconds.end());
  row.median_us = 1e6 * seconds[seconds.size() / 2];
  row.p95_us = 1e6 * seconds[static_cast<std::size_t>(0.95 * static_cast<double>(seconds.size() - 1))];
  row.max_us = 1e6 * seconds.back();
  return row;
}

} // namespace blade_sweep_study

int main(int argc, char** argv) {
  const auto options = kerf_measure::parse_run_options(argc, argv, "07_blade_sweep_study [--quick] [--out DIR]", "output/blade_sweep_study");
  if (!options) return 2;
  try {
    namespace bs = blade_sweep_study;
    std::filesystem::create_directories(options->out);
    std::cout << "Kerf chapter 7 blade sweep study" << (options->quick ? " (quick)" : "") << " on " << kerf_measure::cpu_model() << ", "
              << kerf_measure::now_text() << "\n";
    const int target = options->quick ? 2000 : 10000;
    const kerf::TetMesh mesh = kerf::make_liver_mesh(target);
    const auto start = kerf_measure::clock::now();
    const kerf::SemiProgressiveCut built(mesh);
    const double build_ms = 1e3 * std::chrono::duration<double>(kerf_measure::clock::now() - start).count();
    std::printf("liver: %ld tets, %ld nodes, %d edges; SemiProgressiveCut built in %.1f ms\n", static_cast<long>(mesh.num_tets()),
                static_cast<long>(mesh.num_nodes()), built.num_edges(), build_ms);

    const kerf::BladePath path = bs::liver_blade_path();
    std::ofstream csv(options->out / "blade_sweep.csv");
    csv << "step_mm,calls,mean_us,median_us,p95_us,max_us,edges_crossed,tets_crossed,most_tets_in_one_call\n";
    std::printf("| step (mm) | calls | mean (us) | median (us) | 95 %% (us) | max (us) | edges crossed | tets crossed | most tets in one call |\n");
    std::printf("|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    const std::vector<double> steps = options->quick ? std::vector<double>{1.0} : std::vector<double>{0.5, 1.0, 2.0, 5.0};
    std::vector<bs::Row> rows;
    for (const double step : steps) {
      const bs::Row r = bs::sweep(mesh, path, step, options->quick ? 2 : 7);
      csv << r.step_mm << ',' << r.calls << ',' << r.mean_us << ',' << r.median_us << ',' << r.p95_us << ',' << r.max_us << ',' << r.edges_crossed
          << ',' << r.tets_crossed << ',' << r.most_tets_in_one_call << std::endl;
      std::printf("| %.1f | %d | %.1f | %.1f | %.1f | %.1f | %d | %d | %d |\n", r.step_mm, r.calls, r.mean_us, r.median_us, r.p95_us, r.max_us,
                  r.edges_crossed, r.tets_crossed, r.most_tets_in_one_call);
      rows.push_back(r);
    }

    // The check: the blade translates, so its whole sheet is one rectangle; chapter 4 clips it exactly.
    const kerf::BladeEdge first = path.edge_at(path.start_time()), last = path.edge_at(path.end_time());
    const kerf::RectangleCut rectangle(first.start, first.end - first.start, last.start - first.start);
    const kerf::MeshPieces pieces = kerf::cut_mesh_into_pieces(mesh, kerf::CutSurfaces({kerf::rectangle_surface(rectangle)}));
    std::set<int> split;
    for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
      if (pieces.num_pieces(t) >= 2) split.insert(static_cast<int>(t));
    bool all_agree = true;
    for (const bs::Row& r : rows) all_agree = all_agree && r.crossed == split;
    std::printf("chapter 4 splits %zu tets; the crossed tets of every step are that set: %s\n", split.size(), all_agree ? "yes" : "NO");
    return all_agree ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "07_blade_sweep_study: " << e.what() << '\n';
    return 1;
  }
}
