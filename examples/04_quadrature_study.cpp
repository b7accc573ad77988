/* Kerf, chapter 4 study: Koschier's Table 1 again. How accurately, with how many points and at
   what cost does each way of integrating over a piece of a cut tet integrate Koschier's four
   test polynomials?

   Build:   cmake --preset release && cmake --build --preset release --target 04_quadrature_study

   Sample runs:
     04_quadrature_study --quick --out output/quadrature_study_quick
     04_quadrature_study --out figures/04_cut_quadrature

   Description: the unit tet (0,0,0), (1,0,0), (0,1,0), (0,0,1) is cut by triangle meshes through
   split_tet_by_triangles, and the piece holding the corner (0,0,0) (Koschier's "volume portion
   indicated in blue") is integrated:
     planar     the plane x + y + z = 0.3 as one large triangle: the corner piece x + y + z <= 0.3
                (our reconstruction of Koschier's diagonal cut from his sampling column);
     kinked     our own kink, Koschier's being unknown: the plane x + y + z = 0.6 where z <= 0.3 and
                the plane z = 0.3 where x + y <= 0.3, meeting along the line x + y = 0.3, z = 0.3
                through the tet. The piece is {x + y + z <= 0.6, z <= 0.3}: the corner simplex of
                size 0.6 minus the simplex of size 0.3 standing on z = 0.3;
     spherical  a sphere of radius 0.5 about the corner (0,0,0), tessellated as an icosphere of
                level L (20 4^L triangles on the whole sphere, vertices on the sphere, turned by a
                fixed rotation so that no vertex lies in a face of the tet); the piece is the
                polyhedral ball's part in the tet. Errors are given against the analytic ball's
                octant AND against the tessellated polyhedron (its integrals by Gauss on
                sub-tets, exact for these quadratics), separately.
   The polynomials are Koschier's: 1, x + y + z, yz + xz + xy, x^2 + y^2 + z^2. The analytic
   integrals: on the corner simplex S_t = {x, y, z >= 0, x + y + z <= t}, t^3/6, t^4/8, t^5/40,
   t^5/20; on S_t moved up by c (z -> z + c), t^3/6, t^4/8 + c t^3/6, t^5/40 + c t^4/12,
   t^5/20 + c t^4/12 + c^2 t^3/6, so the kink's are those of S_0.6 minus those of S_0.3 moved
   up by 0.3; on the ball's octant, pi R^3/6, 3 pi R^4/16, R^5/5, pi R^5/10.

   The rules (quadrature/piece_quadrature_rule.hpp): exact (24 points, degree 2, exact moments),
   moment_fitting (Koschier's, fitted face and interface rules), subtets (the 4-point Gauss rule
   on every sub-tet), volume_ratio (the uncut tet's 4-point rule scaled), lattice (Paulus,
   n^3 sub-tet centroids) and regular (Kaufmann, n^3 cells on the bounding box). The program
   writes, into the --out folder:
     table1.csv  one row per (cut, level, rule, resolution, polynomial): value, reference, relative
                 error (against the polyhedron too, for the sphere), contributing points (nonzero
                 weight), seconds per element (building the piece's rule and summing the four
                 polynomials, best of repeats, the cut's geometry excluded: split_seconds has it);
     cost.csv    one row per (cut, level, rule, resolution): points, seconds, the largest relative
                 error of the four polynomials, for the error-vs-cost chart;
     table1.md   the table in Koschier's layout, his printed numbers beside ours.
   --quick runs every rule and cut on small resolutions (sphere levels 1 and 2) in a few seconds;
   it is a test.

   Read chapter 4 first. */

#include "kerf/cut/convex_cell.hpp"
#include "kerf/cut/tet_pieces.hpp"
#include "kerf/quadrature/koschier_moment_fitting.hpp"
#include "kerf/quadrature/piece_quadrature_rule.hpp"
#include "measure.hpp" // bench/measure.hpp: the command line and the timing shared with the benchmarks

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace quadrature_study {

using Corners = Eigen::Matrix<double, 4, 3>;
using kerf::CutTriangle;
using kerf::QuadratureRuleKind;

Corners unit_tet() {
  Corners X;
  X << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  return X;
}

/// The triangle (a, b, c), its corners reordered if need be so that its normal points along
/// `outward` (away from the blue piece).
CutTriangle oriented(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, const Eigen::Vector3d& outward,
                     int index) {
  if ((b - a).cross(c - a).dot(outward) >= 0.0) return {{a, b, c}, 0, index};
  return {{a, c, b}, 0, index};
}

// @sect3{The three cuts and their analytic integrals}

/// Koschier's four polynomials, in Table 1's order.
const std::array<const char*, 4> polynomial_names{"1", "x+y+z", "yz+xz+xy", "x^2+y^2+z^2"};

/// The four integrals from piece_moments' ten (1, x, y, z, x^2, y^2, z^2, xy, yz, xz).
std::array<double, 4> table_integrals(const Eigen::Matrix<double, 10, 1>& m) {
  return {m[0], m[1] + m[2] + m[3], m[7] + m[8] + m[9], m[4] + m[5] + m[6]};
}

/// The four integrals over the corner simplex S_t moved up by c.
std::array<double, 4> simplex_integrals(double t, double c) {
  return {std::pow(t, 3) / 6.0, std::pow(t, 4) / 8.0 + c * std::pow(t, 3) / 6.0, std::pow(t, 5) / 40.0 + c * std::pow(t, 4) / 12.0,
          std::pow(t, 5) / 20.0 + c * std::pow(t, 4) / 12.0 + c * c * std::pow(t, 3) / 6.0};
}

struct Cut {
  std::string name;
  int level = 0;                       ///< the sphere's tessellation level; 0 for the others
  std::vector<CutTriangle> triangles;  ///< those that may meet the tet
  std::array<double, 4> analytic{};    ///< the analytic integrals over the blue piece
  bool polyhedral = true;              ///< the analytic piece is the triangulated one (not the sphere)
};

Cut planar_cut() {
  const double t = 0.3;
  const Eigen::Vector3d n(1, 1, 1), x0 = Eigen::Vector3d::Constant(t / 3.0);
  const Eigen::Vector3d u = n.normalized().unitOrthogonal() * 10.0, v = n.normalized().cross(u);
  return {"planar", 0, {oriented(x0 - u - v, x0 + 2.0 * u - v, x0 - u + 2.0 * v, n, 0)}, simplex_integrals(t, 0.0), true};
}

Cut kinked_cut() {
  Cut cut{"kinked", 0, {}, {}, true};
  // x + y + z = 0.6 where z <= 0.3, as a quad in (x, z) coordinates: y = 0.6 - x - z.
  const auto on_slope = [](double x, double z) { return Eigen::Vector3d(x, 0.6 - x - z, z); };
  const Eigen::Vector3d n_slope(1, 1, 1), n_floor(0, 0, 1);
  const Eigen::Vector3d a = on_slope(-2, -1), b = on_slope(3, -1), c = on_slope(3, 0.3), d = on_slope(-2, 0.3);
  cut.triangles.push_back(oriented(a, b, c, n_slope, 0));
  cut.triangles.push_back(oriented(a, c, d, n_slope, 1));
  // z = 0.3 where x + y <= 0.3: a triangle whose edge from (2.3, -2) to (-2, 2.3) lies on x + y = 0.3.
  cut.triangles.push_back(oriented({2.3, -2.0, 0.3}, {-2.0, 2.3, 0.3}, {-2.0, -2.0, 0.3}, n_floor, 2));
  const std::array<double, 4> whole = simplex_integrals(0.6, 0.0), top = simplex_integrals(0.3, 0.3);
  for (int k = 0; k < 4; ++k) cut.analytic[static_cast<std::size_t>(k)] = whole[static_cast<std::size_t>(k)] - top[static_cast<std::size_t>(k)];
  return cut;
}

/// An icosphere of radius R about the origin: the icosahedron's faces split into four `level`
/// times, every new vertex pushed out onto the sphere; outward normals; turned by `rotation`.
std::vector<std::array<Eigen::Vector3d, 3>> icosphere(int level, double R, const Eigen::Matrix3d& rotation) {
  const double p = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Eigen::Vector3d> v{{-1, p, 0}, {1, p, 0}, {-1, -p, 0}, {1, -p, 0}, {0, -1, p}, {0, 1, p},
                                 {0, -1, -p}, {0, 1, -p}, {p, 0, -1}, {p, 0, 1}, {-p, 0, -1}, {-p, 0, 1}};
  const int faces[20][3] = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                            {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                            {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  std::vector<std::array<Eigen::Vector3d, 3>> triangles;
  for (const auto& f : faces) triangles.push_back({v[f[0]].normalized(), v[f[1]].normalized(), v[f[2]].normalized()});
  for (int l = 0; l < level; ++l) {
    std::vector<std::array<Eigen::Vector3d, 3>> finer;
    for (const auto& t : triangles) {
      const Eigen::Vector3d a = (t[0] + t[1]).normalized(), b = (t[1] + t[2]).normalized(), c = (t[2] + t[0]).normalized();
      finer.push_back({t[0], a, c});
      finer.push_back({a, t[1], b});
      finer.push_back({c, b, t[2]});
      finer.push_back({a, b, c});
    }
    triangles = std::move(finer);
  }
  for (auto& t : triangles) {
    for (Eigen::Vector3d& x : t) x = R * (rotation * x);
    if ((t[1] - t[0]).cross(t[2] - t[0]).dot(t[0]) < 0.0) std::swap(t[1], t[2]); // outward
  }
  return triangles;
}

Cut spherical_cut(int level) {
  const double R = 0.5, pi = std::numbers::pi;
  Cut cut{"spherical", level, {}, {pi * std::pow(R, 3) / 6.0, 3.0 * pi * std::pow(R, 4) / 16.0, std::pow(R, 5) / 5.0, pi * std::pow(R, 5) / 10.0},
          false};
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
  // Only the triangles whose bounding box meets the tet's ([0, 1]^3) can meet it.
  for (const auto& t : icosphere(level, R, rotation)) {
    const Eigen::Vector3d hi = t[0].cwiseMax(t[1]).cwiseMax(t[2]);
    if (hi.minCoeff() < 0.0) continue;
    cut.triangles.push_back({t, 0, static_cast<int>(cut.triangles.size())});
  }
  return cut;
}

// @sect3{One rule on one cut}

struct RuleCase {
  QuadratureRuleKind kind;
  int resolution = 0; ///< lattice: n; regular: n; 0 for the others
};

struct Sizes {
  std::vector<int> sphere_levels;
  std::vector<RuleCase> rules;
  kerf_measure::Repeats repeats;
};

Sizes study_sizes(bool quick) {
  Sizes s;
  const std::vector<RuleCase> common{{QuadratureRuleKind::exact, 0}, {QuadratureRuleKind::moment_fitting, 0},
                                     {QuadratureRuleKind::subtets, 0}, {QuadratureRuleKind::volume_ratio, 0}};
  s.rules = common;
  if (quick) {
    s.sphere_levels = {1, 2};
    s.rules.push_back({QuadratureRuleKind::lattice, 5});
    s.rules.push_back({QuadratureRuleKind::regular, 20});
    s.repeats = {1, 0.0, 0.2};
  } else {
    s.sphere_levels = {1, 2, 3, 4, 5, 6};
    for (int n : {5, 10, 20, 40}) s.rules.push_back({QuadratureRuleKind::lattice, n});
    for (int n : {25, 50, 100}) s.rules.push_back({QuadratureRuleKind::regular, n});
    s.repeats = {3, 0.2, 5.0};
  }
  return s;
}

std::string rule_label(const RuleCase& r) {
  std::string label = kerf::to_string(r.kind);
  if (r.resolution > 0) label += " n=" + std::to_string(r.resolution);
  return label;
}

double relative_error(double value, double reference) { return std::abs(value - reference) / std::abs(reference); }

struct Result {
  std::string cut;
  int level = 0;
  RuleCase rule;
  std::array<double, 4> value{}, analytic{}, polyhedron{};
  int points = 0;
  double seconds = 0.0, split_seconds = 0.0;
  int triangles = 0; ///< cut triangles given to the geometry
  kerf::KoschierFitReport fit; ///< moment_fitting only
  double max_error() const {
    double e = 0.0;
    for (std::size_t k = 0; k < 4; ++k) e = std::max(e, relative_error(value[k], analytic[k]));
    return e;
  }
  double max_error_vs_polyhedron() const {
    double e = 0.0;
    for (std::size_t k = 0; k < 4; ++k) e = std::max(e, relative_error(value[k], polyhedron[k]));
    return e;
  }
};

std::vector<Result> run_cut(const Cut& cut, const Sizes& sizes) {
  const Corners X = unit_tet();
  kerf::TetPieces pieces;
  const double split_seconds = kerf_measure::best_time(
      [&] {
        pieces = kerf::split_tet_by_triangles(X, cut.triangles);
      },
      sizes.repeats);
  if (pieces.num_pieces() < 2) throw std::runtime_error(cut.name + ": the cut leaves the tet in one piece");
  // Koschier's blue piece holds the corner (0,0,0), which no cut passes through.
  if (pieces.corner_pieces[0].size() != 1) throw std::runtime_error(cut.name + ": the cut passes through the corner (0,0,0)");
  const int blue = pieces.corner_pieces[0].front();
  // The triangulated piece's own integrals: Gauss on its sub-tets is exact for quadratics.
  kerf::PieceRuleOptions gauss;
  const std::array<double, 4> polyhedron =
      table_integrals(kerf::piece_moments(kerf::piece_quadrature_rule(QuadratureRuleKind::subtets, X, cut.triangles, pieces, blue, gauss)));
  std::vector<Result> results;
  for (const RuleCase& r : sizes.rules) {
    // The sampled rules test every sample against the cells' boxes: samples x cells work. Past
    // 2e9 (the finest spheres at the finest grids) a run would take minutes; we skip it.
    if (r.resolution > 0 && std::pow(static_cast<double>(r.resolution), 3) * static_cast<double>(pieces.cells.size()) > 2e9) {
      std::printf("%-9s L%d %-20s skipped: %zu cells\n", cut.name.c_str(), cut.level, rule_label(r).c_str(), pieces.cells.size());
      continue;
    }
    kerf::PieceRuleOptions options;
    options.degree = 2;
    if (r.kind == QuadratureRuleKind::lattice) options.lattice_divisions = r.resolution;
    if (r.kind == QuadratureRuleKind::regular) options.regular_cells = r.resolution;
    Result result{cut.name, cut.level, r, {}, cut.analytic, polyhedron, 0, 0.0, split_seconds, static_cast<int>(cut.triangles.size()), {}};
    kerf::PieceQuadratureRule rule;
    result.seconds = kerf_measure::best_time(
        [&] {
          rule = kerf::piece_quadrature_rule(r.kind, X, cut.triangles, pieces, blue, options);
          result.value = table_integrals(kerf::piece_moments(rule));
        },
        sizes.repeats);
    result.points = kerf::count_points(rule);
    if (r.kind == QuadratureRuleKind::moment_fitting) kerf::koschier_moment_fitting_rule(X, cut.triangles, pieces, blue, 2, &result.fit);
    results.push_back(result);
  }
  return results;
}

// @sect3{Koschier's printed numbers, and the files}

/// Koschier et al. 2017, Table 1: his moment fitting (24 QP) and regular sampling (50^3)
/// relative errors and the latter's point counts, per cut and polynomial.
struct Printed {
  std::array<double, 4> koschier, regular;
  int regular_points;
};
const std::map<std::string, Printed> koschier_table1{
    {"planar", {{3.32e-5, 4.43e-5, 5.54e-5, 5.54e-5}, {4.44e-3, 4.44e-3, 9.78e-1, 5.00e-1}, 560}},
    {"kinked", {{2.99e-6, 6.50e-6, 1.26e-5, 1.38e-5}, {4.94e-4, 4.89e-4, 2.50e-3, 1.10e-4}, 3795}},
    {"spherical", {{3.88e-4, 5.15e-4, 6.43e-4, 6.46e-4}, {4.62e-3, 6.23e-3, 7.60e-3, 7.71e-3}, 8219}},
};

void write_csv(const std::vector<Result>& results, const std::filesystem::path& out) {
  std::ofstream csv(out / "table1.csv"), cost(out / "cost.csv");
  csv << "cut,level,rule,resolution,polynomial,value,analytic,rel_error,polyhedron,rel_error_vs_polyhedron,points,seconds,split_seconds,"
         "interface_rank,interface_points,interface_condition\n";
  cost << "cut,level,rule,resolution,label,points,seconds,max_rel_error,max_rel_error_vs_polyhedron\n";
  csv.precision(17);
  cost.precision(6);
  for (const Result& r : results) {
    for (std::size_t k = 0; k < 4; ++k)
      csv << r.cut << ',' << r.level << ',' << kerf::to_string(r.rule.kind) << ',' << r.rule.resolution << ',' << polynomial_names[k] << ','
          << r.value[k] << ',' << r.analytic[k] << ',' << relative_error(r.value[k], r.analytic[k]) << ',' << r.polyhedron[k] << ','
          << relative_error(r.value[k], r.polyhedron[k]) << ',' << r.points << ',' << r.seconds << ',' << r.split_seconds << ','
          << r.fit.interface_rank << ',' << r.fit.interface_points << ',' << r.fit.interface_condition << '\n';
    cost << r.cut << ',' << r.level << ',' << kerf::to_string(r.rule.kind) << ',' << r.rule.resolution << ',' << rule_label(r.rule) << ','
         << r.points << ',' << r.seconds << ',' << r.max_error() << ',' << r.max_error_vs_polyhedron() << '\n';
  }
}

std::string sci(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2e", x);
  return text;
}

void write_markdown(const std::vector<Result>& results, int table_level, const std::filesystem::path& out) {
  std::ofstream md(out / "table1.md");
  md << "# Koschier Table 1 again: the unit tet's corner piece, four polynomials\n\n"
     << "Relative errors against the analytic integrals (the sphere: the analytic ball's octant; the tessellated polyhedron's\n"
     << "own errors are in the second table). \"K\" columns are Koschier's printed numbers (his 24-point moment fitting and\n"
     << "his regular sampling, 50^3, with its point count). Ours: exact = 24-point moment fitting with exact moments;\n"
     << "K-fit = Koschier's moment fitting, fitted face and interface rules; subtets = 4-point Gauss on every sub-tet;\n"
     << "regular = 50^3 cell centres on the bounding box; #QP = points with nonzero weight. Sphere: icosphere level "
     << table_level << ".\n"
     << "Machine: " << kerf_measure::cpu_model() << ", " << kerf_measure::now_text() << ".\n\n"
     << "Cuts (examples/04_quadrature_study.cpp): planar = the corner piece x + y + z <= 0.3 (the cut one large triangle);\n"
     << "kinked = OURS, Koschier's being unknown: {x + y + z <= 0.6, z <= 0.3}, two planes meeting along x + y = 0.3, z = 0.3\n"
     << "(so K's kinked numbers are for another geometry); spherical = an icosphere of radius 0.5 about the corner (0,0,0).\n"
     << "Geometry: every cut through split_tet_by_triangles, the pieces Kerf integrates everywhere else.\n\n"
     << "| cut | h | K (24 QP) | exact | K-fit | subtets | vol. ratio | K reg. | K #QP | regular | #QP |\n"
     << "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  const auto find = [&](const std::string& cut, int level, QuadratureRuleKind kind, int resolution) -> const Result* {
    for (const Result& r : results)
      if (r.cut == cut && r.level == level && r.rule.kind == kind && r.rule.resolution == resolution) return &r;
    return nullptr;
  };
  int regular_n = 0;
  for (const Result& r : results)
    if (r.rule.kind == QuadratureRuleKind::regular && (regular_n == 0 || std::abs(r.rule.resolution - 50) < std::abs(regular_n - 50)))
      regular_n = r.rule.resolution;
  for (const std::string cut : {"planar", "kinked", "spherical"}) {
    const int level = cut == "spherical" ? table_level : 0;
    const Printed& k = koschier_table1.at(cut);
    for (std::size_t p = 0; p < 4; ++p) {
      md << "| " << cut << " | " << polynomial_names[p] << " | " << sci(k.koschier[p]);
      for (QuadratureRuleKind kind : {QuadratureRuleKind::exact, QuadratureRuleKind::moment_fitting, QuadratureRuleKind::subtets,
                                      QuadratureRuleKind::volume_ratio}) {
        const Result* r = find(cut, level, kind, 0);
        md << " | " << (r ? sci(relative_error(r->value[p], r->analytic[p])) : "-");
      }
      md << " | " << sci(k.regular[p]) << " | " << k.regular_points;
      const Result* r = find(cut, level, QuadratureRuleKind::regular, regular_n);
      md << " | " << (r ? sci(relative_error(r->value[p], r->analytic[p])) : "-") << " | " << (r ? std::to_string(r->points) : "-")
         << " |\n";
    }
  }
  md << "\nRegular sampling here: n = " << regular_n << ".\n\n"
     << "## The sphere: against the ball and against the tessellated polyhedron\n\n"
     << "| level | triangles in the tet's box | rule | h | vs ball | vs polyhedron | #QP |\n| --- | --- | --- | --- | --- | --- | --- |\n";
  for (const Result& r : results) {
    if (r.cut != "spherical" || r.rule.resolution != 0 || r.rule.kind == QuadratureRuleKind::volume_ratio) continue;
    for (std::size_t p = 0; p < 4; ++p)
      md << "| " << r.level << " | " << r.triangles << " | " << kerf::to_string(r.rule.kind) << " | " << polynomial_names[p] << " | "
         << sci(relative_error(r.value[p], r.analytic[p])) << " | " << sci(relative_error(r.value[p], r.polyhedron[p])) << " | "
         << r.points << " |\n";
  }
  md << "\n## Cost: points and seconds per element (best of repeats; the cut's geometry, split_tet_by_triangles, apart)\n\n"
     << "| cut | level | rule | #QP | seconds | largest relative error (vs analytic) | geometry seconds |\n"
     << "| --- | --- | --- | --- | --- | --- | --- |\n";
  for (const Result& r : results)
    md << "| " << r.cut << " | " << r.level << " | " << rule_label(r.rule) << " | " << r.points << " | " << sci(r.seconds) << " | "
       << sci(r.max_error()) << " | " << sci(r.split_seconds) << " |\n";
  md << "\nKoschier's moment fitting (K-fit): interface rank / points / condition of eq. 20 per cut:\n\n";
  for (const Result& r : results)
    if (r.rule.kind == QuadratureRuleKind::moment_fitting)
      md << "- " << r.cut << (r.cut == "spherical" ? " level " + std::to_string(r.level) : "") << ": rank " << r.fit.interface_rank << " of "
         << r.fit.interface_basis << " fields, " << r.fit.interface_points << " points (" << r.fit.interface_triangles
         << " sub-triangles), condition " << sci(r.fit.interface_condition) << "\n";
}

} // namespace quadrature_study

int main(int argc, char** argv) {
  const auto options =
      kerf_measure::parse_run_options(argc, argv, "04_quadrature_study [--quick] [--out DIR]", "output/quadrature_study");
  if (!options) return 2;
  try {
    namespace qs = quadrature_study;
    std::filesystem::create_directories(options->out);
    std::cout << "Kerf chapter 4 study" << (options->quick ? " (quick)" : "") << " on " << kerf_measure::cpu_model() << "\n";
    const qs::Sizes sizes = qs::study_sizes(options->quick);
    std::vector<qs::Cut> cuts{qs::planar_cut(), qs::kinked_cut()};
    for (int level : sizes.sphere_levels) cuts.push_back(qs::spherical_cut(level));
    std::vector<qs::Result> results;
    for (const qs::Cut& cut : cuts) {
      const std::vector<qs::Result> these = qs::run_cut(cut, sizes);
      for (const qs::Result& r : these) {
        std::printf("%-9s L%d %-20s #QP %7d  %9.2e s  max rel. error %.2e", r.cut.c_str(), r.level, qs::rule_label(r.rule).c_str(),
                    r.points, r.seconds, r.max_error());
        if (!cut.polyhedral) {
          double e = 0.0;
          for (std::size_t k = 0; k < 4; ++k) e = std::max(e, qs::relative_error(r.value[k], r.polyhedron[k]));
          std::printf("  (vs polyhedron %.2e)", e);
        }
        std::printf("\n");
      }
      results.insert(results.end(), these.begin(), these.end());
    }
    qs::write_csv(results, options->out);
    qs::write_markdown(results, sizes.sphere_levels.back(), options->out);
  } catch (const std::exception& error) {
    std::cerr << "04_quadrature_study: " << error.what() << '\n';
    return 1;
  }
  return 0;
}
