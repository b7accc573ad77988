/* Kerf benchmark: chapter 2's corotated elements and quasi-static solves, on one core.

   Build and run:   cmake --build --preset release --target bench
                    (runs bench_corotation with OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1)
   By hand:         OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 bench_corotation --out bench_corotation.md
                    bench_corotation --quick      (small batch and mesh, a few seconds: does it run?)

   It measures
     (a) one Tet4 rotation point, add_corotated_point<4>: rotation + force (+ tangent), in ns
         per element, with Higham's and with the SVD rotation, force only, warped tangent
         R K R^T (eq. 38) and consistent tangent; over a batch of elements whose F is a random
         rotation times a stretch within 5 % of the identity, the typical state of a soft body;
     (b) the same for a Tet10 (four rotation points, each with its own 30x30 stiffness share);
     (c) one assembly of the corotated forces and tangent into the fixed CSR pattern
         (CorotationalModel::assemble) on the ~10k-tet beam, per element;
     (d) 20 load steps of that beam under a tip load of 1.4 N along x: consistent against warped
         tangent (Newton to 1e-9, CHOLMOD); each Newton step started at the last equilibrium
         or by the secant predictor; a fresh CHOLMOD factorisation per iteration against CG
         preconditioned by a reused one (cg-cholmod) or by an incomplete Cholesky; Newton
         tolerances 1e-4 to 1e-9; 20, 10 and 5 load steps. For each: Newton iterations,
         factorisations, CG iterations, seconds, and the error of the displacement against a
         solve to 1e-12 (max over the nodes of |u - u_ref|, over max |u_ref|). With --out
         FILE.md the rows also go to FILE.csv, the data of chapter 2's time-accuracy chart.
     (a) also times the rotation alone, to show its share.
   Every number is the best of at least five runs and of at least a second of repeats:
   the minimum is what the work costs, the rest is noise from the machine. The report is a
   markdown table on stdout and, with --out, in a file. */

#include "kerf/corotation/corotated_element.hpp"
#include "kerf/corotation/corotational_model.hpp"
#include "kerf/corotation/quasi_static_solver.hpp"
#include "kerf/fem/assemble_loads.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/linear_material.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/fem/tet_quadrature.hpp"
#include "kerf/fem/tet_shape_functions.hpp"
#include "kerf/fem/tet_stiffness.hpp"
#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/node_region.hpp"
#include "kerf/solve/linear_solver.hpp"
#include "measure.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace bench {

using kerf_measure::best_time;

/// Every measurement's rule, as the report states it: the best of at least five runs and of
/// at least a second of repeats, unless 20 s have gone by.
constexpr kerf_measure::Repeats usual_repeats{5, 1.0, 20.0};

/// A batch of elements with everything add_corotated_point needs: the linear stiffness K of
/// each rotation point, its shape gradients G, the reference positions and the displacements.
template <int n>
struct ElementBatch {
  std::vector<Eigen::Matrix<double, 3 * n, 3 * n>> K; ///< one per rotation point
  std::vector<Eigen::Matrix<double, n, 3>> G;         ///< one per rotation point
  std::vector<double> weight;                         ///< the volume each rotation point stands for
  std::vector<Eigen::Matrix<double, n, 3>> X, u;      ///< reference positions and displacements, one per element
  int points_per_element = 1;
  double mu = 0.0, lambda = 0.0; ///< Lame constants, for the consistent tangent's stress
};

/// A random well-shaped tet of size ~1 cm: the unit corner tet, each corner moved by up to
/// 20 % of its size; for n = 10 the mid-edge nodes are added on the straight edges.
template <int n>
Eigen::Matrix<double, n, 3> random_reference_tet(std::mt19937& random) {
  std::uniform_real_distribution<double> jitter(-0.2, 0.2);
  Eigen::Matrix<double, 4, 3> corners;
  corners << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  for (int a = 0; a < 4; ++a)
    for (int p = 0; p < 3; ++p) corners(a, p) = 0.01 * (corners(a, p) + jitter(random));
  Eigen::Matrix<double, n, 3> X;
  X.template topRows<4>() = corners;
  if constexpr (n == 10)
    for (int e = 0; e < 6; ++e)
      X.row(4 + e) = 0.5 * (corners.row(kerf::tet_edge_corners[e][0]) + corners.row(kerf::tet_edge_corners[e][1]));
  return X;
}

/// `count` elements with F = R (I + E): R a random rotation, E a random matrix with entries
/// within 5 %, plus a random translation (which corotation must ignore).
template <int n>
ElementBatch<n> make_batch(int count, const kerf::LinearMaterial& material) {
  std::mt19937 random(2024);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  ElementBatch<n> batch;
  batch.mu = material.mu();
  batch.lambda = material.lambda();
  const kerf::TetQuadratureRule rule = kerf::tet_quadrature_rule(2);
  batch.points_per_element = n == 4 ? 1 : static_cast<int>(rule.points.size());
  for (int e = 0; e < count; ++e) {
    const Eigen::Matrix<double, n, 3> X = random_reference_tet<n>(random);
    const Eigen::Matrix3d R = Eigen::Quaterniond(Eigen::Vector4d::Random().normalized()).toRotationMatrix();
    Eigen::Matrix3d E;
    for (int i = 0; i < 9; ++i) E(i) = 0.05 * unit(random);
    const Eigen::Vector3d translation(unit(random), unit(random), unit(random));
    Eigen::Matrix<double, n, 3> x;
    for (int a = 0; a < n; ++a) x.row(a) = (R * (Eigen::Matrix3d::Identity() + E) * X.row(a).transpose() + translation).transpose();
    batch.X.push_back(X);
    batch.u.push_back(x - X);
    if constexpr (n == 4) {
      double det_J = 0.0;
      batch.G.push_back(kerf::physical_shape_gradients<4>(X, kerf::tet4_shape_gradients(), det_J));
      batch.weight.push_back(det_J / 6.0);
      batch.K.push_back(kerf::tet4_stiffness(X, material));
    } else {
      for (std::size_t q = 0; q < rule.points.size(); ++q) {
        double det_J = 0.0;
        const Eigen::Matrix<double, 10, 3> G = kerf::physical_shape_gradients<10>(X, kerf::tet10_shape_gradients(rule.points[q]), det_J);
        Eigen::Matrix<double, 30, 30> K = Eigen::Matrix<double, 30, 30>::Zero();
        kerf::add_stiffness_integrand<10>(G, rule.weights[q] * det_J, material.mu(), material.lambda(), K);
        batch.G.push_back(G);
        batch.weight.push_back(rule.weights[q] * det_J);
        batch.K.push_back(K);
      }
    }
  }
  return batch;
}

/// What is asked of one element: the force only, or the force and a tangent.
struct ElementVariant {
  kerf::RotationMethod rotation;
  const char* rotation_name;
  bool with_tangent;
  kerf::CorotationalTangent tangent;
  const char* work_name;
};

/// Best time per element, in ns, of one pass over the batch: f and Kt zeroed, then every
/// rotation point of the element added. The sink keeps the compiler from skipping the work.
template <int n>
double nanoseconds_per_element(const ElementBatch<n>& batch, const ElementVariant& variant, double& sink) {
  const std::size_t count = batch.X.size();
  Eigen::Matrix<double, 3 * n, 1> f;
  Eigen::Matrix<double, 3 * n, 3 * n> Kt;
  const double seconds = best_time([&] {
    for (std::size_t e = 0; e < count; ++e) {
      f.setZero();
      if (variant.with_tangent) Kt.setZero();
      for (int q = 0; q < batch.points_per_element; ++q) {
        const std::size_t p = e * static_cast<std::size_t>(batch.points_per_element) + static_cast<std::size_t>(q);
        kerf::add_corotated_point<n>(batch.K[p], batch.G[p], batch.X[e], batch.u[e], batch.weight[p], batch.mu, batch.lambda,
                                     variant.rotation, variant.tangent, f, variant.with_tangent ? &Kt : nullptr);
      }
      sink += f[0] + (variant.with_tangent ? Kt(0, 0) : 0.0);
    }
  }, usual_repeats);
  return 1e9 * seconds / static_cast<double>(count);
}

/// One row of the per-element table.
struct ElementTiming {
  std::string element, rotation, work;
  double nanoseconds = 0.0;
};

template <int n>
std::vector<ElementTiming> time_elements(int count, double& sink) {
  const ElementBatch<n> batch = make_batch<n>(count, kerf::LinearMaterial{});
  const ElementVariant variants[] = {
      {kerf::RotationMethod::higham, "Higham", false, kerf::CorotationalTangent::warped, "force only"},
      {kerf::RotationMethod::higham, "Higham", true, kerf::CorotationalTangent::warped, "force + warped tangent"},
      {kerf::RotationMethod::higham, "Higham", true, kerf::CorotationalTangent::consistent, "force + consistent tangent"},
      {kerf::RotationMethod::svd, "SVD", false, kerf::CorotationalTangent::warped, "force only"},
      {kerf::RotationMethod::svd, "SVD", true, kerf::CorotationalTangent::warped, "force + warped tangent"},
      {kerf::RotationMethod::svd, "SVD", true, kerf::CorotationalTangent::consistent, "force + consistent tangent"}};
  std::vector<ElementTiming> rows;
  // The rotation alone (F = x^T G and its polar factor), to see what share of the total it is.
  for (auto [method, name] : {std::pair{kerf::RotationMethod::higham, "Higham"}, std::pair{kerf::RotationMethod::svd, "SVD"}}) {
    const double seconds = best_time([&] {
      for (std::size_t p = 0; p < batch.G.size(); ++p) {
        const std::size_t e = p / static_cast<std::size_t>(batch.points_per_element);
        sink += kerf::element_rotation(Eigen::Matrix3d::Identity() + batch.u[e].transpose() * batch.G[p], method).R(0, 0);
      }
    }, usual_repeats);
    rows.push_back({n == 4 ? "Tet4" : "Tet10", name, "rotation only (F and its polar factor)",
                    1e9 * seconds / static_cast<double>(batch.X.size())});
  }
  for (const ElementVariant& v : variants)
    rows.push_back({n == 4 ? "Tet4" : "Tet10", v.rotation_name, v.work_name, nanoseconds_per_element<n>(batch, v, sink)});
  return rows;
}

/// The beam 0.03 x 0.06 x 0.2 m with cells[0] x cells[1] x cells[2] cells (six Tet4 each).
kerf::TetMesh beam_mesh(const Eigen::Vector3i& cells) { return kerf::make_box_mesh({0, 0, 0}, {0.03, 0.06, 0.2}, cells); }

/// One row of the solve table.
struct SolveTiming {
  std::string tangent, solver, predictor;
  double newton_tolerance = 0.0;
  int load_steps = 0, iterations = 0, factorisations = 0, linear_iterations = 0;
  bool converged = false;
  double seconds = 0.0;
  double tip_ux = 0.0;
  double relative_error = 0.0; ///< max_v |u - u_ref| / max_v |u_ref|
};

/// What the quasi-static section measures on the beam.
struct BeamTimings {
  std::string cells;
  Eigen::Index tets = 0;
  int dofs = 0;
  double assembly_ns_per_tet_consistent = 0.0, assembly_ns_per_tet_warped = 0.0;
  double factorize_solve_seconds = 0.0;
  std::vector<SolveTiming> solves;
};

BeamTimings time_beam(const Eigen::Vector3i& cells, double tip_load, int load_steps) {
  const kerf::LinearMaterial material;
  const kerf::TetMesh mesh = beam_mesh(cells);
  kerf::NodeRegion base, top;
  base.box_max = {0.03, 0.06, 0.0};
  top.box_min = {0.0, 0.0, 0.2};
  top.box_max = {0.03, 0.06, 0.2};
  const kerf::DofMap dofs = kerf::make_dof_map(mesh.num_nodes(), {{kerf::nodes_in_region(mesh, base), {0, 0, 0}}});
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * mesh.num_nodes());
  kerf::add_uniform_traction(mesh, kerf::boundary_faces(mesh), kerf::node_mask(mesh, top), {tip_load, 0, 0}, f);
  const std::vector<int> top_nodes = kerf::nodes_in_region(mesh, top);
  const kerf::CorotationalModel model(mesh, material);

  BeamTimings b;
  b.cells = std::to_string(cells[0]) + "x" + std::to_string(cells[1]) + "x" + std::to_string(cells[2]);
  b.tets = mesh.num_tets();
  b.dofs = dofs.num_free;

  // One Newton iteration's assembly, at a bent state (the converged solution below), and one
  // CHOLMOD factorisation + solve of its tangent: the two costs that every iteration pays.
  kerf::QuasiStaticSettings settings;
  settings.load_steps = load_steps;
  const Eigen::VectorXd u_bent = kerf::solve_quasi_static(model, dofs, f, settings).u;
  kerf::SparseAssembler assembler(mesh.tets, dofs);
  Eigen::VectorXd f_int, rhs;
  for (auto tangent : {kerf::CorotationalTangent::consistent, kerf::CorotationalTangent::warped}) {
    const double seconds = best_time([&] {
      assembler.set_zero();
      rhs = Eigen::VectorXd::Zero(dofs.num_free);
      model.assemble(u_bent, kerf::RotationMethod::automatic, tangent, f_int, &assembler, &rhs);
    }, usual_repeats);
    (tangent == kerf::CorotationalTangent::consistent ? b.assembly_ns_per_tet_consistent : b.assembly_ns_per_tet_warped) =
        1e9 * seconds / static_cast<double>(mesh.num_tets());
  }
  const auto solver = kerf::make_linear_solver(kerf::SolverSettings{});
  solver->analyze_pattern(assembler.matrix());
  Eigen::VectorXd du = Eigen::VectorXd::Zero(dofs.num_free);
  b.factorize_solve_seconds = best_time([&] {
    solver->factorize(assembler.matrix());
    solver->solve(rhs, du);
  }, usual_repeats);

  // The reference: Newton to 1e-12 (a few times round-off) with fresh factorisations.
  settings.tolerance = 1e-12;
  const Eigen::VectorXd u_reference = kerf::solve_quasi_static(model, dofs, f, settings).u;
  const auto node_max = [](const Eigen::VectorXd& u) { return u.reshaped(3, u.size() / 3).colwise().norm().maxCoeff(); };

  // The chapter's earlier configurations first (no predictor), then what brings the time down.
  struct Variant {
    const char* tangent_name;
    kerf::CorotationalTangent tangent;
    kerf::LoadStepPredictor predictor;
    double newton_tolerance;
    const char* solver;
    int load_steps;
  };
  using kerf::CorotationalTangent;
  using kerf::LoadStepPredictor;
  const CorotationalTangent consistent = CorotationalTangent::consistent;
  const LoadStepPredictor previous = LoadStepPredictor::previous_state, secant = LoadStepPredictor::secant;
  const std::vector<Variant> variants = {
      {"consistent", consistent, previous, 1e-9, "cholmod", load_steps},
      {"warped", CorotationalTangent::warped, previous, 1e-9, "cholmod", load_steps},
      {"consistent", consistent, previous, 1e-4, "cholmod", load_steps},
      {"consistent", consistent, previous, 1e-4, "cg-ichol", load_steps},
      {"consistent", consistent, secant, 1e-9, "cholmod", load_steps},
      {"consistent", consistent, secant, 1e-9, "cg-cholmod", load_steps},
      {"consistent", consistent, secant, 1e-6, "cholmod", load_steps},
      {"consistent", consistent, secant, 1e-6, "cg-cholmod", load_steps},
      {"consistent", consistent, secant, 1e-4, "cholmod", load_steps},
      {"consistent", consistent, secant, 1e-4, "cg-cholmod", load_steps},
      {"consistent", consistent, secant, 1e-6, "cholmod", load_steps / 4},
      {"consistent", consistent, secant, 1e-6, "cg-cholmod", load_steps / 4},
      {"consistent", consistent, secant, 1e-4, "cg-cholmod", load_steps / 4},
      {"consistent", consistent, secant, 1e-6, "cholmod", 1},
      {"consistent", consistent, secant, 1e-6, "cg-cholmod", 1},
  };
  for (const Variant& v : variants) {
    settings.tangent = v.tangent;
    settings.predictor = v.predictor;
    settings.tolerance = v.newton_tolerance;
    settings.load_steps = std::max(1, v.load_steps);
    settings.solver.type = v.solver;
    // CG's own tolerance: tight enough not to slow Newton's convergence at 1e-9, loose enough
    // not to waste iterations on digits Newton throws away.
    settings.solver.tolerance = 1e-6;
    SolveTiming s;
    s.tangent = v.tangent_name;
    s.solver = v.solver;
    s.predictor = v.predictor == secant ? "secant" : "previous";
    s.newton_tolerance = v.newton_tolerance;
    s.load_steps = settings.load_steps;
    kerf::QuasiStaticResult result;
    s.seconds = best_time([&] { result = kerf::solve_quasi_static(model, dofs, f, settings); }, {3, 0.0, 30.0});
    s.iterations = result.total_iterations;
    s.factorisations = result.factorisations;
    s.linear_iterations = result.linear_iterations;
    s.converged = result.converged;
    for (int v_top : top_nodes) s.tip_ux += result.u[3 * v_top] / static_cast<double>(top_nodes.size());
    s.relative_error = node_max(result.u - u_reference) / node_max(u_reference);
    b.solves.push_back(s);
  }
  return b;
}

/// (d) as a table for the chart: one row per variant.
void write_solves_csv(const std::filesystem::path& path, const BeamTimings& beam) {
  std::ofstream csv(path);
  csv << "tangent,predictor,newton_tolerance,solver,load_steps,newton_iterations,factorisations,linear_iterations,converged,"
         "seconds,tip_ux,relative_error\n";
  csv.precision(6);
  for (const SolveTiming& t : beam.solves)
    csv << t.tangent << ',' << t.predictor << ',' << t.newton_tolerance << ',' << t.solver << ',' << t.load_steps << ','
        << t.iterations << ',' << t.factorisations << ',' << t.linear_iterations << ',' << (t.converged ? 1 : 0) << ','
        << t.seconds << ',' << t.tip_ux << ',' << t.relative_error << '\n';
}

/// The markdown report.
std::string report(const std::vector<ElementTiming>& elements, const BeamTimings& beam, double tip_load, int batch) {
  std::ostringstream s;
  char line[512];
  s << "## bench_corotation\n\n"
    << "- CPU: " << kerf_measure::cpu_model() << "\n- date: " << kerf_measure::now_text()
    << "\n- OPENBLAS_NUM_THREADS=" << kerf_measure::environment("OPENBLAS_NUM_THREADS")
    << ", OMP_NUM_THREADS=" << kerf_measure::environment("OMP_NUM_THREADS")
    << "\n- best of >= 5 runs and >= 1 s per measurement (the quasi-static solves: best of 3)\n\n";
  s << "### (a, b) One element: rotation + force (+ tangent), add_corotated_point\n\n"
    << "Batch of " << batch << " elements, F = R (I + E) with R random and |E_ij| <= 0.05. Tet10: four rotation points.\n\n"
    << "| element | rotation | work | ns per element |\n|---|---|---|---:|\n";
  for (const ElementTiming& e : elements) {
    std::snprintf(line, sizeof line, "| %s | %s | %s | %.0f |\n", e.element.c_str(), e.rotation.c_str(), e.work.c_str(),
                  e.nanoseconds);
    s << line;
  }
  s << "\n### (c, d) Quasi-static solve of the beam (Tet4, cells " << beam.cells << ", " << beam.tets << " tets, " << beam.dofs
    << " DOFs), tip load " << tip_load << " N along x, CHOLMOD, automatic rotation\n\n";
  std::snprintf(line, sizeof line,
                "One assembly (CorotationalModel::assemble into the CSR pattern): %.0f ns per tet with the consistent "
                "tangent, %.0f ns with the warped one; one CHOLMOD factorisation + solve of the tangent: %.4f s.\n\n",
                beam.assembly_ns_per_tet_consistent, beam.assembly_ns_per_tet_warped, beam.factorize_solve_seconds);
  s << line
    << "| tangent | predictor | Newton tolerance | linear solver | load steps | Newton iterations | factorisations "
    << "| CG iterations | converged | seconds | per iteration (s) | tip u_x (m) | error vs 1e-12 |\n"
    << "|---|---|---:|---|---:|---:|---:|---:|---|---:|---:|---:|---:|\n";
  for (const SolveTiming& t : beam.solves) {
    const bool iterative = t.solver.rfind("cg-", 0) == 0;
    std::snprintf(line, sizeof line, "| %s | %s | %.0e | %s | %d | %d | %d | %s | %s | %.3f | %.4f | %.6f | %.1e |\n",
                  t.tangent.c_str(), t.predictor.c_str(), t.newton_tolerance, t.solver.c_str(), t.load_steps, t.iterations,
                  t.factorisations, iterative ? std::to_string(t.linear_iterations).c_str() : "-", t.converged ? "yes" : "no",
                  t.seconds, t.seconds / std::max(1, t.iterations), t.tip_ux, t.relative_error);
    s << line;
  }
  return s.str();
}

} // namespace bench

/// `bench_corotation [--quick] [--out FILE.md]`: see the header comment.
int main(int argc, char** argv) {
  try {
    const std::optional<kerf_measure::RunOptions> options =
        kerf_measure::parse_run_options(argc, argv, "bench_corotation [--quick] [--out FILE.md] [--only elements,beam]", {},
                                        {"elements", "beam"});
    if (!options) return 2;
    const bool quick = options->quick;
    const std::filesystem::path& out = options->out;
    const int batch = quick ? 256 : 4096;
    double sink = 0.0;
    std::vector<bench::ElementTiming> elements;
    if (options->runs("elements")) {
      elements = bench::time_elements<4>(batch, sink);
      const std::vector<bench::ElementTiming> tet10 = bench::time_elements<10>(batch / 4, sink);
      elements.insert(elements.end(), tet10.begin(), tet10.end());
      std::cerr << "measured the elements\n";
    }
    // 5 x 10 x 33 cells: nearly cubic cells of 6 mm, 9900 Tet4.
    const Eigen::Vector3i cells = quick ? Eigen::Vector3i(1, 2, 6) : Eigen::Vector3i(5, 10, 33);
    const double tip_load = 1.4;
    const bench::BeamTimings beam = options->runs("beam") ? bench::time_beam(cells, tip_load, 20) : bench::BeamTimings{};
    const std::string text = bench::report(elements, beam, tip_load, batch);
    std::cout << text;
    if (!out.empty()) {
      std::ofstream(out) << text;
      std::filesystem::path csv = out;
      bench::write_solves_csv(csv.replace_extension(".csv"), beam);
    }
    if (sink == 42.0) std::cout << ' '; // uses the sink; never true in practice
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "bench_corotation: " << e.what() << '\n';
    return 3;
  }
}
