/* Kerf, chapter 6 study: the conditioning of the implicit step's matrix when a cut nears the
   nodes, Koschier's Fig. 14 again (Koschier et al. 2017, section 6, eqs. 22-27, and section 7).

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
   condition number (dense eigenvalues, dynamics/newton_matrix_conditioning.hpp) for nine
   variants:
     plain                    bare (only enrichments without volume held);
     jacobi                   Jacobi-scaled, T = diag(A)^(-1/2);
     koschier                 with Koschier's bilateral preconditioner (eqs. 23-27, v for V in eq. 26);
     plain_constrained        bare after eq. 22 with Koschier's epsilon = 1e-9;
     jacobi_constrained       Jacobi-scaled after eq. 22 (epsilon = 1e-9);
     koschier_constrained     eqs. 23-27 after eq. 22 (epsilon = 1e-9);
     part_jacobi              Kerf's addition: the part basis (dynamics/part_basis.hpp), Jacobi-scaled;
     part_jacobi_constrained  the same after eq. 22 (epsilon = 1e-9);
     jacobi_constrained_1e-3  Jacobi-scaled after eq. 22 with epsilon = 1e-3 (a second call of
                              newton_matrix_conditioning): a threshold that holds the home slabs of
                              the face's nodes (relative volume 0.6 d and 1.5 d) from d = 6.7e-4 on
                              (Koschier's 1e-9 from 6.7e-10 on).
   Eq. 22 is tested on every part of a node's support, its home part too
   (xfem/enrichment_volumes.hpp, sliver_enrichments). Files in --out:
     conditioning_sweep.csv  one row per cut position: x_c, d (distance to the nearer face),
                 the enrichments, how many eq. 22 holds (epsilon = 1e-9), the smallest V_enr / V_supp,
                 the condition numbers plain to part_jacobi_constrained in the order above but
                 jacobi_constrained, which follows them (the columns the figures read stay put),
                 the smallest home fraction (V_supp less the node's enriched parts, over V_supp),
                 how many eq. 22 holds with epsilon = 1e-3 and jacobi_constrained_1e-3; and the
                 uncut cube as the row x_c = NaN;
     conditioning_slopes.csv the growth exponents p of kappa ~ d^-p as d -> 0, fitted by least
                 squares on log kappa against log d on each side's points: 1e-4 <= d <= 1e-2 for
                 the unconstrained variants, 1e-8 <= d <= 1e-3 for the constrained ones with
                 epsilon = 1e-9, 1e-8 <= d <= 1e-4 (slabs held) with epsilon = 1e-3.
   It also prints, for each side, below which d the Jacobi-scaled kappa after eq. 22 stays within
   twice the uncut cube's, beside the prediction d < epsilon / 1.5.
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
#include <functional>
#include <iostream>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace conditioning_study {

const double not_a_number = std::numeric_limits<double>::quiet_NaN();
const kerf::LinearMaterial material{1e6, 0.3, 1000.0}; // Koschier et al. 2017, section 7
const double dt = 1e-3;                                 // s
// Eq. 22's second threshold. A node on the face the cut nears keeps as its home part the slab
// between face and cut: relative volume 0.6 d at the face's two corners of the central tet
// (a slab of 4 d, in two corner tets, of a support of 20/3), 1.5 d at its two other corners
// (2 d of their one corner tet's 4/3). Eq. 22 holds both once 1.5 d < epsilon: from
// d = 6.7e-4 on with 1e-3, from 6.7e-10 on with Koschier's 1e-9.
const double wide_epsilon = 1e-3;

// Sub-tetrahedra with Gauss rules of the degree asked for: exact for the mass and stiffness integrands.
kerf::PieceQuadratureRule subtets(const Eigen::Matrix<double, 4, 3>&, const kerf::TetPieces& pieces, int piece, int degree) {
  return kerf::subtet_rule(pieces, piece, degree);
}

// The plane x = x_c as a square of two triangles reaching past the cube, normal +x.
kerf::TriangleSurface cut_plane(double x_c) {
  return kerf::rectangle_surface(kerf::RectangleCut({x_c, -2.0, -2.0}, {0.0, 4.0, 0.0}, {0.0, 0.0, 4.0}));
}

struct Row {
  double x_c = not_a_number, d = not_a_number;
  kerf::NewtonMatrixConditioning c;    // eq. 22 with Koschier's epsilon = 1e-9
  kerf::NewtonMatrixConditioning wide; // eq. 22 with wide_epsilon (only its constrained variants are new)
  double smallest_home_fraction = 1.0; // the smallest (V_supp - V_enrichments) / V_supp of an enriched node
};

// The cube cut at x_c (no cut for NaN), measured with both thresholds.
Row measure(double x_c, double d) {
  const kerf::TetMesh mesh = kerf::make_five_tet_cube({-1, -1, -1}, {1, 1, 1});
  std::vector<kerf::TriangleSurface> surfaces;
  if (!std::isnan(x_c)) surfaces.push_back(cut_plane(x_c));
  const kerf::CutSurfaces cuts(std::move(surfaces));
  const kerf::MeshPieces pieces = kerf::cut_mesh_into_pieces(mesh, cuts);
  const kerf::SurfaceEnrichment enrichment = kerf::make_surface_enrichment(mesh, pieces);
  const kerf::CutXfemModel model(mesh, material, pieces, enrichment, subtets);
  Row row{x_c, d, kerf::newton_matrix_conditioning(model, material.density, dt, subtets),
          kerf::newton_matrix_conditioning(model, material.density, dt, subtets, wide_epsilon)};
  const kerf::EnrichmentVolumes volumes = model.enrichment_volumes();
  for (Eigen::Index k = 0; k < static_cast<Eigen::Index>(volumes.enriched.size()); ++k)
    row.smallest_home_fraction = std::min(row.smallest_home_fraction, volumes.home_fraction(k));
  return row;
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

using Kappa = std::function<double(const Row&)>;

// Least-squares slope p of log kappa = -p log d + b over the rows of one side with d in [lo, hi].
double growth_exponent(const std::vector<Row>& rows, int side, const Kappa& kappa, double lo, double hi) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const Row& r : rows) {
    if (!(r.d >= lo && r.d <= hi) || (r.x_c < 0 ? -1 : 1) != side || !std::isfinite(kappa(r))) continue;
    const double x = std::log(r.d), y = std::log(kappa(r));
    n += 1, sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  if (n < 2) return not_a_number;
  return -(n * sxy - sx * sy) / (n * sxx - sx * sx);
}

// The largest distance d of one side below which (at every d the sweep took down to 1e-10;
// further down the cut's own geometry nears round-off) kappa stays under `bound`: where the
// variant is bounded; NaN if not even at the smallest d.
double bounded_below(const std::vector<Row>& rows, int side, const Kappa& kappa, double bound) {
  double largest = not_a_number;
  std::vector<const Row*> near_face;
  for (const Row& r : rows)
    if (r.d < 0.99e-2 && r.d >= 1e-10 && (r.x_c < 0 ? -1 : 1) == side) near_face.push_back(&r);
  std::sort(near_face.begin(), near_face.end(), [](const Row* a, const Row* b) { return a->d < b->d; });
  for (const Row* r : near_face) {
    if (!(kappa(*r) < bound)) break;
    largest = r->d;
  }
  return largest;
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
    rows.push_back(cs::measure(cs::not_a_number, cs::not_a_number));
    for (const auto& [x_c, d] : cs::positions(options->quick)) rows.push_back(cs::measure(x_c, d));

    std::ofstream csv(options->out / "conditioning_sweep.csv");
    csv << "x_c,d,enrichments,constrained,smallest_fraction,plain,jacobi,koschier,plain_constrained,koschier_constrained,part_jacobi,"
           "part_jacobi_constrained,jacobi_constrained,smallest_home_fraction,constrained_1e-3,jacobi_constrained_1e-3\n";
    csv.precision(10);
    for (const cs::Row& r : rows)
      csv << r.x_c << ',' << r.d << ',' << r.c.enrichments << ',' << r.c.constrained << ',' << r.c.smallest_fraction << ','
          << r.c.plain << ',' << r.c.jacobi << ',' << r.c.koschier << ',' << r.c.plain_constrained << ',' << r.c.koschier_constrained
          << ',' << r.c.part_jacobi << ',' << r.c.part_jacobi_constrained << ',' << r.c.jacobi_constrained << ','
          << r.smallest_home_fraction << ',' << r.wide.constrained << ',' << r.wide.jacobi_constrained << '\n';

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
    std::printf("%10s %9s %4s %11s %9s %11s %11s %11s %11s %11s %11s %11s %4s %11s\n", "x_c", "d", "con", "min v", "min home", "plain",
                "jacobi", "koschier", "plain+c", "jacobi+c", "kosch+c", "part+c", "c3", "jac+c3");
    for (const cs::Row& r : rows)
      if (r.d < 0.99e-2 || r.x_c == 0.0)
        std::printf("%10.6g %9.2e %4d %11.3e %9.2e %11.4e %11.4e %11.4e %11.4e %11.4e %11.4e %11.4e %4d %11.4e\n", r.x_c, r.d,
                    r.c.constrained, r.c.smallest_fraction, r.smallest_home_fraction, r.c.plain, r.c.jacobi, r.c.koschier,
                    r.c.plain_constrained, r.c.jacobi_constrained, r.c.koschier_constrained, r.c.part_jacobi_constrained,
                    r.wide.constrained, r.wide.jacobi_constrained);
    std::printf("(con: enrichments eq. 22 holds with epsilon = 1e-9; c3 and jac+c3: with epsilon = %g)\n", cs::wide_epsilon);

    // Where eq. 22 on every part bounds Jacobi's kappa: within twice the uncut cube's
    // Jacobi-scaled value, at this d and every smaller one the sweep took (down to 1e-10);
    // predicted once the odd corners' home slabs (1.5 d) are below epsilon.
    const cs::Kappa jacobi_koschier_epsilon = [](const cs::Row& r) { return r.c.jacobi_constrained; };
    const cs::Kappa jacobi_wide_epsilon = [](const cs::Row& r) { return r.wide.jacobi_constrained; };
    for (const int side : {-1, 1})
      for (const auto& [epsilon, kappa] : {std::pair{kerf::koschier_sliver_fraction, jacobi_koschier_epsilon},
                                           std::pair{cs::wide_epsilon, jacobi_wide_epsilon}})
        std::printf("Jacobi and eq. 22 (epsilon = %g) within 2 x the uncut cube's %.4g as the cut nears x = %+d: from d = %.3g "
                    "down (predicted d < epsilon / 1.5 = %.3g; nan: at no d of the sweep)\n",
                    epsilon, uncut.c.jacobi, side, cs::bounded_below(rows, side, kappa, 2.0 * uncut.c.jacobi), epsilon / 1.5);

    // The fit ranges: the bare and the scaled matrices from d = 1e-2, where the slivers begin to
    // rule, to 1e-4, below which the bare matrix is numerically singular and the slivers' own
    // entries are round-off (their volumes near 1e-16); the constrained ones on to 1e-8 (with
    // epsilon = 1e-3 from 1e-4, where the home slabs are held).
    std::ofstream slopes(options->out / "conditioning_slopes.csv");
    slopes << "side,variant,d_min,d_max,exponent\n";
    struct Fit {
      std::string name;
      cs::Kappa kappa;
      double lo, hi;
    };
    const std::vector<Fit> fits{{"plain", [](const cs::Row& r) { return r.c.plain; }, 1e-4, 1e-2},
                                {"jacobi", [](const cs::Row& r) { return r.c.jacobi; }, 1e-4, 1e-2},
                                {"koschier", [](const cs::Row& r) { return r.c.koschier; }, 1e-4, 1e-2},
                                {"plain_constrained", [](const cs::Row& r) { return r.c.plain_constrained; }, 1e-8, 1e-3},
                                {"jacobi_constrained", jacobi_koschier_epsilon, 1e-8, 1e-3},
                                {"koschier_constrained", [](const cs::Row& r) { return r.c.koschier_constrained; }, 1e-8, 1e-3},
                                {"part_jacobi", [](const cs::Row& r) { return r.c.part_jacobi; }, 1e-4, 1e-2},
                                {"part_jacobi_constrained", [](const cs::Row& r) { return r.c.part_jacobi_constrained; }, 1e-8, 1e-3},
                                {"jacobi_constrained_1e-3", jacobi_wide_epsilon, 1e-8, 1e-4}};
    for (const int side : {-1, 1})
      for (const Fit& fit : fits) {
        const double p = cs::growth_exponent(rows, side, fit.kappa, fit.lo, fit.hi);
        slopes << (side < 0 ? "left" : "right") << ',' << fit.name << ',' << fit.lo << ',' << fit.hi << ',' << p << '\n';
        std::printf("kappa_%s ~ d^-p, p = %.3f, as the cut nears x = %+d (d from %.0e to %.0e)\n", fit.name.c_str(), p, side, fit.lo,
                    fit.hi);
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
