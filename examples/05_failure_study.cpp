/* Kerf, chapter 5 study: where crack-tip enrichment fails, the condition number of the static
   stiffness with the branch DOFs.

   Build:   cmake --preset release && cmake --build --preset release --target 05_failure_study

   Sample runs:
     05_failure_study --quick --out output/failure_study_quick
     05_failure_study --out figures/05_crack_tip

   Description: Tet4 boxes (each cell six tets, mesh/box_mesh.hpp), E = 1e6 Pa, nu = 0.3, the
   bottom face z = 0 clamped (every DOF of its nodes, their enrichments too), cut by a straight
   crack through the whole thickness that ends inside along its front. We assemble the linear
   XFEM stiffness K_ff (branch functions integrated by the collapsed rule on the front tets,
   front_quadrature.hpp) and write its 2-norm condition number (dense eigenvalues,
   dynamics/stiffness_conditioning.hpp) bare, Jacobi-scaled, with Koschier's bilateral diagonal
   (eqs. 23-27 on the sign DOFs, 1 on the branch DOFs), in the part basis then Jacobi-scaled,
   and with Bechet et al.'s node blocks (the Cholesky factor of each node's diagonal block).

   Three sweeps, each a series of rows in failures.csv:
     radius      the geometric enrichment radius r_e = 0 (topological), 1, 2, 3, 4 element sizes h,
                 on [-0.45, 0.45]^2 x [0, 0.2] in 9 x 9 x 2 cells (h = 0.1): the crack y = 0,
                 x < 0, its front x = y = 0 along z through the middle of a row of elements;
     node_ahead  the front nearing the interior node (0, 0, 0.1) of [-0.2, 0.2]^2 x [0, 0.2]
     node_behind (4 x 4 x 2 cells, h = 0.1), topological rule: the front in a direction along
                 no mesh line, c ~ (0.3, -0.2, 1), at the distance d from the node, the node at
                 the polar angle 60 degrees (ahead of the front, above the cut's plane) or 150
                 degrees (behind it, so the cut passes d / 2 from the node);
     face_before the front x = x_f, y = 0.05 along z (the crack y = 0.05, x < x_f) nearing the
     face_after  plane of faces x = 0 of the same box, from the cut's side (x_f = -d) or just
                 past it (x_f = +d);
   with d / h = 1e-1, 1e-2, 1e-3 (not further: the collapsed rule grades the sub-tets near the
   front, and a front 1e-3 h from a node already makes 1.4 million points; at 1e-5 h a model
   takes minutes). failures_slopes.csv holds the growth exponents: p of kappa ~ (r_e / h)^p over
   r_e = 1..4 h, and p of kappa ~ (d / h)^-p over 1e-3 <= d / h <= 1e-1 (the points below 1e14,
   where the eigenvalues still mean something).
   --quick runs r_e = 0, 1 on a 5 x 5 x 1 box and the face sweeps at d / h = 1e-1; it is a test.

   Read chapter 5 first. */

#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/dynamics/stiffness_conditioning.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/quadrature/gauss_piece_rules.hpp"
#include "kerf/xfem/branch_enrichment.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"
#include "measure.hpp" // bench/measure.hpp: the command line shared with the benchmarks

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace failure_study {

const double not_a_number = std::numeric_limits<double>::quiet_NaN();
const kerf::LinearMaterial material{1e6, 0.3, 1000.0};
const double h = 0.1; // the cells' size in every sweep (m)

kerf::PieceQuadratureRule subtets(const Eigen::Matrix<double, 4, 3>&, const kerf::TetPieces& pieces, int piece, int degree) {
  return kerf::subtet_rule(pieces, piece, degree);
}

// A straight front: a point of it and its frame, a ahead, b the cut's normal, c = a x b along it.
struct StraightFront {
  Eigen::Vector3d origin, a, b, c;
  StraightFront(const Eigen::Vector3d& o, const Eigen::Vector3d& ahead, const Eigen::Vector3d& normal)
      : origin(o), a(ahead.normalized()), b(normal.normalized()), c(a.cross(b)) {}
};

// The half-plane behind the front (behind = -a), as a rectangle reaching past the box:
// edge1 x edge2 = c x a = b, its normal.
kerf::TriangleSurface half_plane_behind(const StraightFront& front) {
  return kerf::rectangle_surface(kerf::RectangleCut(front.origin - 2.0 * front.c - 2.0 * front.a, 4.0 * front.c, 2.0 * front.a));
}

// The box cut behind `front`, its bottom clamped, measured.
kerf::StiffnessConditioning measure(const kerf::TetMesh& mesh, const StraightFront& front, kerf::TipEnrichmentRule rule,
                                    double radius) {
  const kerf::CutSurfaces cuts({half_plane_behind(front)});
  const kerf::MeshPieces pieces = kerf::cut_mesh_into_pieces(mesh, cuts);
  const kerf::CrackFronts fronts = kerf::find_crack_fronts(mesh, cuts);
  const kerf::BranchEnrichment branch = kerf::make_branch_enrichment(mesh, pieces, fronts, rule, radius);
  // Cheaper rules than the defaults (3 points per direction, degree 4, graded once): kappa does
  // not see the quadrature's last digits, and a front near a node already costs a million points.
  const kerf::CrackTipFunctions functions{branch, fronts, kerf::FrontRule::collapsed, 3, 4, 1};
  const kerf::CutXfemModel model(mesh, material, pieces, branch.sign, subtets, &functions);
  kerf::DirichletNodes bottom;
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v)
    if (std::abs(mesh.nodes(v, 2)) < 1e-12) bottom.nodes.push_back(static_cast<int>(v));
  // Eq. 22 with epsilon 0: only enrichments without any volume are constrained.
  return kerf::stiffness_conditioning(model, kerf::make_cut_xfem_dof_map(model, {bottom}, 0.0));
}

struct Row {
  std::string series;
  double radius_over_h = not_a_number, d_over_h = not_a_number;
  kerf::StiffnessConditioning c;
};

// The front of the node sweeps: at the distance d h from the node (0, 0, 0.1), the node at polar angle phi.
StraightFront node_front(double d, double phi) {
  const Eigen::Vector3d c = Eigen::Vector3d(0.3, -0.2, 1.0).normalized();
  const Eigen::Vector3d b = (Eigen::Vector3d::UnitY() - c.y() * c).normalized();
  const Eigen::Vector3d a = b.cross(c);
  const Eigen::Vector3d node(0.0, 0.0, 0.1);
  return StraightFront(node - d * h * (std::cos(phi) * a + std::sin(phi) * b), a, b);
}

// Least-squares slope of log kappa against log x over the rows of `series` with x in [lo, hi]
// and kappa below 1e14.
double slope(const std::vector<Row>& rows, const std::string& series, double Row::*x, double kerf::StiffnessConditioning::*kappa,
             double lo, double hi) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const Row& r : rows) {
    const double k = r.c.*kappa;
    if (r.series != series || !(r.*x >= lo && r.*x <= hi) || !(k < 1e14)) continue;
    const double lx = std::log(r.*x), ly = std::log(k);
    n += 1, sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
  }
  if (n < 2) return not_a_number;
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

} // namespace failure_study

int main(int argc, char** argv) {
  const auto options = kerf_measure::parse_run_options(argc, argv, "05_failure_study [--quick] [--out DIR]", "output/failure_study");
  if (!options) return 2;
  try {
    namespace fs = failure_study;
    std::filesystem::create_directories(options->out);
    std::cout << "Kerf chapter 5 failure study" << (options->quick ? " (quick)" : "") << " on " << kerf_measure::cpu_model() << ", "
              << kerf_measure::now_text() << "\n";
    std::vector<fs::Row> rows;
    // Each row is written as soon as it is measured (a front near a node costs a million
    // quadrature points and minutes): an interrupted run keeps what it measured.
    std::ofstream csv(options->out / "failures.csv");
    csv << "series,radius_over_h,d_over_h,free_dofs,branch_nodes,sign_enrichments,smallest_fraction,plain,jacobi,koschier,part_jacobi,"
           "node_block\n";
    csv.precision(10);
    const auto add = [&](fs::Row row) {
      const fs::Row& r = rows.emplace_back(std::move(row));
      csv << r.series << ',' << r.radius_over_h << ',' << r.d_over_h << ',' << r.c.free_dofs << ',' << r.c.branch_nodes << ','
          << r.c.sign_enrichments << ',' << r.c.smallest_fraction << ',' << r.c.plain << ',' << r.c.jacobi << ',' << r.c.koschier << ','
          << r.c.part_jacobi << ',' << r.c.node_block << std::endl;
      std::cout << r.series << " r_e/h " << r.radius_over_h << " d/h " << r.d_over_h << ": " << r.c.free_dofs << " DOFs, kappa " << r.c.plain
                << ", node blocks " << r.c.node_block << std::endl;
    };

    // The radius sweep.
    {
      const int cells = options->quick ? 5 : 9;
      const double half = 0.5 * cells * fs::h;
      const kerf::TetMesh mesh = kerf::make_box_mesh({-half, -half, 0.0}, {half, half, options->quick ? 0.1 : 0.2},
                                                     {cells, cells, options->quick ? 1 : 2});
      const fs::StraightFront front = fs::StraightFront({0, 0, 0}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY());
      for (int k = 0; k <= (options->quick ? 1 : 4); ++k) {
        const auto rule = k == 0 ? kerf::TipEnrichmentRule::topological : kerf::TipEnrichmentRule::geometric;
        add({"radius", double(k), fs::not_a_number, fs::measure(mesh, front, rule, k * fs::h)});
      }
    }

    // The distance sweeps.
    {
      const kerf::TetMesh mesh = kerf::make_box_mesh({-0.2, -0.2, 0.0}, {0.2, 0.2, 0.2}, {4, 4, 2});
      std::vector<double> distances;
      if (options->quick) distances = {1e-1};
      else
        for (int k = 1; k <= 3; ++k) distances.push_back(std::pow(10.0, -double(k)));
      for (const double d : distances) {
        const auto topological = kerf::TipEnrichmentRule::topological;
        if (!options->quick) {
          add({"node_ahead", fs::not_a_number, d, fs::measure(mesh, fs::node_front(d, M_PI / 3.0), topological, 0.0)});
          add({"node_behind", fs::not_a_number, d, fs::measure(mesh, fs::node_front(d, 5.0 * M_PI / 6.0), topological, 0.0)});
        }
        const auto face_front = [](double x_f) {
          return fs::StraightFront({x_f, 0.05, 0.0}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY());
        };
        add({"face_before", fs::not_a_number, d, fs::measure(mesh, face_front(-d * fs::h), topological, 0.0)});
        add({"face_after", fs::not_a_number, d, fs::measure(mesh, face_front(d * fs::h), topological, 0.0)});
      }
    }

    std::printf("%-12s %6s %9s %5s %4s %4s %10s %11s %11s %11s %11s %11s\n", "series", "r_e/h", "d/h", "dofs", "NB", "NS", "min v",
                "plain", "jacobi", "koschier", "part+jac", "node block");
    for (const fs::Row& r : rows)
      std::printf("%-12s %6.0f %9.2e %5d %4d %4d %10.3e %11.4e %11.4e %11.4e %11.4e %11.4e\n", r.series.c_str(), r.radius_over_h,
                  r.d_over_h, r.c.free_dofs, r.c.branch_nodes, r.c.sign_enrichments, r.c.smallest_fraction, r.c.plain, r.c.jacobi,
                  r.c.koschier, r.c.part_jacobi, r.c.node_block);

    using C = kerf::StiffnessConditioning;
    const std::vector<std::pair<std::string, double C::*>> variants{
        {"plain", &C::plain}, {"jacobi", &C::jacobi}, {"koschier", &C::koschier}, {"part_jacobi", &C::part_jacobi}, {"node_block", &C::node_block}};
    std::ofstream slopes(options->out / "failures_slopes.csv");
    slopes << "series,variant,x_min,x_max,exponent\n";
    for (const auto& [name, kappa] : variants) {
      const double p = fs::slope(rows, "radius", &fs::Row::radius_over_h, kappa, 1.0, 4.0);
      slopes << "radius," << name << ",1,4," << p << '\n';
      std::printf("radius: kappa_%s ~ (r_e / h)^%.3f over r_e = 1..4 h\n", name.c_str(), p);
    }
    for (const std::string series : {"node_ahead", "node_behind", "face_before", "face_after"})
      for (const auto& [name, kappa] : variants) {
        const double p = -fs::slope(rows, series, &fs::Row::d_over_h, kappa, 1e-3, 1e-1);
        slopes << series << ',' << name << ",1e-3,1e-1," << p << '\n';
        std::printf("%s: kappa_%s ~ (d / h)^-%.3f over d / h = 1e-3..1e-1\n", series.c_str(), name.c_str(), p);
      }
  } catch (const std::exception& error) {
    std::cerr << "05_failure_study: " << error.what() << '\n';
    return 1;
  }
  return 0;
}
