// When the cut grows during a run, the state is carried into the new model's DOFs
// (xfem/cut_state_transfer.hpp), and the claim is one sentence: the new field equals the old one
// on every piece of the new model. We check it where it can be seen: the displacement at points
// strictly inside every piece of every tet, the linear and corotated strain energies, and the
// kinetic energy with the consistent and the lumped masses; the enrichments of parts that were
// the node's home part before start at exactly zero, and a far part that a crossing cut splits
// in two gives both halves its value. The cuts are the sheets a straight blade leaves
// (cut/cut_sheet.hpp), grown as chapter 7 grows them.
#include "kerf/cut/cut_sheet.hpp"
#include "kerf/cut/convex_cell.hpp"
#include "kerf/dynamics/lumped_mass.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"
#include "kerf/mesh/tet_neighbours.hpp"
#include "kerf/xfem/cut_state_transfer.hpp"
#include "kerf/xfem/cut_xfem_mass.hpp"
#include "kerf/xfem/crack_tip_body.hpp"
#include "kerf/mesh/node_region.hpp"
#include "kerf/fem/dof_map.hpp"

#include "support/cut_body.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <stdexcept>
#include <vector>

namespace {

const kerf::LinearMaterial tissue{3000.0, 0.45, 1000.0};

// One model of a cut on a mesh it shares with the other models, with what it refers to.
struct CutModel {
  kerf::CutSurfaces cuts;
  kerf::MeshPieces pieces;
  kerf::SurfaceEnrichment enrichment;
  kerf::CutXfemModel model;
  CutModel(const kerf::TetMesh& mesh, std::vector<kerf::TriangleSurface> surfaces, std::shared_ptr<const kerf::TetNeighbours> neighbours)
      : cuts(std::move(surfaces)), pieces(kerf::cut_mesh_into_pieces(mesh, cuts, std::move(neighbours))),
        enrichment(kerf::make_surface_enrichment(mesh, pieces)), model(mesh, tissue, pieces, enrichment, support::subtets) {}
};

// A blade translating along `motion`: its edge from `origin + s motion` to `origin + edge + s motion`.
struct StraightBlade {
  Eigen::Vector3d origin, edge, motion;
  kerf::BladeEdge at(double s) const { return {origin + s * motion, origin + edge + s * motion}; }
};

// Offers the blade at s = from + 0.05 k up to `to` (forced there) to the sheet, as chapter 7
// offers it frame by frame.
void sweep(kerf::CutSheet& sheet, const StraightBlade& blade, double from, double to) {
  const int frames = static_cast<int>(std::lround((to - from) / 0.05));
  for (int k = 0; k <= frames; ++k) sheet.offer(blade.at(from + (to - from) * k / frames), k == frames);
}

// The cuts of these tests, in the unit box: sheet A, nearly the plane y = 0.47, swept in x
// from outside the box to x ~ 0.45 (short) and on to x ~ 0.75 (long); sheet B, nearly the plane
// z = 0.57, swept in x to x ~ 0.5, crossing A. Neither comes near a node of the 5 x 5 x 5 box
// (nodes at multiples of 0.2: A stays within 0.43 < y < 0.53, B within 0.54 < z < 0.59).
struct Sheets {
  kerf::TriangleSurface a_short, a_long, b;
};

Sheets make_sheets() {
  const StraightBlade a{{-0.3, 0.47, -0.3}, {0.08, -0.06, 1.6}, {1.0, 0.05, 0.0}};
  const StraightBlade b{{-0.3, -0.3, 0.57}, {0.05, 1.6, -0.04}, {1.0, 0.0, 0.03}};
  Sheets sheets;
  kerf::CutSheet sheet_a(0.15);
  sweep(sheet_a, a, 0.0, 0.75);
  sheets.a_short = sheet_a.surface();
  sweep(sheet_a, a, 0.75, 1.05);
  sheets.a_long = sheet_a.surface();
  kerf::CutSheet sheet_b(0.15);
  sweep(sheet_b, b, 0.0, 0.8);
  sheets.b = sheet_b.surface();
  return sheets;
}

Eigen::VectorXd random_vector(Eigen::Index size, std::mt19937& rng) {
  std::uniform_real_distribution<double> value(-0.01, 0.01);
  Eigen::VectorXd q(size);
  for (Eigen::Index i = 0; i < size; ++i) q[i] = value(rng);
  return q;
}

double kinetic(const Eigen::SparseMatrix<double>& M, const Eigen::VectorXd& v) { return 0.5 * v.dot(M * v); }

// A point strictly inside piece p of tet t of `m`: the inner point of the piece's first cell,
// or the tet's centroid for a tet without pieces.
Eigen::Vector3d point_in_piece(const kerf::TetMesh& mesh, const CutModel& m, Eigen::Index t, int p) {
  const int e = m.pieces.entry[static_cast<std::size_t>(t)];
  if (e < 0) return kerf::tet_corners(mesh, t).colwise().mean().transpose();
  const kerf::TetPieces& tp = m.pieces.tets[static_cast<std::size_t>(e)];
  return kerf::convex_cell_inner_point(tp.cells[static_cast<std::size_t>(tp.pieces[static_cast<std::size_t>(p)].cells.front())]);
}

// What one transfer measured, relative to the size of the state or the energy.
struct TransferErrors {
  double field = 0.0, linear_energy = 0.0, corotated_energy = 0.0, consistent_kinetic = 0.0, virtual_tet_kinetic = 0.0,
         row_sum_kinetic = 0.0, hrz_kinetic = 0.0, far_values = 0.0;
  int points = 0, new_at_zero = 0, kept = 0, most_heirs = 0; // enrichments: started at 0, kept from a far part; most new per old
};

double relative(double a, double b) { return std::abs(a - b) / std::max(std::abs(a), std::abs(b)); }

// Transfers a random state from `from` to `to` and measures everything the claim says.
TransferErrors transfer_and_measure(const kerf::TetMesh& mesh, const CutModel& from, const CutModel& to, std::mt19937& rng) {
  TransferErrors errors;
  const Eigen::VectorXd u_old = random_vector(3 * from.model.num_dof_nodes(), rng);
  const Eigen::VectorXd u_new = kerf::transfer_cut_state(from.model, to.model, u_old);
  REQUIRE(u_new.size() == 3 * to.model.num_dof_nodes());
  const double scale = u_old.cwiseAbs().maxCoeff();
  const Eigen::Index N = mesh.num_nodes();
  // The standard DOFs are the same DOFs in both models.
  CHECK(u_new.head(3 * N) == u_old.head(3 * N));

  // The field at points strictly inside the pieces: every cell of every tet the new cut
  // meets, and three random points in each other tet.
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    std::vector<Eigen::Vector3d> points;
    const int e = to.pieces.entry[static_cast<std::size_t>(t)];
    if (e >= 0) {
      for (const kerf::ConvexCell& cell : to.pieces.tets[static_cast<std::size_t>(e)].cells) points.push_back(kerf::convex_cell_inner_point(cell));
    } else {
      const Eigen::Matrix<double, 4, 3> X = kerf::tet_corners(mesh, t);
      for (int k = 0; k < 3; ++k) {
        Eigen::Vector4d lambda(unit(rng), unit(rng), unit(rng), unit(rng));
        lambda = (lambda.array() + 0.05).matrix() / (lambda.sum() + 0.2); // every weight >= 0.05 / 4.2: inside
        points.push_back(X.transpose() * lambda);
      }
    }
    for (const Eigen::Vector3d& x : points) {
      const Eigen::Vector3d before = from.model.displacement_at(u_old, t, x), after = to.model.displacement_at(u_new, t, x);
      REQUIRE(before.allFinite());
      REQUIRE(after.allFinite());
      errors.field = std::max(errors.field, (after - before).norm() / scale);
      ++errors.points;
    }
  }

  errors.linear_energy = relative(from.model.energy(u_old, false), to.model.energy(u_new, false));
  errors.corotated_energy = relative(from.model.energy(u_old, true), to.model.energy(u_new, true));
  const double rho = tissue.density;
  errors.consistent_kinetic = relative(kinetic(kerf::assemble_cut_xfem_mass(from.model, rho, support::subtets), u_old),
                                       kinetic(kerf::assemble_cut_xfem_mass(to.model, rho, support::subtets), u_new));
  const auto lumped = [&](kerf::LumpingScheme scheme) {
    return relative(kinetic(kerf::lump_cut_xfem_mass(from.model, rho, scheme, support::subtets), u_old),
                    kinetic(kerf::lump_cut_xfem_mass(to.model, rho, scheme, support::subtets), u_new));
  };
  errors.virtual_tet_kinetic = lumped(kerf::LumpingScheme::virtual_tet);
  errors.row_sum_kinetic = lumped(kerf::LumpingScheme::row_sum);
  errors.hrz_kinetic = lumped(kerf::LumpingScheme::hrz);

  // Each new enrichment: found where it is active, the old model's phantom node there says
  // whether its part was the home part (then a = 0 exactly) or a far part (then a = the old a).
  const Eigen::Index num_new = to.enrichment.num_enrichments();
  std::vector<char> seen(static_cast<std::size_t>(num_new), 0);
  std::map<int, int> heirs; // old enrichment -> how many new enrichments took its value
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    for (int p = 0; p < to.pieces.num_pieces(t); ++p)
      for (int a = 0; a < mesh.nodes_per_tet(); ++a) {
        const int k = to.enrichment.active_enrichment(to.pieces, t, a, p);
        if (k < 0 || seen[static_cast<std::size_t>(k)]) continue;
        seen[static_cast<std::size_t>(k)] = 1;
        const Eigen::Vector3d x = point_in_piece(mesh, to, t, p);
        const int p_old = from.model.piece_at(t, x);
        REQUIRE(p_old >= 0);
        const int old_node = from.model.phantom_node(t, p_old, a);
        const Eigen::Vector3d a_new = u_new.segment<3>(3 * (N + k));
        if (old_node == mesh.tets(t, a)) {
          CHECK(a_new == Eigen::Vector3d::Zero());
          ++errors.new_at_zero;
        } else {
          errors.far_values = std::max(errors.far_values, (a_new - u_old.segment<3>(3 * old_node)).norm() / scale);
          ++errors.kept;
          errors.most_heirs = std::max(errors.most_heirs, ++heirs[old_node]);
        }
      }
  CHECK(std::all_of(seen.begin(), seen.end(), [](char s) { return s == 1; }));
  return errors;
}

// The tolerances of every transfer, from what was measured on the 750-tet box (MESSAGE below):
// the field and the strain energies came out bitwise equal (0), the kinetic energies within
// 1.7e-16 relative, the far parts' a, (u + a) - u, within 1.7e-16 of the state's largest value
// (one rounding of u + a). 1e-12 leaves room for other compilers' round-off over a few hundred
// tets; 1e-15 for one rounding. HRZ lumping is measured, not asserted: it scales each piece's
// diagonal to the piece's mass, which is not additive when a piece is split, so its kinetic
// energy changes at a rebuild (measured 2.5e-4, 5.8e-5 and 4.9e-5 relative); the row sum (on
// these Tet4 the scene's "lumped", Bernstein) and the virtual tet are sums over the pieces and keep it.
void check_round_off(const TransferErrors& errors) {
  MESSAGE("transfer: " << errors.points << " points, field " << errors.field << ", energies linear " << errors.linear_energy
                       << " corotated " << errors.corotated_energy << ", kinetic consistent " << errors.consistent_kinetic
                       << " virtual tet " << errors.virtual_tet_kinetic << " row sum " << errors.row_sum_kinetic << " (hrz "
                       << errors.hrz_kinetic << "); enrichments started at 0: " << errors.new_at_zero << ", kept: " << errors.kept
                       << ", far values " << errors.far_values << ", most heirs of one: " << errors.most_heirs);
  CHECK(errors.field < 1e-12);
  CHECK(errors.linear_energy < 1e-12);
  CHECK(errors.corotated_energy < 1e-12);
  CHECK(errors.consistent_kinetic < 1e-12);
  CHECK(errors.virtual_tet_kinetic < 1e-12);
  CHECK(errors.row_sum_kinetic < 1e-12);
  CHECK(errors.far_values < 1e-15);
}

} // namespace

TEST_CASE("cut state transfer: a sheet that grows keeps the field, both strain energies and the kinetic energy") {
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {5, 5, 5});
  const auto neighbours = std::make_shared<const kerf::TetNeighbours>(kerf::tet_neighbours(mesh));
  const Sheets sheets = make_sheets();
  const CutModel uncut(mesh, {}, neighbours), short_cut(mesh, {sheets.a_short}, neighbours), long_cut(mesh, {sheets.a_long}, neighbours);
  REQUIRE(short_cut.enrichment.num_enrichments() > 0);
  REQUIRE(long_cut.enrichment.num_enrichments() > short_cut.enrichment.num_enrichments());
  std::mt19937 rng(7);

  SUBCASE("from no cut to the short sheet: every enrichment starts at 0") {
    const TransferErrors errors = transfer_and_measure(mesh, uncut, short_cut, rng);
    check_round_off(errors);
    CHECK(errors.new_at_zero == short_cut.enrichment.num_enrichments());
    CHECK(errors.kept == 0);
  }
  SUBCASE("from the short sheet to the long one: the old enrichments kept, the new ones at 0") {
    const TransferErrors errors = transfer_and_measure(mesh, short_cut, long_cut, rng);
    check_round_off(errors);
    CHECK(errors.kept == short_cut.enrichment.num_enrichments());
    CHECK(errors.new_at_zero == long_cut.enrichment.num_enrichments() - short_cut.enrichment.num_enrichments());
    CHECK(errors.most_heirs == 1);
  }
}

TEST_CASE("cut state transfer: a crossing sheet splits old far parts in two, and both halves keep the old value") {
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {5, 5, 5});
  const auto neighbours = std::make_shared<const kerf::TetNeighbours>(kerf::tet_neighbours(mesh));
  const Sheets sheets = make_sheets();
  const CutModel one(mesh, {sheets.a_long}, neighbours), crossed(mesh, {sheets.a_long, sheets.b}, neighbours);
  REQUIRE(crossed.enrichment.most_enrichments >= 3); // a node of the junction: four parts
  std::mt19937 rng(11);
  const TransferErrors errors = transfer_and_measure(mesh, one, crossed, rng);
  check_round_off(errors);
  // Some old far part is now two parts of its node's support, each with its own enrichment.
  CHECK(errors.most_heirs >= 2);
  CHECK(errors.new_at_zero > 0);
}

TEST_CASE("cut state transfer on Tet10: the field, the linear energy and the kinetic energy kept") {
  // The 3 x 3 x 3 box made Tet10 (its mid-edge nodes at multiples of 1/6; the sheets miss them).
  // The corotated energy is not a polynomial on a Tet10 piece (the rotation varies inside it),
  // so rules on different pieces integrate it differently: measured (3.9e-5 relative), not
  // asserted. The rest came out bitwise equal, as on Tet4.
  const kerf::TetMesh mesh = kerf::tet10_from_tet4(kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {3, 3, 3}));
  const auto neighbours = std::make_shared<const kerf::TetNeighbours>(kerf::tet_neighbours(mesh));
  const Sheets sheets = make_sheets();
  const CutModel short_cut(mesh, {sheets.a_short}, neighbours), long_cut(mesh, {sheets.a_long}, neighbours);
  REQUIRE(long_cut.enrichment.num_enrichments() > short_cut.enrichment.num_enrichments());
  std::mt19937 rng(5);
  const TransferErrors errors = transfer_and_measure(mesh, short_cut, long_cut, rng);
  MESSAGE("Tet10: field " << errors.field << ", linear energy " << errors.linear_energy << ", corotated energy " << errors.corotated_energy
                          << ", kinetic consistent " << errors.consistent_kinetic << " virtual tet " << errors.virtual_tet_kinetic);
  CHECK(errors.field < 1e-12);
  CHECK(errors.linear_energy < 1e-12);
  CHECK(errors.consistent_kinetic < 1e-12);
  CHECK(errors.virtual_tet_kinetic < 1e-12);
  CHECK(errors.far_values < 1e-15);
  CHECK(errors.kept == short_cut.enrichment.num_enrichments());
}

TEST_CASE("cut state transfer: a vector of the wrong size, or models on different meshes, are refused") {
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {5, 5, 5});
  const auto neighbours = std::make_shared<const kerf::TetNeighbours>(kerf::tet_neighbours(mesh));
  const Sheets sheets = make_sheets();
  const CutModel short_cut(mesh, {sheets.a_short}, neighbours), long_cut(mesh, {sheets.a_long}, neighbours);
  const Eigen::Index n = 3 * short_cut.model.num_dof_nodes();
  CHECK_THROWS_AS(kerf::transfer_cut_state(short_cut.model, long_cut.model, Eigen::VectorXd::Zero(n - 1)), std::invalid_argument);
  CHECK_THROWS_AS(kerf::transfer_cut_state(short_cut.model, long_cut.model, Eigen::VectorXd::Zero(n + 3)), std::invalid_argument);
  // The long model's vector given as if it were the short one's.
  CHECK_THROWS_AS(kerf::transfer_cut_state(short_cut.model, long_cut.model, Eigen::VectorXd::Zero(3 * long_cut.model.num_dof_nodes())),
                  std::invalid_argument);
  CHECK_NOTHROW(kerf::transfer_cut_state(short_cut.model, long_cut.model, Eigen::VectorXd::Zero(n)));
  const kerf::TetMesh other = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {4, 4, 4});
  const CutModel elsewhere(other, {sheets.a_long}, std::make_shared<const kerf::TetNeighbours>(kerf::tet_neighbours(other)));
  CHECK_THROWS_AS(kerf::transfer_cut_state(short_cut.model, elsewhere.model, Eigen::VectorXd::Zero(n)), std::invalid_argument);
}

namespace {

// The L2 norm of the field of u on `model`, and of its difference to the field of w on `other`,
// over every tet, at the model's own quadrature points.
std::pair<double, double> field_norms(const kerf::CutXfemModel& model, const Eigen::VectorXd& u, const kerf::CutXfemModel& other,
                                      const Eigen::VectorXd& w) {
  const kerf::TetMesh& mesh = model.mesh();
  double norm = 0.0, difference = 0.0;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    model.for_each_slot_value(t, [&](int, double weight, const Eigen::VectorXd& g) {
      Eigen::Vector3d x = Eigen::Vector3d::Zero();
      for (int a = 0; a < mesh.nodes_per_tet(); ++a) x += g[a] * mesh.nodes.row(mesh.tets(t, a)).transpose();
      const Eigen::Vector3d here = model.displacement_at(u, t, x), there = other.displacement_at(w, t, x);
      norm += weight * here.squaredNorm();
      difference += weight * (here - there).squaredNorm();
    });
  return {std::sqrt(norm), std::sqrt(difference)};
}

} // namespace

TEST_CASE("cut state transfer with branch functions: the fit near the front keeps the energies, keeping the branch values does not") {
  // The box pulled open across sheet A (y = 0.47 behind the front, x < 0.45): the face y = 0
  // held, the face y = 1 lifted by 1 cm, solved on the short cut; then the sheet grows to the
  // long cut (front at x ~ 0.75) and the state is carried over, the static field as the
  // displacement and, to weigh the kinetic energy, as the velocity too. Branch functions on the
  // topological rule, with the blending rules chapter 7 uses (graded once, scene_crack_tip.hpp).
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {5, 5, 5});
  const Sheets sheets = make_sheets();
  const kerf::BranchRules rules{.blending_depth = 1};
  const kerf::CrackTipBody short_cut(mesh, {sheets.a_short}, tissue, kerf::TipTreatment::topological, 0.0, rules);
  const kerf::CrackTipBody long_cut(mesh, {sheets.a_long}, tissue, kerf::TipTreatment::topological, 0.0, rules);
  REQUIRE(short_cut.branch() != nullptr);
  REQUIRE(long_cut.branch() != nullptr);
  kerf::NodeRegion bottom, top;
  bottom.box_max = {1, 0, 1};
  top.box_min = {0, 1, 0};
  top.box_max = {1, 1, 1};
  const std::vector<kerf::DirichletNodes> held{{kerf::nodes_in_region(mesh, bottom), {0, 0, 0}}, {kerf::nodes_in_region(mesh, top), {0, 0.01, 0}}};
  const kerf::DofMap dofs = kerf::make_cut_xfem_dof_map(short_cut.model(), held);
  const Eigen::VectorXd u_old =
      kerf::solve_linear_cut_xfem(short_cut.model(), dofs, Eigen::VectorXd::Zero(3 * short_cut.model().num_dof_nodes()), kerf::SolverSettings{});
  REQUIRE(u_old.allFinite());

  const kerf::DofMap new_dofs = kerf::make_cut_xfem_dof_map(long_cut.model(), held);
  const auto start = std::chrono::steady_clock::now();
  const kerf::CutStateTransfer fit(short_cut.model(), long_cut.model(), kerf::BranchStateRule::fit, &new_dofs);
  const Eigen::VectorXd u_fit = fit(u_old);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  const Eigen::VectorXd u_kept = kerf::CutStateTransfer(short_cut.model(), long_cut.model(), kerf::BranchStateRule::keep_values)(u_old);
  REQUIRE(u_fit.allFinite());
  REQUIRE(fit.num_fitted() > 0);

  const auto change = [&](bool corotated, const Eigen::VectorXd& u_new) {
    return long_cut.model().energy(u_new, corotated) / short_cut.model().energy(u_old, corotated) - 1.0;
  };
  const auto kinetic_change = [&](const Eigen::VectorXd& v_new) {
    return kinetic(kerf::assemble_cut_xfem_mass(long_cut.model(), tissue.density, support::subtets), v_new) /
               kinetic(kerf::assemble_cut_xfem_mass(short_cut.model(), tissue.density, support::subtets), u_old) -
           1.0;
  };
  const auto [norm, error_fit] = field_norms(long_cut.model(), u_fit, short_cut.model(), u_old);
  const double error_kept = field_norms(long_cut.model(), u_kept, short_cut.model(), u_old).second;
  const double linear_fit = change(false, u_fit), corotated_fit = change(true, u_fit), kinetic_fit = kinetic_change(u_fit);
  const double linear_kept = change(false, u_kept), kinetic_kept = kinetic_change(u_kept);
  MESSAGE("branch transfer (" << ms << " ms, " << fit.num_fitted() << " DOF nodes fitted at " << fit.num_fit_points()
                              << " points): elastic energy change " << linear_fit << " linear, " << corotated_fit << " corotated, kinetic "
                              << kinetic_fit << "; with the values kept " << linear_kept << " and " << kinetic_kept
                              << "; L2 field error " << error_fit / norm << " fitted, " << error_kept / norm << " kept");
  // Measured: +0.19 % elastic (linear), the kinetic energy as printed; the old rule +132 %. A
  // change of 1 % at a rebuild is what the fit is held to: small against the dissipation of a
  // step of chapter 7's damped run, and five times the measured one.
  CHECK(std::abs(linear_fit) < 0.01);
  CHECK(std::abs(corotated_fit) < 0.01);
  CHECK(std::abs(kinetic_fit) < 0.01);
  CHECK(linear_kept > 0.5); // the baseline the fit replaces does inject energy
  CHECK(error_fit < error_kept);
  // The held DOFs keep their prescribed values: the standard DOFs of the held nodes are u_old's.
  for (const kerf::DirichletNodes& condition : held)
    for (const int v : condition.nodes) CHECK(u_fit.segment<3>(3 * v) == u_old.segment<3>(3 * v));
}

namespace {

// The largest difference of the old and the new field at points strictly inside every cell of
// every tet the new cuts meet, relative to the state's largest value; and in how many of them.
std::pair<double, int> field_difference(const kerf::TetMesh& mesh, const CutModel& from, const Eigen::VectorXd& u_old, const CutModel& to,
                                        const Eigen::VectorXd& u_new) {
  double worst = 0.0;
  int points = 0;
  const double scale = u_old.cwiseAbs().maxCoeff();
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const int e = to.pieces.entry[static_cast<std::size_t>(t)];
    if (e < 0) continue;
    for (const kerf::ConvexCell& cell : to.pieces.tets[static_cast<std::size_t>(e)].cells) {
      const Eigen::Vector3d x = kerf::convex_cell_inner_point(cell);
      const Eigen::Vector3d before = from.model.displacement_at(u_old, t, x), after = to.model.displacement_at(u_new, t, x);
      REQUIRE(before.allFinite());
      REQUIRE(after.allFinite());
      worst = std::max(worst, (after - before).norm() / scale);
      ++points;
    }
  }
  return {worst, points};
}

kerf::TriangleSurface plane_through_box(int axis, double at) {
  // A square 3 x 3 about the unit box, normal along `axis`, at coordinate `at`.
  Eigen::Vector3d origin = Eigen::Vector3d::Constant(-1.0), e1 = Eigen::Vector3d::Zero(), e2 = Eigen::Vector3d::Zero();
  origin[axis] = at;
  e1[(axis + 1) % 3] = 3.0;
  e2[(axis + 2) % 3] = 3.0;
  return kerf::rectangle_surface(kerf::RectangleCut(origin, e1, e2));
}

} // namespace

TEST_CASE("cut state transfer: a second sheet through nodes that lie on the first keeps the field, though their home part changes") {
  // The plane z = 0.4 runs through a layer of nodes of the 5 x 5 x 5 box, so each node of that
  // layer has its home part above it (H(0) = +1, surface_enrichment.hpp) and one enrichment
  // below. The plane x = 0.4 then passes through the nodes of the line x = z = 0.4, splitting
  // each support into four parts, renumbered: the part that is now the home part need not lie in
  // the old home part. The new u_i must then take the old field's value on the new home part,
  // not the old u_i (which is the old home part's).
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {5, 5, 5});
  const auto neighbours = std::make_shared<const kerf::TetNeighbours>(kerf::tet_neighbours(mesh));
  const CutModel one(mesh, {plane_through_box(2, 0.4)}, neighbours), two(mesh, {plane_through_box(2, 0.4), plane_through_box(0, 0.4)}, neighbours);
  REQUIRE(one.enrichment.num_enrichments() > 0);
  std::mt19937 rng(23);
  const Eigen::VectorXd u_old = random_vector(3 * one.model.num_dof_nodes(), rng);
  const Eigen::VectorXd u_new = kerf::transfer_cut_state(one.model, two.model, u_old);
  // Nodes whose u_i changed: the home part switched.
  int switched = 0;
  for (Eigen::Index i = 0; i < mesh.num_nodes(); ++i) switched += u_new.segment<3>(3 * i) != u_old.segment<3>(3 * i) ? 1 : 0;
  const auto [worst, points] = field_difference(mesh, one, u_old, two, u_new);
  MESSAGE("node on two sheets: " << switched << " nodes' home part switched; field difference " << worst << " at " << points << " points");
  CHECK(switched > 0); // the case this test is about occurs
  CHECK(worst < 1e-12); // the field is kept to round-off (one rounding of u + a - u)
}

TEST_CASE("cut state transfer: an enrichment the new DofMap holds starts at its held 0, and only its sliver's field jumps") {
  // The old cut z = 0.5 gives each node of the layer z = 0.4 a far part above it, up to z = 0.6.
  // A second sheet at z = 0.6 - 1e-5 splits that far part into a slab of 0.1 and one of 1e-5,
  // below eq. 22's 1e-3 here: the new DofMap holds the sliver's enrichment, and the step will
  // move it with u_i. The transfer starts it there (not at the old far value, which the first
  // step would snap away), so every other piece keeps the old field exactly and the sliver alone
  // changes, by little: its phantom value jumps, but N_i is small on it.
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {5, 5, 5});
  const auto neighbours = std::make_shared<const kerf::TetNeighbours>(kerf::tet_neighbours(mesh));
  const CutModel one(mesh, {plane_through_box(2, 0.5)}, neighbours),
      two(mesh, {plane_through_box(2, 0.5), plane_through_box(2, 0.6 - 1e-5)}, neighbours);
  const double epsilon = 1e-3;
  const kerf::DofMap dofs = kerf::make_cut_xfem_dof_map(two.model, {}, epsilon);
  const Eigen::Index N = mesh.num_nodes();
  std::vector<char> held(static_cast<std::size_t>(two.enrichment.num_enrichments()), 0);
  int num_held = 0;
  for (Eigen::Index k = 0; k < two.enrichment.num_enrichments(); ++k)
    if (dofs.free_index[static_cast<std::size_t>(3 * (N + k))] < 0) held[static_cast<std::size_t>(k)] = 1, ++num_held;
  REQUIRE(num_held > 0);
  std::mt19937 rng(29);
  const Eigen::VectorXd u_old = random_vector(3 * one.model.num_dof_nodes(), rng);
  const Eigen::VectorXd u_new = kerf::CutStateTransfer(one.model, two.model, kerf::BranchStateRule::fit, &dofs)(u_old);
  double held_values = 0.0;
  for (Eigen::Index k = 0; k < two.enrichment.num_enrichments(); ++k)
    if (held[static_cast<std::size_t>(k)]) held_values = std::max(held_values, u_new.segment<3>(3 * (N + k)).norm());
  CHECK(held_values == 0.0);
  // The field inside every cell of a piece on which no held enrichment acts: the old one.
  double worst = 0.0, largest_jump = 0.0;
  int compared = 0, skipped = 0;
  const double scale = u_old.cwiseAbs().maxCoeff();
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const int e = two.pieces.entry[static_cast<std::size_t>(t)];
    if (e < 0) continue;
    const kerf::TetPieces& tp = two.pieces.tets[static_cast<std::size_t>(e)];
    for (int p = 0; p < two.pieces.num_pieces(t); ++p) {
      bool glued = false;
      for (int a = 0; a < 4; ++a) {
        const int k = two.enrichment.active_enrichment(two.pieces, t, a, p);
        glued = glued || (k >= 0 && held[static_cast<std::size_t>(k)]);
      }
      for (const int c : tp.pieces[static_cast<std::size_t>(p)].cells) {
        const Eigen::Vector3d x = kerf::convex_cell_inner_point(tp.cells[static_cast<std::size_t>(c)]);
        const double difference = (two.model.displacement_at(u_new, t, x) - one.model.displacement_at(u_old, t, x)).norm() / scale;
        if (glued) {
          largest_jump = std::max(largest_jump, difference);
          ++skipped;
        } else {
          worst = std::max(worst, difference);
          ++compared;
        }
      }
    }
  }
  MESSAGE("held enrichments: " << num_held << "; field difference " << worst << " at " << compared << " points off the slivers, up to "
                               << largest_jump << " at " << skipped << " points on them");
  REQUIRE(compared > 0);
  REQUIRE(skipped > 0);
  CHECK(worst < 1e-12);
  // On the slivers the field moves by N_i times the jump of the held part's phantom value, and
  // N_i of a node of the layer z = 0.4 is ~1e-5 / 0.2 in a slab 1e-5 below z = 0.6: measured
  // 3.7e-5 of the state's scale. (The rule alone gave the held enrichments the far part's value,
  // which the first step then snapped to 0.)
  CHECK(largest_jump < 1e-3);
}
