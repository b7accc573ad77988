/* Kerf, chapter 5 study: integrating the crack-tip integrands over a tet the front crosses.
   Error against the number of points for sub-tets refined k times with Gauss rules, and for the
   collapsed rule with n points per direction (quadrature/front_quadrature.hpp).

   Build:   cmake --preset release && cmake --build --preset release --target 05_front_quadrature_study

   Sample runs:
     05_front_quadrature_study --quick --out output/front_quadrature_study_quick
     05_front_quadrature_study --out figures/05_crack_tip

   Description: the front is the z-axis, the cut the half-plane y = 0, x < 0 (a rectangle through
   find_crack_fronts and split_tet_by_triangles, as the model will see it), so that
   r = sqrt(x^2 + y^2) and theta = atan2(y, x). Two tets:
     crossed   the front enters through one face and leaves through another, off every edge;
     grazing   the front passes 1e-3 of the tet's size from one of its edges (a front near an edge,
               the hard case for sub-tets: their Gauss points sit close to the singular line).
   The integrands are those of the branch-enriched stiffness and loads (Paulus et al., section 3.5): 1/sqrt(r),
   1/r, sqrt(r) sin(theta/2) (F_1, discontinuous across the cut), cos(theta/2)/sqrt(r) (a
   gradient) and sin(3 theta/2)^2 / r (a product of gradients). The reference is the integral in
   cylindrical coordinates about the front (quadrature/cylindrical_tet_integral.hpp, 32 points per
   part, converged to about 1e-13). The rules:
     subtets   refined_subtet_rule: the piece's sub-tets refined k = 0 .. 4 times (8^k each), with
               the Gauss rule of degree 2 (4 points) or 5 (27 points) on each;
     collapsed front_collapsed_rule with n = 1 .. 8 points per direction.
   The program writes front_quadrature.csv (one row per tet, rule, parameter, integrand: points,
   value, reference, relative error) into the --out folder and prints a summary. --quick stops
   at k = 2 and n = 5 (a test).

   Read chapter 5 first. */

#include "kerf/cut/crack_front.hpp"
#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/cut/tet_pieces.hpp"
#include "kerf/quadrature/cylindrical_tet_integral.hpp"
#include "kerf/quadrature/front_quadrature.hpp"
#include "kerf/quadrature/gauss_piece_rules.hpp"
#include "measure.hpp" // bench/measure.hpp: the command line shared with the benchmarks

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

namespace front_quadrature_study {

using Corners = Eigen::Matrix<double, 4, 3>;

struct Integrand {
  std::string name;
  double alpha;
  std::function<double(double)> g;
};

std::vector<Integrand> integrands() {
  return {{"1/sqrt(r)", -0.5, [](double) { return 1.0; }},
          {"1/r", -1.0, [](double) { return 1.0; }},
          {"sqrt(r)sin(t/2)", 0.5, [](double t) { return std::sin(t / 2); }},
          {"cos(t/2)/sqrt(r)", -0.5, [](double t) { return std::cos(t / 2); }},
          {"sin(3t/2)^2/r", -1.0, [](double t) { return std::pow(std::sin(1.5 * t), 2); }}};
}

// A tet cut by the half-plane y = 0, x < 0, as the model sees it: its pieces and its fronts.
struct Case {
  std::string name;
  Corners X;
  kerf::CrackFronts fronts;
  kerf::TetPieces pieces;
};

Case make_case(const std::string& name, const Corners& X) {
  Case c{name, X, {}, {}};
  kerf::TetMesh mesh;
  mesh.nodes = X;
  mesh.tets.resize(1, 4);
  mesh.tets << 0, 1, 2, 3;
  const kerf::CutSurfaces cuts({kerf::rectangle_surface(kerf::RectangleCut({-5, 0, -5}, {0, 0, 10}, {5, 0, 0}))});
  c.fronts = kerf::find_crack_fronts(mesh, cuts);
  c.pieces = kerf::split_tet_by_triangles(X, cuts.triangles_meeting_tet(X));
  if (c.fronts.polylines.size() != 1 || c.pieces.num_pieces() != 1)
    throw std::runtime_error(name + ": the front does not cross the tet as the study expects");
  return c;
}

std::vector<Case> cases() {
  Corners crossed, grazing;
  crossed << -0.55, -0.45, -0.12, 0.72, -0.38, 0.03, 0.08, 0.78, -0.02, 0.04, -0.06, 0.95;
  // The edge from (1e-3, -0.5, 0) to (1e-3, 0.5, 0.1)... passes 1e-3 from the z-axis at y = 0.
  grazing << 1e-3, -0.5, 0.0, 1e-3, 0.5, 0.1, -0.8, 0.1, 0.6, 0.7, 0.05, 0.9;
  return {make_case("crossed", crossed), make_case("grazing", grazing)};
}

struct Row {
  std::string tet, rule, integrand;
  int parameter = 0;
  int points = 0;
  double value = 0.0, reference = 0.0;
  double error() const { return std::abs(value - reference) / std::abs(reference); }
};

// r^alpha g(theta) with r and theta about the front, the z-axis.
double about_z_axis(const Integrand& f, const Eigen::Vector3d& x) {
  return std::pow(std::hypot(x.x(), x.y()), f.alpha) * f.g(std::atan2(x.y(), x.x()));
}

std::vector<Row> run(const Case& c, bool quick) {
  std::vector<Row> rows;
  const std::vector<Integrand> list = integrands();
  std::vector<double> reference;
  for (const Integrand& f : list)
    reference.push_back(kerf::cylindrical_tet_integral(c.X, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(),
                                                       Eigen::Vector3d::UnitZ(), f.alpha, f.g, 32));
  const auto add = [&](const std::string& rule_name, int parameter, const kerf::PieceQuadratureRule& rule) {
    for (std::size_t k = 0; k < list.size(); ++k)
      rows.push_back({c.name, rule_name, list[k].name, parameter, static_cast<int>(rule.points.size()),
                      kerf::integrate(rule, [&](const Eigen::Vector3d& x) { return about_z_axis(list[k], x); }), reference[k]});
  };
  for (const int degree : {2, 5})
    for (int k = 0; k <= (quick ? 2 : 4); ++k)
      add("subtets_degree" + std::to_string(degree), k, kerf::refined_subtet_rule(c.pieces, 0, degree, k));
  for (int n = 1; n <= (quick ? 5 : 8); ++n) add("collapsed", n, kerf::front_collapsed_rule(c.X, c.pieces, 0, c.fronts, n));
  return rows;
}

void write_csv(const std::vector<Row>& rows, const std::filesystem::path& out) {
  std::ofstream csv(out / "front_quadrature.csv");
  csv << "tet,rule,parameter,integrand,points,value,reference,relative_error\n";
  csv.precision(17);
  for (const Row& r : rows)
    csv << r.tet << ',' << r.rule << ',' << r.parameter << ',' << r.integrand << ',' << r.points << ',' << r.value << ','
        << r.reference << ',' << r.error() << '\n';
  if (!csv) throw std::runtime_error("cannot write " + (out / "front_quadrature.csv").string());
}

} // namespace front_quadrature_study

int main(int argc, char** argv) {
  const auto options = kerf_measure::parse_run_options(argc, argv, "05_front_quadrature_study [--quick] [--out DIR]",
                                                       "output/front_quadrature_study");
  if (!options) return 2;
  try {
    namespace fq = front_quadrature_study;
    std::filesystem::create_directories(options->out);
    std::vector<fq::Row> rows;
    for (const fq::Case& c : fq::cases()) {
      const std::vector<fq::Row> these = fq::run(c, options->quick);
      // The largest relative error over the integrands, per rule and parameter.
      for (std::size_t i = 0; i < these.size();) {
        double worst = 0.0;
        std::size_t j = i;
        for (; j < these.size() && these[j].rule == these[i].rule && these[j].parameter == these[i].parameter; ++j)
          worst = std::max(worst, these[j].error());
        std::printf("%-8s %-16s %d  %8d points  largest relative error %.2e\n", c.name.c_str(), these[i].rule.c_str(),
                    these[i].parameter, these[i].points, worst);
        i = j;
      }
      rows.insert(rows.end(), these.begin(), these.end());
    }
    fq::write_csv(rows, options->out);
  } catch (const std::exception& error) {
    std::cerr << "05_front_quadrature_study: " << error.what() << '\n';
    return 1;
  }
  return 0;
}
