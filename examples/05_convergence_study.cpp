/* Kerf, chapter 5 study: does the crack-tip enrichment restore the optimal convergence rate?

   Build:   cmake --preset release && cmake --build --preset release --target 05_convergence_study

   Sample runs:
     05_convergence_study --quick --out output/convergence_study_quick
     05_convergence_study --out figures/05_crack_tip
     05_convergence_study --only ladder,sif --out /tmp/c

   Description: Williams's plane-strain field prescribed on the whole boundary of the cracked slab
   [-0.5, 0.5]^2 x [0, 0.2] m (examples/williams_slab.hpp: the front at (0.2 h, -0.1 h), through
   the middle of elements on every mesh; every DOF of a boundary node prescribed by the XFEM
   interpolant of the exact field). n x n x max(2, n / 5) box cells, n odd. The parts:
     rules     the blending tets' rule (degree 6 or 4, graded 0 to 3 times) on n = 9, r_e = 0.2 m:
               the errors do not change in 4 digits, so the rest uses degree 4, ungraded;
     small     the ladder n = 5, 7, 9, 11, 13 (the test's meshes), with r_e = 0.1 m and 0.25 m;
     ladder    the mesh ladder n = 5, 9, 17, 33 for the enrichment none (chapter 4: Heaviside
               only, the cut ends at the last row of sign nodes), topological (the front tets'
               nodes) and geometric with the fixed radius 0.1 m (Laborde et al. 2005), mode I,
               Tet4: relative L2 and energy errors, the L2 error in the blending tets and in the
               tets with all corners enriched, the same errors of the interpolant, K by the
               interaction integral of the solution and of the interpolant, unknowns, and the
               seconds to build, assemble and solve (on a shared machine: indicative only);
     fine      the ladder's n = 65 (not with --quick);
     corrected the ladder n = 5 to 65 with Fries's blending correction (branch_enrichment.hpp),
               topological and geometric with r_e = 0.1 m;
     tet10     the same on Tet10 for n = 5, 9 (the collapsed front rule has 6^3 points per
               sub-tet: small meshes only);
     radius    r_e = 0 (topological), h, 2 h, 4 h, 0.05, 0.1, 0.2 m and the library's default
               (xfem/tip_enrichment_radius.hpp) on n = 9, 17: error against cost;
     sif       K for modes II and mixed (K_II / K_I = -0.6) with r_e = 0.1 m on n = 9, 17, 33;
     sif_radius  K for the three modes with r_e = 0.2 m and 0.35 m on n = 9, 17 (0.35 m puts the
               interaction integral's ring, 0.1 to 0.3 m, where every node is branch enriched);
     gripped   the boundary as the scene's displacement_file prescribes it (the enrichments of a
               boundary node held at 0): the crack's mouth closed where the exact field opens it.
   It writes convergence.csv (one row per run) into the --out folder and prints each row; --quick
   runs every part on n = 5 only, the rules ungraded only (a test).

   Read chapter 5 first. */

#include "williams_slab.hpp"

#include "kerf/fracture/interaction_integral.hpp"
#include "kerf/xfem/tip_enrichment_radius.hpp"
#include "measure.hpp" // bench/measure.hpp: the command line shared with the benchmarks

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace convergence_study {

namespace ws = williams_slab;

struct Row {
  std::string part;
  ws::Setup setup;
  std::string radius_rule; // how the radius was chosen ("", "h", "2h", "0.1m", ...)
  double h = 0.0;
  int unknowns = 0, branch_nodes = 0, blending_tets = 0;
  double seconds = 0.0; // model built, assembled and solved
  ws::Errors errors;
  ws::Errors interpolation; // of the interpolant (every DOF from the exact field)
  kerf::StressIntensityFactors K_measured;
  kerf::StressIntensityFactors K_interpolant; // of the interpolant: the integral's own error on an XFEM field
};

Row run(const std::string& part, const ws::Setup& setup, const std::string& radius_rule, bool with_sifs) {
  Row row;
  row.part = part;
  row.setup = setup;
  row.radius_rule = radius_rule;
  row.h = ws::cell_size(setup);
  const auto start = std::chrono::steady_clock::now();
  const ws::Slab slab(setup);
  const Eigen::VectorXd u = ws::solve(slab, &row.unknowns);
  row.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (slab.branch) {
    row.branch_nodes = slab.branch->num_branch_nodes();
    for (const char b : slab.branch->blending) row.blending_tets += b != 0;
  }
  row.errors = ws::measure_errors(slab, u);
  row.interpolation = ws::measure_errors(slab, slab.interpolant());
  if (with_sifs) {
    row.K_measured = ws::interaction_sifs(slab, u);
    row.K_interpolant = ws::interaction_sifs(slab, slab.interpolant());
  }
  const kerf::StressIntensityFactors& K = setup.K;
  const double scale = std::max(std::abs(K.K_I), std::abs(K.K_II));
  std::printf("%-8s %-11s Tet%-2d n %3d r_e %-7s %7d unknowns %5d branch %7.2f s  L2 %.3e  energy %.3e (interpolant %.3e)  blending %.3e  K_I %+.2e K_II %+.2e (interpolant %+.2e %+.2e)\n",
              part.c_str(), ws::name(setup.enrichment), setup.order == 1 ? 4 : 10, setup.cells, radius_rule.c_str(), row.unknowns,
              row.branch_nodes, row.seconds, row.errors.relative_L2(), row.errors.relative_energy(), row.interpolation.relative_energy(), row.errors.L2_blending / row.errors.L2_exact,
              with_sifs ? (row.K_measured.K_I - K.K_I) / scale : NAN, with_sifs ? (row.K_measured.K_II - K.K_II) / scale : NAN,
              with_sifs ? (row.K_interpolant.K_I - K.K_I) / scale : NAN, with_sifs ? (row.K_interpolant.K_II - K.K_II) / scale : NAN);
  std::fflush(stdout);
  return row;
}

void write_csv(const std::vector<Row>& rows, const std::filesystem::path& out) {
  std::ofstream csv(out / "convergence.csv");
  csv << "part,enrichment,order,boundary,n,h,radius_rule,radius,K_I,K_II,unknowns,branch_nodes,blending_tets,seconds,"
         "L2,L2_exact,energy,energy_exact,L2_blending,L2_enriched,L2_interpolant,energy_interpolant,K_I_measured,K_II_measured,K_I_interpolant,K_II_interpolant\n";
  csv.precision(10);
  for (const Row& r : rows) {
    const ws::Setup& s = r.setup;
    const bool geometric = s.enrichment == ws::TipEnrichment::geometric;
    const bool has_K = r.part == "sif" || r.part == "ladder" || r.part == "sif_radius" || r.part == "corrected";
    csv << r.part << ',' << ws::name(s.enrichment) << ',' << s.order << ','
        << (s.boundary == ws::BoundaryEnrichments::interpolated ? "interpolated" : "gripped") << ',' << s.cells << ',' << r.h << ','
        << (r.radius_rule.empty() ? "NaN" : r.radius_rule) << ',' << (geometric ? s.radius : NAN) << ',' << s.K.K_I << ',' << s.K.K_II
        << ',' << r.unknowns << ',' << r.branch_nodes << ',' << r.blending_tets << ',' << r.seconds << ',' << r.errors.L2 << ','
        << r.errors.L2_exact << ',' << r.errors.energy << ',' << r.errors.energy_exact << ',' << r.errors.L2_blending << ','
        << r.errors.L2_enriched << ',' << r.interpolation.L2 << ','
        << r.interpolation.energy << ',' << (has_K ? r.K_measured.K_I : NAN) << ',' << (has_K ? r.K_measured.K_II : NAN) << ','
        << (has_K ? r.K_interpolant.K_I : NAN) << ',' << (has_K ? r.K_interpolant.K_II : NAN) << '\n';
  }
  if (!csv) throw std::runtime_error("cannot write " + (out / "convergence.csv").string());
}

} // namespace convergence_study

int main(int argc, char** argv) {
  const auto options = kerf_measure::parse_run_options(argc, argv, "05_convergence_study [--quick] [--out DIR] [--only PARTS]",
                                                       "output/convergence_study", {"rules", "small", "ladder", "fine", "corrected", "tet10", "radius", "sif", "sif_radius", "gripped"});
  if (!options) return 2;
  try {
    namespace cs = convergence_study;
    namespace ws = williams_slab;
    std::filesystem::create_directories(options->out);
    std::vector<cs::Row> rows;
    const std::vector<int> ladder = options->quick ? std::vector<int>{5} : std::vector<int>{5, 9, 17, 33};
    const std::vector<int> short_ladder = options->quick ? std::vector<int>{5} : std::vector<int>{9, 17};
    const std::vector<int> sif_ladder = options->quick ? std::vector<int>{5} : std::vector<int>{9, 17, 33};
    const double fixed_radius = 0.1;
    const auto setup = [](int n, int order, ws::TipEnrichment e, double radius) {
      ws::Setup s;
      s.cells = n;
      s.order = order;
      s.enrichment = e;
      s.radius = radius;
      return s;
    };
    if (options->runs("rules"))
      for (const int depth : options->quick ? std::vector<int>{0} : std::vector<int>{3, 2, 1, 0})
        for (const int degree : {6, 4}) {
          ws::Setup s = setup(options->quick ? 5 : 9, 1, ws::TipEnrichment::geometric, 0.2);
          s.blending_degree = degree;
          s.blending_depth = depth;
          char rule[32];
          std::snprintf(rule, sizeof rule, "d%dr%d", degree, depth);
          rows.push_back(cs::run("rules", s, rule, false));
        }
    // The small ladder of tests/chapter_05/test_convergence_rates.cpp, whose tolerances it justifies.
    if (options->runs("small"))
      for (const int n : options->quick ? std::vector<int>{5} : std::vector<int>{5, 7, 9, 11, 13}) {
        for (const ws::TipEnrichment e : {ws::TipEnrichment::none, ws::TipEnrichment::topological})
          rows.push_back(cs::run("small", setup(n, 1, e, 0.0), "", false));
        for (const auto& [rule, radius] : std::vector<std::pair<std::string, double>>{{"0.1m", 0.1}, {"0.25m", 0.25}})
          rows.push_back(cs::run("small", setup(n, 1, ws::TipEnrichment::geometric, radius), rule, false));
      }
    if (options->runs("ladder"))
      for (const ws::TipEnrichment e : {ws::TipEnrichment::none, ws::TipEnrichment::topological, ws::TipEnrichment::geometric})
        for (const int n : ladder)
          rows.push_back(cs::run("ladder", setup(n, 1, e, fixed_radius), e == ws::TipEnrichment::geometric ? "0.1m" : "", true));
    // One more step of the ladder (minutes): n = 65.
    if (options->runs("fine") && !options->quick)
      for (const ws::TipEnrichment e : {ws::TipEnrichment::none, ws::TipEnrichment::topological, ws::TipEnrichment::geometric})
        rows.push_back(cs::run("ladder", setup(65, 1, e, fixed_radius), e == ws::TipEnrichment::geometric ? "0.1m" : "", true));
    // Fries's corrected XFEM (branch_enrichment.hpp) on the same ladder: does the ramp over the
    // blending tets restore h^2?
    if (options->runs("corrected"))
      for (const ws::TipEnrichment e : {ws::TipEnrichment::topological, ws::TipEnrichment::geometric})
        for (const int n : options->quick ? std::vector<int>{5} : std::vector<int>{5, 9, 17, 33, 65}) {
          ws::Setup s = setup(n, 1, e, fixed_radius);
          s.blending = kerf::BlendingCorrection::corrected;
          rows.push_back(cs::run("corrected", s, e == ws::TipEnrichment::geometric ? "0.1m" : "", true));
        }
    if (options->runs("tet10"))
      for (const ws::TipEnrichment e : {ws::TipEnrichment::none, ws::TipEnrichment::topological, ws::TipEnrichment::geometric})
        for (const int n : options->quick ? std::vector<int>{5} : std::vector<int>{5, 9}) rows.push_back(cs::run("tet10", setup(n, 2, e, fixed_radius), e == ws::TipEnrichment::geometric ? "0.1m" : "", false));
    if (options->runs("radius"))
      for (const int n : short_ladder) {
        const double h = 1.0 / n;
        rows.push_back(cs::run("radius", setup(n, 1, ws::TipEnrichment::topological, 0.0), "0", false));
        for (const auto& [rule, radius] : std::vector<std::pair<std::string, double>>{
                 {"h", h}, {"2h", 2 * h}, {"4h", 4 * h}, {"0.05m", 0.05}, {"0.1m", 0.1}, {"0.2m", 0.2}})
          rows.push_back(cs::run("radius", setup(n, 1, ws::TipEnrichment::geometric, radius), rule, false));
        // The library's default rule (xfem/tip_enrichment_radius.hpp) on this mesh.
        ws::Setup probe = setup(n, 1, ws::TipEnrichment::geometric, 0.0);
        const kerf::TetMesh mesh = ws::slab_mesh(probe);
        const kerf::CutSurfaces cuts(std::vector<kerf::TriangleSurface>{ws::slab_crack(probe)});
        probe.radius = kerf::default_tip_enrichment_radius(mesh, kerf::find_crack_fronts(mesh, cuts));
        rows.push_back(cs::run("radius", probe, "default", false));
      }
    if (options->runs("sif"))
      for (const kerf::StressIntensityFactors K : {kerf::StressIntensityFactors{0.0, 1.0e4, 0.0}, kerf::StressIntensityFactors{1.0e4, -0.6e4, 0.0}})
        for (const int n : sif_ladder) {
          ws::Setup s = setup(n, 1, ws::TipEnrichment::geometric, fixed_radius);
          s.K = K;
          rows.push_back(cs::run("sif", s, "0.1m", true));
        }
    // K against the radius: with r_e beyond the domain's outer radius (0.3 m) the interaction
    // integral's ring lies where every node carries the branch functions.
    if (options->runs("sif_radius"))
      for (const kerf::StressIntensityFactors K : {kerf::StressIntensityFactors{1.0e4, 0.0, 0.0}, kerf::StressIntensityFactors{0.0, 1.0e4, 0.0},
                                                    kerf::StressIntensityFactors{1.0e4, -0.6e4, 0.0}})
        for (const int n : short_ladder)
          for (const auto& [rule, radius] : std::vector<std::pair<std::string, double>>{{"0.2m", 0.2}, {"0.35m", 0.35}}) {
            ws::Setup s = setup(n, 1, ws::TipEnrichment::geometric, radius);
            s.K = K;
            rows.push_back(cs::run("sif_radius", s, rule, true));
          }
    if (options->runs("gripped"))
      for (const ws::TipEnrichment e : {ws::TipEnrichment::none, ws::TipEnrichment::geometric})
        for (const int n : short_ladder) {
          ws::Setup s = setup(n, 1, e, fixed_radius);
          s.boundary = ws::BoundaryEnrichments::gripped;
          rows.push_back(cs::run("gripped", s, e == ws::TipEnrichment::geometric ? "0.1m" : "", false));
        }
    cs::write_csv(rows, options->out);
  } catch (const std::exception& error) {
    std::cerr << "05_convergence_study: " << error.what() << '\n';
    return 1;
  }
  return 0;
}
