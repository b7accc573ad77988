/* Kerf, chapter 6 study: the conditioning of the implicit step's matrix when a cut nears the
   nodes, Koschier's Fig. 14 again (Paper 002, section 6, eqs. 22-27, and section 7).

   Build:   cmake --preset release && cmake --build --preset release --target 06_conditioning_study

   Sample runs:
     06_conditioning_study --quick --out output/conditioning_study_quick
     06_conditioning_study --out figures/06_newmark

   Description: the cube [-1, 1]^3 as five Tet4 (mesh/five_tet_cube.hpp; a central tet and four
   corner tets), free (no Dirichlet condition), E = 1e6 Pa, nu = 0.3, rho = 1000 kg/m^3, cut by
   the plane x = x_c with normal (1, 0, 0), as in the paper:

         z
         |  +-------+          the plane x = x_c sweeps from x = -1 to x = 1;
         | /|  :   /|          the pieces on its left side shrink to slivers as
         |/ |  :  / |          x_c -> -1 (a distance d = 1 + x_c), on its right
         +-------+  |          side as x_c -> +1 (d = 1 - x_c)
         |  +--:-|--+
         | /   : | /
         |/    : |/
         +-------+---- x
              x_c

   We assemble A = M + dt^2 K (consistent XFEM mass, linear XFEM stiffness, dt = 1e-3 s: the
   matrix of a backward Euler step without damping, the paper's choice) and write its 2-norm
   condition number (dense eigenvalues, dynamics/newton_matrix_conditioning.hpp) for seven
   variants: bare; Jacobi-scaled; with Koschier's bilateral preconditioner (eqs. 23-27, v for V
   in eq. 26); bare after eq. 22's constraining (epsilon = 1e-9); preconditioned and
   constrained; and, Kerf's addition, in the part basis (dynamics/part_basis.hpp) with Jacobi
   scaling, without and with eq. 22. Files in --out:
     conditioning_sweep.csv  one row per cut position: x_c, d (distance to the nearer face),
                 the enrichments, how many eq. 22 constrains, the smallest V_enr / V_supp and
                 the seven condition numbers; and the uncut cube as the row x_c = NaN;
     conditioning_slopes.csv the growth exponents p of kappa ~ d^-p as d -> 0, fitted by least
                 squares on log kappa against log d on each side's points: 1e-4 <= d <= 1e-2 for
                 the unconstrained variants, 1e-8 <= d <= 1e-3 for the constrained ones.
   --quick runs fewer positions in a second; it is a test.

   Read chapter 6 first. */

#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/rectangle_cut.hpp"
#include "kerf/dynamics/newton_matrix_conditioning.hpp"
#include "kerf/fem/linear_material.hpp"
#include "kerf/mesh/five_tet_cube.hpp"
#include "kerf/quadrature/gauss_piece_rules.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"
#include "kerf/xfem/surface_enrichment.hpp"
#include "measure.hpp" // bench/measure.hpp: the command line shared with the benchmarks

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

namespace conditioning_study {

const double not_a_number = std::numeric_limits<double>::quiet_NaN();
const kerf::LinearMaterial material{1e6, 0.3, 1000.0}; // Paper 002 section 7
const double dt = 1e-3;                                 // s

// Sub-tetrahedra with Gauss rules of the degree asked for: exact for the mass and stiffness integrands.
kerf::PieceQuadratureRule subtets(const Eigen::Matrix<double, 4, 3>&, const kerf::TetPieces& pieces, int piece, int degree) {
  return kerf::subtet_rule(pieces, piece, degree);
}

// The plane x = x_c as a square of two triangles reaching past the cube, normal +x.
kerf::TriangleSurface cut_plane(double x_c) {
  return kerf::rectangle_surface(kerf::RectangleCut({x_c, -2.0, -2.0}, {0.0, 4.0, 0.0}, {0.0, 0.0, 4.0}));
}

// The cube cut at x_c (no cut for NaN), measured.
kerf::NewtonMatrixConditioning measure(double x_c) {
  const kerf::TetMesh mesh = kerf::make_five_tet_cube({-1, -1, -1}, {1, 1, 1});
  std::vector<kerf::TriangleSurface> surfaces;
  if (!std::isnan(x_c)) surfaces.push_back(cut_plane(x_c));
  const kerf::CutSurfaces cuts(std::move(surfaces));
  const kerf::MeshPieces pieces = kerf::cut_mesh_into_pieces(mesh, cuts);
  const kerf::SurfaceEnrichment enrichment = kerf::make_surface_enrichment(mesh, pieces);
  const kerf::CutXfemModel model(mesh, material, pieces, enrichment, subtets);
  return kerf::newton_matrix_conditioning(model, material.density, dt, subtets);
}

// The cut positions (x_c, d): a uniform sweep over the cube, then log-spaced distances d from each face.
std::vector<std::pair<double, double>> positions(bool quick) {
  std::vector<std::pair<double, double>> x;
  const int uniform = quick ? 8 : 100;
  for (int k = 1; k < uniform; ++k) x.emplace_back(-1.0 + 2.0 * k / uniform, 1.0 - std::abs(-1.0 + 2.0 * k / uniform));
  const int per_decade = quick ? 1 : 4, decades = quick ? 8 : 12;
  for (int k = 2 * per_decade; k <= decades * per_decade; ++k) {
    const double d = std::pow(10.0, -double(k) / per_decade);
    x.emplace_back(-1.0 + d, d);
    x.emplace_back(1.0 - d, d);
  }
  std::sort(x.begin(), x.end());
  return x;
}

struct Row {
  double x_c = not_a_number, d = not_a_number;
  kerf::NewtonMatrixConditioning c;
};

// Least-squares slope p of log kappa = -p log d + b over the rows of one side with d in [lo, hi].
double growth_exponent(const std::vector<Row>& rows, int side, double kerf::NewtonMatrixConditioning::*kappa, double lo, double hi) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const Row& r : rows) {
    if (!(r.d >= lo && r.d <= hi) || (r.x_c < 0 ? -1 : 1) != side || !std::isfinite(r.c.*kappa)) continue;
    const double x = std::log(r.d), y = std::log(r.c.*kappa);
    n += 1, sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  if (n < 2) return not_a_number;
  return -(n * sxy - sx * sy) / (n * sxx - sx * sx);
}

} // namespace conditioning_study

int main(int argc, char** argv) {
  const auto options =
      kerf_measure::parse_run_options(argc, argv, "06_conditioning_study [--quick] [--out DIR]", "output/conditioning_study");
  if (!options) return 2;
  try {
    namespace cs = conditioning_study;
    std::filesystem::create_directories(options->out);
    std::cout << "Kerf chapter 6 conditioning study" << (options->quick ? " (quick)" : "") << " on " << kerf_measure::cpu_model()
              << ", " << kerf_measure::now_text() << "\n";
    std::vector<cs::Row> rows;
    rows.push_back({cs::not_a_number, cs::not_a_number, cs::measure(cs::not_a_number)});
    for (const auto& [x_c, d] : cs::positions(options->quick)) rows.push_back({x_c, d, cs::measure(x_c)});

    std::ofstream csv(options->out / "conditioning_sweep.csv");
    csv << "x_c,d,enrichments,constrained,smallest_fraction,plain,jacobi,koschier,plain_constrained,koschier_constrained,part_jacobi,"
           "part_jacobi_constrained\n";
    csv.precision(10);
    for (const cs::Row& r : rows)
      csv << r.x_c << ',' << r.d << ',' << r.c.enrichments << ',' << r.c.constrained << ',' << r.c.smallest_fraction << ','
          << r.c.plain << ',' << r.c.jacobi << ',' << r.c.koschier << ',' << r.c.plain_constrained << ',' << r.c.koschier_constrained
          << ',' << r.c.part_jacobi << ',' << r.c.part_jacobi_constrained << '\n';

    const cs::Row& uncut = rows.front();
    std::printf("uncut cube: kappa = %.4g, Jacobi-scaled %.4g\n", uncut.c.plain, uncut.c.jacobi);
    double part_largest = 0.0;
    for (const cs::Row& r : rows)
      if (r.d >= 1e-10) part_largest = std::max(part_largest, r.c.part_jacobi_constrained);
    std::printf("part basis and Jacobi, eq. 22: largest kappa over every cut with d >= 1e-10: %.4g\n", part_largest);
    for (const cs::Row& r : rows)
      if (r.x_c == 0.0)
        std::printf("cut at x_c = 0 (%d enrichments): kappa = %.4g (%.3g x the uncut), Jacobi %.4g, Koschier %.4g\n", r.c.enrichments,
                    r.c.plain, r.c.plain / uncut.c.plain, r.c.jacobi, r.c.koschier);
    std::printf("%10s %9s %4s %11s %11s %11s %11s %11s %11s %11s\n", "x_c", "d", "con", "min v", "plain", "jacobi", "koschier", "plain+c",
                "kosch+c", "part+c");
    for (const cs::Row& r : rows)
      if (r.d < 0.99e-2 || r.x_c == 0.0)
        std::printf("%10.6g %9.2e %4d %11.3e %11.4e %11.4e %11.4e %11.4e %11.4e %11.4e\n", r.x_c, r.d, r.c.constrained,
                    r.c.smallest_fraction, r.c.plain, r.c.jacobi, r.c.koschier, r.c.plain_constrained, r.c.koschier_constrained,
                    r.c.part_jacobi_constrained);

    // The fit ranges: the bare and the scaled matrices from d = 1e-2, where the slivers begin to
    // rule, to 1e-4, below which the bare matrix is numerically singular and the slivers' own
    // entries are round-off (their volumes near 1e-16); the constrained ones on to 1e-8.
    std::ofstream slopes(options->out / "conditioning_slopes.csv");
    slopes << "side,variant,d_min,d_max,exponent\n";
    using C = kerf::NewtonMatrixConditioning;
    struct Fit {
      std::string name;
      double C::*kappa;
      double lo, hi;
    };
    const std::vector<Fit> fits{{"plain", &C::plain, 1e-4, 1e-2},
                                {"jacobi", &C::jacobi, 1e-4, 1e-2},
                                {"koschier", &C::koschier, 1e-4, 1e-2},
                                {"plain_constrained", &C::plain_constrained, 1e-8, 1e-3},
                                {"koschier_constrained", &C::koschier_constrained, 1e-8, 1e-3},
                                {"part_jacobi", &C::part_jacobi, 1e-4, 1e-2},
                                {"part_jacobi_constrained", &C::part_jacobi_constrained, 1e-8, 1e-3}};
    for (const int side : {-1, 1})
      for (const Fit& fit : fits) {
        const double p = cs::growth_exponent(rows, side, fit.kappa, fit.lo, fit.hi);
        slopes << (side < 0 ? "left" : "right") << ',' << fit.name << ',' << fit.lo << ',' << fit.hi << ',' << p << '\n';
        std::printf("kappa_%s ~ d^-%.3f as the cut nears x = %+d (d from %.0e to %.0e)\n", fit.name.c_str(), p, side, fit.lo, fit.hi);
      }
    for (const cs::Row& r : rows)
      if (std::abs(std::log10(r.d) + 3.0) < 1e-9 || std::abs(std::log10(r.d) + 4.0) < 1e-9)
        std::printf("x_c = %+.4f: kappa_plain * smallest v = %.4g\n", r.x_c, r.c.plain * r.c.smallest_fraction);
  } catch (const std::exception& error) {
    std::cerr << "06_conditioning_study: " << error.what() << '\n';
    return 1;
  }
  return 0;
}
