// Linear XFEM against plain FEM solves that need no enrichment: a cut that misses the body
// (chapter 1's system), a bar cut clean through along a node layer (two sub-meshes) and
// obliquely through elements (two "phantom node" meshes with volume-scaled stiffnesses), a
// half-depth cut along faces (the split_mesh_along_cut reference of Schoch et al. section 6.1) and
// cuts that leave slivers (the minimum volume fraction rule).
#include "xfem_test_support.hpp"

#include "kerf/cut/split_mesh_along_cut.hpp"
#include "kerf/fem/assemble_loads.hpp"
#include "kerf/fem/solve_linear_static.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/fem/tet_stiffness.hpp"
#include "kerf/solve/linear_solver.hpp"
#include "kerf/xfem/xfem_model.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

using namespace xfem_test;

namespace {

const kerf::LinearMaterial material{300e3, 0.35, 1070.0};
const Eigen::Vector3d body_force = 1070.0 * Eigen::Vector3d(9.81, 0.0, -9.81);

using Field = std::function<Eigen::Vector3d(const Eigen::Vector3d&)>;

// Non-rigid end displacements: the z = 0 face pushed down and sheared, the z = L face pulled up
// and sheared the other way. Each half of a bar cut through is held at one end only.
Eigen::Vector3d bottom_end(const Eigen::Vector3d& x) { return {0.001 * x.y() / 0.06, 0.0005, -0.002 + 0.001 * x.x() / 0.03}; }
Eigen::Vector3d top_end(const Eigen::Vector3d& x) { return {-0.0005, 0.001 * x.x() / 0.03, 0.002 + 0.0005 * x.y() / 0.06}; }

// One Dirichlet condition per node of `mesh` where `where` holds, at `field` of its position.
std::vector<kerf::DirichletNodes> conditions_where(const kerf::TetMesh& mesh, const std::function<bool(const Eigen::Vector3d&)>& where,
                                                   const Field& field) {
  std::vector<kerf::DirichletNodes> conditions;
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v)
    if (where(node(mesh, v))) conditions.push_back({{static_cast<int>(v)}, field(node(mesh, v))});
  return conditions;
}

bool at_bottom(const Eigen::Vector3d& x) { return std::abs(x.z()) < 1e-12; }
bool at_top(const Eigen::Vector3d& x) { return std::abs(x.z() - beam_length) < 1e-12; }

std::vector<kerf::DirichletNodes> both_ends(const kerf::TetMesh& mesh) {
  auto conditions = conditions_where(mesh, at_bottom, bottom_end);
  const auto top = conditions_where(mesh, at_top, top_end);
  conditions.insert(conditions.end(), top.begin(), top.end());
  return conditions;
}

double max_abs(const Eigen::VectorXd& v) { return v.cwiseAbs().maxCoeff(); }

} // namespace

TEST_CASE("xfem reference: a cut whose rectangle misses the body gives chapter 1's system exactly") {
  const kerf::TetMesh mesh = beam({2, 3, 8});
  // The plane z = 0.11 crosses a layer of elements; z = 0.1 runs along a node layer. In both
  // cases the rectangle lies 1 m away from the beam.
  for (const double z : {0.11, 0.1}) {
    CAPTURE(z);
    const kerf::RectangleCut cut({1.0, 1.0, z}, {0.05, 0, 0}, {0, 0.05, 0});
    const kerf::Enrichment e = kerf::make_enrichment(mesh, cut);
    CHECK(e.num_enriched() == 0);
    CHECK(e.cut_tets == 0);
    if (z == 0.11) CHECK(std::count(e.tet_side.begin(), e.tet_side.end(), kerf::TetSide::beyond) > 0);
    const kerf::XfemModel model(mesh, material, e);
    REQUIRE(model.num_dof_nodes() == mesh.num_nodes());
    const auto conditions = both_ends(mesh);
    const Eigen::VectorXd f = kerf::assemble_gravity(mesh, material.density, body_force / material.density);
    const Eigen::VectorXd u_fem = kerf::solve_linear_static(mesh, material, kerf::make_dof_map(mesh.num_nodes(), conditions), f, {});
    const Eigen::VectorXd u_xfem = kerf::solve_linear_xfem(model, kerf::make_xfem_dof_map(model, conditions), f, {});
    // Same element matrices, same assembly order, same CHOLMOD factorisation: equal up to the
    // last bits (1e-14 relative leaves room for a different summation order only).
    const double difference = max_abs(u_fem - u_xfem) / max_abs(u_fem);
    MESSAGE("uncut XFEM vs chapter 1: relative difference " << difference);
    CHECK(difference <= 1e-14);
  }
}

TEST_CASE("xfem reference: a bar cut through along a node layer is its two halves solved apart") {
  const kerf::TetMesh mesh = beam({2, 3, 8}); // node layers every 0.025 m: z = 0.1 is one
  const kerf::RectangleCut cut({-0.01, -0.01, 0.1}, {0.05, 0, 0}, {0, 0.08, 0});
  const kerf::Enrichment e = kerf::make_enrichment(mesh, cut);
  const kerf::XfemModel model(mesh, material, e);
  // Enriched: exactly the 3 x 4 nodes of the layer z = 0.1.
  std::vector<int> layer;
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v)
    if (std::abs(mesh.nodes(v, 2) - 0.1) < 1e-12) layer.push_back(static_cast<int>(v));
  CHECK(e.enriched_nodes == layer);
  CHECK(e.cut_tets == 0);

  const Eigen::VectorXd f = xfem_gravity(model, body_force);
  const Eigen::VectorXd u = kerf::solve_linear_xfem(model, kerf::make_xfem_dof_map(model, both_ends(mesh)), f, {});
  REQUIRE(u.allFinite());

  double worst = 0.0, scale = 0.0;
  for (const int side : {+1, -1}) {
    std::vector<int> original;
    const kerf::TetMesh half = submesh(
        mesh, [&](Eigen::Index t) { return side * (corners(mesh, t).col(2).mean() - 0.1) > 0.0; }, original);
    const auto conditions = conditions_where(half, side > 0 ? at_top : at_bottom, side > 0 ? top_end : bottom_end);
    const Eigen::VectorXd f_half = kerf::assemble_gravity(half, material.density, body_force / material.density);
    const Eigen::VectorXd u_half =
        kerf::solve_linear_static(half, material, kerf::make_dof_map(half.num_nodes(), conditions), f_half, {});
    scale = std::max(scale, max_abs(u_half));
    // Nodal values: every node of the half, the nodes on the cut by their value on this side.
    for (std::size_t s = 0; s < original.size(); ++s)
      worst = std::max(worst, (node_side_value(model, u, original[s], side) - u_half.segment<3>(3 * static_cast<Eigen::Index>(s)))
                                  .cwiseAbs()
                                  .maxCoeff());
    // The same through the model's own side_displacement, corner by corner of the tets on this side.
    std::vector<int> renumber(static_cast<std::size_t>(mesh.num_nodes()), -1);
    for (std::size_t s = 0; s < original.size(); ++s) renumber[static_cast<std::size_t>(original[s])] = static_cast<int>(s);
    for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
      if (e.tet_side[static_cast<std::size_t>(t)] != (side > 0 ? kerf::TetSide::above : kerf::TetSide::below)) continue;
      for (int c = 0; c < 4; ++c) {
        const int s = renumber[static_cast<std::size_t>(mesh.tets(t, c))];
        REQUIRE(s >= 0);
        worst = std::max(worst, (model.side_displacement(u, t, c, side) - u_half.segment<3>(3 * s)).cwiseAbs().maxCoeff());
      }
    }
  }
  // Both are the same linear system in different variables (u_b = u - a on the cut): they agree
  // to round-off amplified by the condition number (about 1e5 here), far below 1e-10.
  MESSAGE("node-layer cut vs two halves: max difference " << worst << " m of max |u| " << scale << " m");
  CHECK(worst <= 1e-10 * scale);
}

TEST_CASE("xfem reference: an oblique cut through elements is two phantom-node meshes with V_side/V stiffnesses") {
  const kerf::TetMesh mesh = beam({2, 3, 8});
  const Eigen::Vector3d point(0.015, 0.03, 0.1), normal(0.3, 0.2, 1.0);
  const kerf::RectangleCut cut = plane_cut(point, normal);
  const kerf::Enrichment e = kerf::make_enrichment(mesh, cut);
  // The plane was chosen so that no corner is within the minimum volume fraction of it.
  REQUIRE(e.snapped_nodes == 0);
  CHECK(e.front_nodes == 0);
  CHECK(e.cut_tets > 0);
  const kerf::XfemModel model(mesh, material, e);

  // The raw signed distances and, from them, every tet's fraction above.
  Eigen::VectorXd lambda(mesh.num_nodes());
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) lambda[v] = cut.signed_distance_to_plane(node(mesh, v));
  std::vector<double> fraction(static_cast<std::size_t>(mesh.num_tets()));
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    Eigen::Vector4d l;
    for (int a = 0; a < 4; ++a) l[a] = lambda[mesh.tets(t, a)];
    const kerf::ClippedTet clipped = kerf::clip_tet(corners(mesh, t), l);
    fraction[static_cast<std::size_t>(t)] = clipped.V_a / (clipped.V_a + clipped.V_b);
    CHECK(std::abs(fraction[static_cast<std::size_t>(t)] - e.fraction_above[static_cast<std::size_t>(t)]) <= 1e-14);
  }

  const Eigen::VectorXd f = xfem_gravity(model, body_force);
  const Eigen::VectorXd u = kerf::solve_linear_xfem(model, kerf::make_xfem_dof_map(model, both_ends(mesh)), f, {});
  REQUIRE(u.allFinite());

  double worst = 0.0, scale = 0.0;
  for (const int side : {+1, -1}) {
    // The phantom-node mesh of this side: every tet with volume on it, the nodes on the other
    // side included. A Tet4's strain is constant, so the piece's stiffness is exactly
    // (V_side / V) K, and its gravity load is int_piece Phi_i rho g.
    const auto side_fraction = [&](Eigen::Index t) {
      const double fa = fraction[static_cast<std::size_t>(t)];
      return side > 0 ? fa : 1.0 - fa;
    };
    std::vector<int> original;
    const kerf::TetMesh half = submesh(mesh, [&](Eigen::Index t) { return side_fraction(t) > 0.0; }, original);
    std::vector<Eigen::Index> parent;
    for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
      if (side_fraction(t) > 0.0) parent.push_back(t);
    const auto conditions = conditions_where(half, side > 0 ? at_top : at_bottom, side > 0 ? top_end : bottom_end);
    const kerf::DofMap dofs = kerf::make_dof_map(half.num_nodes(), conditions);
    Eigen::VectorXd f_half = Eigen::VectorXd::Zero(3 * half.num_nodes());
    for (Eigen::Index k = 0; k < half.num_tets(); ++k) {
      const Eigen::Index t = parent[static_cast<std::size_t>(k)];
      Eigen::Vector4d l;
      for (int a = 0; a < 4; ++a) l[a] = lambda[mesh.tets(t, a)];
      const Eigen::Vector4d integrals = piece_integrals(mesh, t, l, side);
      for (int a = 0; a < 4; ++a) f_half.segment<3>(3 * half.tets(k, a)) += integrals[a] * body_force;
    }
    kerf::SparseAssembler assembler(half.tets, dofs);
    Eigen::VectorXd rhs = dofs.restrict_to_free(f_half);
    for (Eigen::Index k = 0; k < half.num_tets(); ++k) {
      const Eigen::Index t = parent[static_cast<std::size_t>(k)];
      const Eigen::Matrix<double, 12, 12> K = side_fraction(t) * kerf::tet4_stiffness(corners(half, k), material);
      assembler.add_element<12>(k, K, rhs);
    }
    auto solver = kerf::make_linear_solver({});
    solver->analyze_pattern(assembler.matrix());
    solver->factorize(assembler.matrix());
    Eigen::VectorXd u_free = Eigen::VectorXd::Zero(dofs.num_free);
    solver->solve(rhs, u_free);
    const Eigen::VectorXd u_half = dofs.expand(u_free);
    scale = std::max(scale, max_abs(u_half));
    for (std::size_t s = 0; s < original.size(); ++s) {
      const int v = original[s];
      // A node of this phantom mesh is on this side or enriched: its value here is defined.
      CHECK((e.node_sign[static_cast<std::size_t>(v)] == side || e.enriched_index[static_cast<std::size_t>(v)] >= 0));
      worst = std::max(worst, (node_side_value(model, u, v, side) - u_half.segment<3>(3 * static_cast<Eigen::Index>(s))).cwiseAbs().maxCoeff());
    }
  }
  double smallest = 1.0;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    if (e.tet_side[static_cast<std::size_t>(t)] == kerf::TetSide::cut)
      smallest = std::min({smallest, fraction[static_cast<std::size_t>(t)], 1.0 - fraction[static_cast<std::size_t>(t)]});
  // Same system in other variables; the smallest piece (a fraction of about 1e-3 here) raises
  // the condition number by its inverse, still leaving round-off far below 1e-10.
  MESSAGE("oblique cut vs phantom-node meshes: max difference " << worst << " m of max |u| " << scale << " m, " << e.cut_tets
                                                                 << " cut tets, smallest fraction " << smallest);
  CHECK(worst <= 1e-10 * scale);
}

TEST_CASE("xfem reference: a half-depth cut along a node layer is the split-mesh FEM solve, node by node") {
  const kerf::TetMesh mesh = beam({2, 3, 8}); // x = 0.015 and z = 0.1 are node planes
  const kerf::RectangleCut cut({0, 0, 0.1}, {0.015, 0, 0}, {0, 0.06, 0});
  const kerf::Enrichment e = kerf::make_enrichment(mesh, cut);
  // The cut runs along faces: tets touch it, none is cut, and no level set value is NaN.
  CHECK(e.level_set.lambda.allFinite());
  CHECK(std::all_of(e.fraction_above.begin(), e.fraction_above.end(), [](double f) { return std::isfinite(f); }));
  CHECK(e.classification.count(kerf::ElementCutState::touched) > 0);
  CHECK(e.cut_tets == 0);
  CHECK(e.classification.count(kerf::ElementCutState::completely_cut) == 0);
  CHECK(e.classification.count(kerf::ElementCutState::partially_cut) == 0);
  REQUIRE(e.num_enriched() > 0);
  const kerf::XfemModel model(mesh, material, e);

  const kerf::SplitMesh split = kerf::split_mesh_along_cut(mesh, cut, 1e-9);
  // The enriched nodes are the duplicated ones: the cut's surface nodes, not its front x = 0.015.
  CHECK(e.enriched_nodes == split.duplicate_of);

  // Clamped at z = 0, gravity across the beam and along it: the cut opens.
  const auto conditions = conditions_where(mesh, at_bottom, [](const Eigen::Vector3d&) { return Eigen::Vector3d::Zero(); });
  const Eigen::VectorXd u = kerf::solve_linear_xfem(model, kerf::make_xfem_dof_map(model, conditions), xfem_gravity(model, body_force), {});
  REQUIRE(u.allFinite());
  const auto split_conditions =
      conditions_where(split.mesh, at_bottom, [](const Eigen::Vector3d&) { return Eigen::Vector3d::Zero(); });
  const Eigen::VectorXd u_split = kerf::solve_linear_static(
      split.mesh, material, kerf::make_dof_map(split.mesh.num_nodes(), split_conditions),
      kerf::assemble_gravity(split.mesh, material.density, body_force / material.density), {});

  double worst = 0.0, opening = 0.0;
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) {
    const int own = e.node_sign[static_cast<std::size_t>(v)];
    worst = std::max(worst, (node_side_value(model, u, static_cast<int>(v), own) - u_split.segment<3>(3 * v)).cwiseAbs().maxCoeff());
  }
  for (std::size_t k = 0; k < split.duplicate_of.size(); ++k) {
    const int v = split.duplicate_of[k];
    CHECK(e.node_sign[static_cast<std::size_t>(v)] == +1); // on the cut counts as above
    const Eigen::Vector3d below = node_side_value(model, u, v, -1);
    worst = std::max(worst, (below - u_split.segment<3>(3 * (mesh.num_nodes() + static_cast<Eigen::Index>(k)))).cwiseAbs().maxCoeff());
    opening = std::max(opening, (u.segment<3>(3 * v) - below).norm());
  }
  const double scale = max_abs(u_split);
  // XFEM on a cut-conforming mesh is the duplicated-node FEM in other variables: round-off only.
  MESSAGE("half-depth node-layer cut vs split mesh: max difference " << worst << " m, max |u| " << scale << " m, max opening "
                                                                     << opening << " m");
  CHECK(worst <= 1e-10 * scale);
  CHECK(opening > 1e-3 * scale); // and the cut does open
}

TEST_CASE("xfem reference: slivers below the minimum volume fraction are snapped onto the cut") {
  const kerf::TetMesh mesh = beam({2, 3, 8});
  const double h = 0.025; // the layer height; the plane z = 0.1 + delta cuts the layer [0.1, 0.125]
  const auto solve = [&](const kerf::Enrichment& e) {
    const kerf::XfemModel model(mesh, material, e);
    return kerf::solve_linear_xfem(model, kerf::make_xfem_dof_map(model, both_ends(mesh)), xfem_gravity(model, body_force), {});
  };
  const kerf::Enrichment reference_e = kerf::make_enrichment(mesh, plane_cut({0.015, 0.03, 0.1}, Eigen::Vector3d::UnitZ()));
  REQUIRE(reference_e.cut_tets == 0);
  const kerf::XfemModel reference_model(mesh, material, reference_e);
  const Eigen::VectorXd reference = solve(reference_e);

  // The difference of two solutions, side by side: each node's values on the sides it has.
  const auto difference = [&](const kerf::XfemModel& model, const Eigen::VectorXd& u) {
    double d = 0.0;
    for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) {
      for (const int side : {+1, -1}) {
        const auto has_side = [&](const kerf::XfemModel& m) {
          const auto k = static_cast<std::size_t>(v);
          return m.enrichment().node_sign[k] == side || m.enrichment().enriched_index[k] >= 0;
        };
        if (!has_side(model) || !has_side(reference_model)) continue;
        d = std::max(d, (node_side_value(model, u, static_cast<int>(v), side) -
                         node_side_value(reference_model, reference, static_cast<int>(v), side))
                            .cwiseAbs()
                            .maxCoeff());
      }
    }
    return d / max_abs(reference.head(3 * mesh.num_nodes()));
  };

  // A tet with one corner on the layer z = 0.1 and three on z = 0.125 keeps a corner piece of
  // fraction (delta / h)^3 below the plane.
  for (const double target : {1e-12, 1e-6}) {
    CAPTURE(target);
    const double delta = h * std::cbrt(target);
    const kerf::RectangleCut cut = plane_cut({0.015, 0.03, 0.1 + delta}, Eigen::Vector3d::UnitZ());
    double smallest_raw = 1.0;
    for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
      Eigen::Vector4d l;
      for (int a = 0; a < 4; ++a) l[a] = cut.signed_distance_to_plane(node(mesh, mesh.tets(t, a)));
      if (l.minCoeff() >= 0.0 || l.maxCoeff() <= 0.0) continue;
      const kerf::ClippedTet clipped = kerf::clip_tet(corners(mesh, t), l);
      smallest_raw = std::min(smallest_raw, std::min(clipped.V_a, clipped.V_b) / (clipped.V_a + clipped.V_b));
    }
    CHECK(smallest_raw == kerf_test::relative(target, 1e-3));

    const kerf::Enrichment e = kerf::make_enrichment(mesh, cut);
    CHECK(e.snapped_nodes > 0);
    CHECK(e.largest_snap <= delta * (1 + 1e-9));
    CHECK(e.level_set.lambda.allFinite());
    double smallest_kept = 1.0;
    for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
      const double fa = e.fraction_above[static_cast<std::size_t>(t)];
      CHECK(std::isfinite(fa));
      if (e.tet_side[static_cast<std::size_t>(t)] == kerf::TetSide::cut) smallest_kept = std::min({smallest_kept, fa, 1.0 - fa});
    }
    CHECK(smallest_kept >= e.minimum_volume_fraction);
    const kerf::XfemModel model(mesh, material, e);
    const Eigen::VectorXd u = solve(e);
    REQUIRE(u.allFinite());
    // The snapped cut lies within delta of the node layer (2.5e-6 m for 1e-12, 2.5e-4 m for
    // 1e-6), on a bar whose halves are L = 0.1 m long: moving the cut by delta changes the
    // solution by O(delta / L) (measured: 0.17 and 0.93 delta / L). So the bound is 1e-3 as long
    // as delta / L is below 5e-4, and 2 delta / L for the larger delta.
    const double d = difference(model, u);
    const double bound = std::max(1e-3, 2.0 * delta / 0.1);
    MESSAGE("fraction " << target << ": " << e.snapped_nodes << " nodes snapped (largest " << e.largest_snap << " m), "
                        << e.cut_tets << " tets still cut, smallest kept fraction " << smallest_kept
                        << ", relative difference to the node-layer cut " << d);
    CHECK(d <= bound);
    if (target == 1e-12) CHECK(d <= 1e-3);
  }

  // Without the rule, a 1e-6 sliver is kept and CHOLMOD still factorises K^X: the enriched
  // diagonal of a node on the big side scales with the fraction, so the condition number grows
  // by about 1e6 over the uncut one (about 1e11 here): solvable, but six digits are gone.
  const double delta = h * std::cbrt(1e-6);
  const kerf::Enrichment e = kerf::make_enrichment(mesh, plane_cut({0.015, 0.03, 0.1 + delta}, Eigen::Vector3d::UnitZ()),
                                                   kerf::EnrichmentSettings{0.0});
  CHECK(e.snapped_nodes == 0);
  const kerf::XfemModel model(mesh, material, e);
  const Eigen::VectorXd u = solve(e);
  REQUIRE(u.allFinite());
  const double d = difference(model, u);
  MESSAGE("minimum fraction 0, sliver 1e-6 kept: relative difference to the node-layer cut " << d);
  // The cut really is delta = 2.5e-4 m off the layer now (measured 2.45 delta / L): 4 delta / L.
  CHECK(d <= 4.0 * delta / 0.1);
}

TEST_CASE("xfem reference: a piece no condition holds is reported, and Tet10 or a foreign enrichment is refused") {
  const kerf::TetMesh mesh = beam({2, 3, 8});
  const kerf::Enrichment e = kerf::make_enrichment(mesh, plane_cut({0.015, 0.03, 0.1}, {0.3, 0.2, 1.0}));
  const kerf::XfemModel model(mesh, material, e);
  // Clamped at z = 0 only: the piece above floats, K^X_ff is singular.
  const auto clamped = conditions_where(mesh, at_bottom, [](const Eigen::Vector3d&) { return Eigen::Vector3d::Zero(); });
  bool threw = false;
  try {
    kerf::solve_linear_xfem(model, kerf::make_xfem_dof_map(model, clamped), xfem_gravity(model, body_force), {});
  } catch (const std::runtime_error& error) {
    threw = true;
    CHECK(std::string(error.what()).find("Dirichlet") != std::string::npos);
  }
  CHECK(threw);

  kerf::TetMesh tet10 = mesh;
  tet10.tets.conservativeResize(Eigen::NoChange, 10);
  tet10.tets.rightCols(6).setZero(); // only the order matters: make_enrichment refuses before reading them
  CHECK_THROWS_AS(kerf::make_enrichment(tet10, plane_cut({0.015, 0.03, 0.1}, {0, 0, 1})), std::invalid_argument);
  const kerf::TetMesh other = beam({2, 3, 4});
  CHECK_THROWS_AS(kerf::XfemModel(other, material, e), std::invalid_argument);
}

TEST_CASE("xfem reference: snapping keeps each node's side and stops at a tenth of the shortest edge") {
  const kerf::TetMesh mesh = beam({2, 3, 8});
  // The plane 1e-6 of a layer height above the node layer z = 0.1: the corners on that layer
  // are snapped up onto the cut (they were below it); the plane as far below z = 0.125 puts
  // the corners on that layer (above it) onto the cut from the other side.
  const double h = 0.025, delta = h * std::cbrt(1e-6);
  for (const double z : {0.1 + delta, 0.125 - delta}) {
    CAPTURE(z);
    const kerf::RectangleCut cut = plane_cut({0.015, 0.03, z}, Eigen::Vector3d::UnitZ());
    const kerf::Enrichment e = kerf::make_enrichment(mesh, cut);
    REQUIRE(e.snapped_nodes > 0);
    CHECK(e.snapped_nodes == static_cast<int>(e.snapped.size()));
    for (const int v : e.snapped) {
      CHECK(e.level_set.lambda[v] == 0.0);
      // The side it came from, not "above" for all: before, every snapped node became H = +1.
      CHECK(e.node_sign[static_cast<std::size_t>(v)] == (cut.signed_distance_to_plane(node(mesh, v)) > 0.0 ? 1 : -1));
    }
    // With the limit below the distance (delta = 2.5e-4 m; the shortest edge is 0.015 m, so a
    // limit of 1e-3 of it is 1.5e-5 m), nothing is snapped and the slivers are kept: still
    // solvable, and close to the snapped answer (both are within O(delta / L) of the layer cut).
    kerf::EnrichmentSettings limited;
    limited.maximum_snap_fraction = 1e-3;
    const kerf::Enrichment kept = kerf::make_enrichment(mesh, cut, limited);
    CHECK(kept.snapped_nodes == 0);
    CHECK(kept.kept_slivers > 0);
    const kerf::XfemModel model(mesh, material, kept);
    const Eigen::VectorXd u = kerf::solve_linear_xfem(model, kerf::make_xfem_dof_map(model, both_ends(mesh)), xfem_gravity(model, body_force), {});
    REQUIRE(u.allFinite());
  }
}

TEST_CASE("xfem reference: a tet beyond the front has no sides, and no enriched corner") {
  const kerf::TetMesh mesh = beam({3, 6, 19});
  const kerf::Enrichment e = kerf::make_enrichment(mesh, kerf::RectangleCut({0, 0, 0.1}, {0.015, 0, 0}, {0, 0.06, 0}));
  const kerf::XfemModel model(mesh, material, e);
  int beyond = 0;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    if (e.tet_side[static_cast<std::size_t>(t)] != kerf::TetSide::beyond) {
      CHECK(e.piece_fraction(t, +1) + e.piece_fraction(t, -1) == kerf_test::relative(1.0));
      continue;
    }
    ++beyond;
    CHECK(std::isnan(e.fraction_above[static_cast<std::size_t>(t)]));
    CHECK_THROWS_AS(e.piece_fraction(t, +1), std::logic_error);
    CHECK_FALSE(model.has_enriched_corner(t));
  }
  CHECK(beyond > 0);
}

TEST_CASE("xfem reference: an inverted tet built in code is refused by the XFEM model, naming it") {
  kerf::TetMesh mesh = beam({1, 1, 2});
  std::swap(mesh.tets(1, 0), mesh.tets(1, 1)); // tet 1 now has det J < 0
  const kerf::Enrichment e = kerf::make_enrichment(mesh, plane_cut({0.015, 0.03, 0.1003}, {0.2, 0.1, 1.0}));
  std::string message;
  try {
    const kerf::XfemModel model(mesh, material, e);
  } catch (const std::invalid_argument& error) {
    message = error.what();
  }
  CHECK(message.find("XfemModel") != std::string::npos);
  CHECK(message.find("1") != std::string::npos);
}
