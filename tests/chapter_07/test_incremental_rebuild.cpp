// Chapter 7 rebuilds its model whenever the blade crosses a tet, and pays only where the cut
// changed: CutXfemModel's constructor from the model before (the recut tets integrated anew,
// every other tet's points kept) and SparseAssembler's from the assembler before (the mesh's
// part of the pattern copied, the enriched rows walked). The claim is that both give what
// building from scratch gives. We grow a blade's sheet quad by quad through a box, Tet4 and
// Tet10, with sign enrichments only and with chapter 5's branch functions, and compare after
// every quad: the slots, the assembled stiffness, the corotated energy and forces of a random
// state, and the pattern and the scatter map (the same matrix assembled both ways, with
// clamped nodes and gripped enrichments in the DofMap). The split tets' piece masses
// (SplitTetMasses) are kept the same way and compared the same way, with the masses made from
// them; and the energy that comes with the forces (assemble_with_energy) against energy() and,
// as the forces' potential, against a central difference.
#include "kerf/cut/crack_front.hpp"
#include "kerf/cut/cut_sheet.hpp"
#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/node_region.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"
#include "kerf/mesh/tet_neighbours.hpp"
#include "kerf/xfem/branch_enrichment.hpp"
#include "kerf/dynamics/lumped_mass.hpp"
#include "kerf/xfem/cut_xfem_mass.hpp"
#include "kerf/xfem/split_tet_masses.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"
#include "kerf/xfem/surface_enrichment.hpp"

#include "support/cut_body.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <memory>
#include <random>
#include <stdexcept>
#include <vector>

namespace {

const kerf::LinearMaterial tissue{3000.0, 0.45, 1000.0};

// The stiffness (linear or the corotated tangent at u) of `model` on `dofs`, with the forces.
struct Assembled {
  Eigen::SparseMatrix<double> K;
  Eigen::VectorXd f_int;
};

Assembled assemble(const kerf::CutXfemModel& model, kerf::SparseAssembler& assembler, const kerf::DofMap& dofs, const Eigen::VectorXd& u) {
  Assembled result;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(dofs.num_free);
  assembler.set_zero();
  model.assemble(u, kerf::RotationMethod::automatic, kerf::CorotationalTangent::consistent, result.f_int, &assembler, &rhs);
  result.K = assembler.matrix();
  return result;
}

double max_abs(const Eigen::SparseMatrix<double>& A) {
  double m = 0.0;
  for (Eigen::Index k = 0; k < A.nonZeros(); ++k) m = std::max(m, std::abs(A.valuePtr()[k]));
  return m;
}

// One state of the growing cut: its pieces, enrichments (and branch functions), and two models
// of it, one built from scratch and one from the model of the state before.
struct Stage {
  kerf::CutSurfaces cuts;
  kerf::MeshPieces pieces;
  kerf::CrackFronts fronts;
  std::unique_ptr<kerf::BranchEnrichment> branch;
  std::unique_ptr<kerf::SurfaceEnrichment> sign;
  std::unique_ptr<kerf::CrackTipFunctions> functions;
  std::unique_ptr<kerf::CutXfemModel> scratch, grown;
  std::unique_ptr<kerf::SplitTetMasses> grown_masses;
};

// The piece masses of every tet, kept from `before` (`grown`, made for the model `model`) and
// integrated from scratch: equal to the bit (the same rule on the same pieces); and the lumped
// and consistent masses built from them equal the ones the rule gives directly. Returns how many
// split tets the kept masses integrated.
Eigen::Index check_same_masses(const kerf::CutXfemModel& scratch, const kerf::CutXfemModel& model, const kerf::SplitTetMasses& grown) {
  const kerf::SplitTetMasses from_scratch(scratch, support::subtets);
  for (Eigen::Index t = 0; t < scratch.mesh().num_tets(); ++t) {
    CAPTURE(t);
    const std::vector<Eigen::MatrixXd> expected = from_scratch(scratch, t), actual = grown(model, t);
    REQUIRE(actual.size() == expected.size());
    for (std::size_t p = 0; p < expected.size(); ++p) CHECK((actual[p] - expected[p]).cwiseAbs().maxCoeff() == 0.0);
  }
  const double density = 1060.0;
  for (const kerf::LumpingScheme scheme : {kerf::LumpingScheme::virtual_tet, kerf::LumpingScheme::row_sum}) {
    const Eigen::SparseMatrix<double> expected = kerf::lump_cut_xfem_mass(scratch, density, scheme, support::subtets);
    CHECK(max_abs(kerf::lump_cut_xfem_mass(model, density, scheme, grown) - expected) <= 1e-15 * max_abs(expected));
  }
  // Consistent: density times the unit masses instead of density inside the sum, round-off apart.
  const Eigen::SparseMatrix<double> expected = kerf::assemble_cut_xfem_mass(scratch, density, support::subtets);
  CHECK(max_abs(kerf::assemble_cut_xfem_mass(model, density, grown) - expected) <= 1e-14 * max_abs(expected));
  return grown.num_integrated();
}

// The shared comparison: slots, stiffness and forces, energy, and both assemblers. With
// `exact_gradient` (no branch functions), also that the forces are the energy's gradient.
void check_same_model(const kerf::TetMesh& mesh, const kerf::CutXfemModel& scratch, const kerf::CutXfemModel& grown,
                      const kerf::SparseAssembler* assembler_before, std::unique_ptr<kerf::SparseAssembler>& assembler, std::mt19937& rng,
                      bool exact_gradient) {
  REQUIRE(grown.num_dof_nodes() == scratch.num_dof_nodes());
  REQUIRE(grown.assembly_slots() == scratch.assembly_slots());
  CHECK(grown.position_force_norm() == kerf_test::relative(scratch.position_force_norm(), 1e-12));
  CHECK(grown.num_piece_points() == scratch.num_piece_points());

  // Clamped bottom; the enrichments of its nodes and the slivers prescribed by the cut DofMap.
  kerf::NodeRegion bottom;
  bottom.box_max = {1, 1, 0};
  const std::vector<kerf::DirichletNodes> held{{kerf::nodes_in_region(mesh, bottom), {0, 0, 0}}};
  const kerf::DofMap dofs = kerf::make_cut_xfem_dof_map(scratch, held);
  REQUIRE(dofs.num_free < 3 * scratch.num_dof_nodes());

  kerf::SparseAssembler from_scratch(scratch.assembly_slots(), dofs);
  std::unique_ptr<kerf::SparseAssembler> grown_assembler =
      assembler_before ? std::make_unique<kerf::SparseAssembler>(*assembler_before, grown.assembly_slots(), dofs, mesh.nodes_per_tet())
                       : std::make_unique<kerf::SparseAssembler>(grown.assembly_slots(), dofs);
  // The same pattern, index for index.
  REQUIRE(grown_assembler->num_stored_entries() == from_scratch.num_stored_entries());
  const Eigen::SparseMatrix<double>& a = grown_assembler->matrix();
  const Eigen::SparseMatrix<double>& b = from_scratch.matrix();
  CHECK(std::equal(a.outerIndexPtr(), a.outerIndexPtr() + a.outerSize() + 1, b.outerIndexPtr()));
  CHECK(std::equal(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros(), b.innerIndexPtr()));

  // A random state of 1 % strain: the corotated tangent and forces of each model, each assembled
  // through its own assembler, agree to round-off (the scatter maps put every block in place).
  std::uniform_real_distribution<double> value(-0.01, 0.01);
  Eigen::VectorXd u(3 * scratch.num_dof_nodes());
  for (Eigen::Index i = 0; i < u.size(); ++i) u[i] = value(rng);
  const Assembled expected = assemble(scratch, from_scratch, dofs, u);
  const Assembled actual = assemble(grown, *grown_assembler, dofs, u);
  CHECK(max_abs(actual.K - expected.K) <= 1e-13 * max_abs(expected.K));
  CHECK((actual.f_int - expected.f_int).cwiseAbs().maxCoeff() <= 1e-13 * expected.f_int.cwiseAbs().maxCoeff());
  CHECK(grown.energy(u, true) == kerf_test::relative(scratch.energy(u, true), 1e-12));
  // The energy that comes with the forces and the warped tangent (chapter 7's step): energy()'s,
  // which sums the strain density instead of 1/2 d^T K_q d, and, where every point has its own
  // polar rotation (no branch functions), the potential of the forces: a central difference of
  // W along a random direction equals f . du.
  Eigen::VectorXd f_with_energy, rhs = Eigen::VectorXd::Zero(dofs.num_free);
  grown_assembler->set_zero();
  const auto W = [&](const Eigen::VectorXd& v, Eigen::VectorXd& f) {
    return grown.assemble_with_energy(v, kerf::RotationMethod::automatic, kerf::CorotationalTangent::warped, f, grown_assembler.get(), &rhs);
  };
  const double W_u = W(u, f_with_energy);
  CHECK(W_u == kerf_test::relative(grown.energy(u, true), 1e-12));
  if (exact_gradient) {
    Eigen::VectorXd du(u.size()), unused;
    for (Eigen::Index i = 0; i < du.size(); ++i) du[i] = value(rng);
    const double h = 1e-4; // u moves by 1e-6: central difference error ~h^2, round-off ~1e-16 W / h
    const double slope = (W(u + h * du, unused) - W(u - h * du, unused)) / (2.0 * h);
    CHECK(slope == kerf_test::relative(f_with_energy.dot(du), 1e-6));
  }
  assembler = std::move(grown_assembler);
}

// Grows the sheet of an upright blade moving along -x through the unit box near the plane y =
// `y`, quad by quad, and checks every stage. The blade's edge zigzags by +-`wiggle` in y from
// one quad to the next, so that a tet that two quads cross is split anew by the second: a
// model that kept the points of its old pieces would differ there. With `tips`, chapter 5's branch functions
// (topological, no blending correction) act where the sheet ends inside the box. Returns the
// number of split tets whose points the grown model took from the model before, summed over
// the stages, and of those whose masses SplitTetMasses copied (the comparisons must have
// compared something).
struct Kept {
  int points = 0;
  Eigen::Index masses = 0;
};
Kept grow_and_compare(const kerf::TetMesh& mesh, double y, double wiggle, bool tips) {
  const auto neighbours = std::make_shared<const kerf::TetNeighbours>(kerf::tet_neighbours(mesh));
  std::mt19937 rng(7);
  kerf::CutSheet sheet(0.05);
  sheet.offer({{1.2, y, 1.2}, {1.2, y, 0.45}});
  std::unique_ptr<Stage> before;
  std::unique_ptr<kerf::SparseAssembler> assembler;
  int kept_split_tets = 0;
  Eigen::Index integrated_masses = 0, split_with_masses = 0, copyable_masses = 0;
  for (int k = 1; k <= 12; ++k) {
    CAPTURE(k);
    const double x = 1.2 - 0.07 * k;
    const double y_k = y + wiggle * (k % 2 == 0 ? 1.0 : -1.0);
    const std::vector<kerf::SweptTriangle> added = sheet.offer({{x, y_k, 1.2}, {x, y_k, 0.45}});
    Eigen::AlignedBox3d changed;
    for (const kerf::SweptTriangle& triangle : added)
      for (const Eigen::Vector3d& corner : triangle) changed.extend(corner);
    auto stage = std::make_unique<Stage>(Stage{kerf::CutSurfaces({sheet.surface()}), {}, {}, {}, {}, {}, {}, {}, {}});
    stage->pieces = before ? kerf::recut_mesh_into_pieces(mesh, stage->cuts, before->pieces, changed)
                           : kerf::cut_mesh_into_pieces(mesh, stage->cuts, neighbours);
    const kerf::SurfaceEnrichment* sign = nullptr;
    if (tips) {
      stage->fronts = kerf::find_crack_fronts(mesh, stage->cuts);
      stage->branch = std::make_unique<kerf::BranchEnrichment>(
          kerf::make_branch_enrichment(mesh, stage->pieces, stage->fronts, kerf::TipEnrichmentRule::topological, 0.0));
      stage->functions = std::make_unique<kerf::CrackTipFunctions>(kerf::CrackTipFunctions{*stage->branch, stage->fronts});
      // The cheapest rules: the claim is equality, whatever the rules (the collapsed ones cost
      // minutes here).
      stage->functions->front_rule = kerf::FrontRule::refined_subtets;
      stage->functions->front_points = 1;
      stage->functions->blending_degree = 2;
      stage->functions->blending_depth = 0;
      sign = &stage->branch->sign;
    } else {
      stage->sign = std::make_unique<kerf::SurfaceEnrichment>(kerf::make_surface_enrichment(mesh, stage->pieces));
      sign = stage->sign.get();
    }
    stage->scratch = std::make_unique<kerf::CutXfemModel>(mesh, tissue, stage->pieces, *sign, support::subtets, stage->functions.get());
    stage->grown = before ? std::make_unique<kerf::CutXfemModel>(*before->grown, stage->pieces, *sign, stage->functions.get())
                          : std::make_unique<kerf::CutXfemModel>(mesh, tissue, stage->pieces, *sign, support::subtets, stage->functions.get());
    for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
      if (before && stage->pieces.kept_from_previous[static_cast<std::size_t>(t)] && stage->grown->integrated_by_pieces(t) &&
          before->grown->integrated_by_pieces(t) && !stage->grown->has_branch_functions(t) && !before->grown->has_branch_functions(t))
        ++kept_split_tets;
    check_same_model(mesh, *stage->scratch, *stage->grown, assembler.get(), assembler, rng, !tips);
    // The tets whose pieces SplitTetMasses integrates by the rule, and those of them it can copy.
    const auto has_rule_masses = [&](const Stage& s, Eigen::Index t) {
      return s.grown->integrated_by_pieces(t) && s.pieces.num_pieces(t) > 1 && !s.grown->has_branch_functions(t);
    };
    for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
      if (!has_rule_masses(*stage, t)) continue;
      ++split_with_masses;
      if (before && stage->pieces.kept_from_previous[static_cast<std::size_t>(t)] && has_rule_masses(*before, t)) ++copyable_masses;
    }
    stage->grown_masses = std::make_unique<kerf::SplitTetMasses>(*stage->grown, support::subtets, before ? before->grown_masses.get() : nullptr);
    integrated_masses += check_same_masses(*stage->scratch, *stage->grown, *stage->grown_masses);
    before = std::move(stage);
  }
  // The masses were integrated for the split tets that did not keep their pieces, and copied
  // for the others (how many were kept, the callers assert).
  CHECK(integrated_masses == split_with_masses - copyable_masses);
  return {kept_split_tets, copyable_masses};
}

} // namespace

TEST_CASE("a model and a pattern grown from the ones before equal those built from scratch, quad after quad") {
  const kerf::TetMesh tet4 = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {4, 4, 4});
  // The counts of split tets whose points were kept, summed over the 12 stages, are measured
  // (72, 72, 72 and 15; the masses copied: 72, 72 and 15): the bounds only say that the reuse
  // happened.
  SUBCASE("Tet4, sign enrichments, the sheet through the tets") {
    const Kept kept = grow_and_compare(tet4, 0.37, 0.03, false);
    CHECK(kept.points > 20);
    CHECK(kept.masses > 20);
  }
  // On the plane the tets split into one piece each: nothing to integrate by the rule.
  SUBCASE("Tet4, sign enrichments, the sheet in a plane of nodes and faces") { CHECK(grow_and_compare(tet4, 0.5, 0.0, false).points > 20); }
  SUBCASE("Tet10, sign enrichments") {
    const Kept kept = grow_and_compare(kerf::tet10_from_tet4(tet4), 0.37, 0.03, false);
    CHECK(kept.points > 20);
    CHECK(kept.masses > 20);
  }
  SUBCASE("Tet4, with chapter 5's branch functions at the front") {
    const Kept kept = grow_and_compare(tet4, 0.37, 0.03, true);
    CHECK(kept.points > 4);
    CHECK(kept.masses > 4);
  }
}

TEST_CASE("a tet cut anew into as many pieces as before gets new points") {
  // A blade moving forward never changes the pieces of a tet it has split (it has passed it),
  // so the growing sheets above cannot tell whether the model honours
  // MeshPieces::kept_from_previous. Here the second cut is another plane through the same
  // tets, tilted, and every tet is cut again (the changed box holds the mesh): each split tet
  // keeps its two pieces, of other shapes, and must be integrated anew.
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {4, 4, 4});
  const auto neighbours = std::make_shared<const kerf::TetNeighbours>(kerf::tet_neighbours(mesh));
  const auto plane = [](double y_start, double y_end) {
    kerf::CutSheet sheet(0.5);
    sheet.offer({{1.2, y_start, 1.2}, {1.2, y_start, -0.2}});
    sheet.offer({{-0.2, y_end, 1.2}, {-0.2, y_end, -0.2}}, true);
    return kerf::CutSurfaces({sheet.surface()});
  };
  const kerf::CutSurfaces first = plane(0.37, 0.37), second = plane(0.33, 0.41);
  const kerf::MeshPieces pieces_first = kerf::cut_mesh_into_pieces(mesh, first, neighbours);
  const kerf::SurfaceEnrichment enrichment_first = kerf::make_surface_enrichment(mesh, pieces_first);
  const kerf::CutXfemModel model_first(mesh, tissue, pieces_first, enrichment_first, support::subtets);
  const Eigen::AlignedBox3d everything(Eigen::Vector3d::Constant(-1.0), Eigen::Vector3d::Constant(2.0));
  const kerf::MeshPieces pieces_second = kerf::recut_mesh_into_pieces(mesh, second, pieces_first, everything);
  const kerf::SurfaceEnrichment enrichment_second = kerf::make_surface_enrichment(mesh, pieces_second);
  int same_count = 0;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    if (pieces_first.num_pieces(t) == 2 && pieces_second.num_pieces(t) == 2) ++same_count;
  REQUIRE(same_count > 20); // measured 32: the case to test is there
  const kerf::CutXfemModel scratch(mesh, tissue, pieces_second, enrichment_second, support::subtets);
  const kerf::CutXfemModel grown(model_first, pieces_second, enrichment_second);
  std::mt19937 rng(11);
  std::unique_ptr<kerf::SparseAssembler> assembler;
  check_same_model(mesh, scratch, grown, nullptr, assembler, rng, true);
  // The masses too: every split tet integrated again, none copied by its piece count alone.
  const kerf::SplitTetMasses masses_first(model_first, support::subtets);
  const kerf::SplitTetMasses masses_second(grown, support::subtets, &masses_first);
  CHECK(check_same_masses(scratch, grown, masses_second) == kerf::SplitTetMasses(scratch, support::subtets).num_integrated());
}

TEST_CASE("a model or masses grown from pieces that do not say which tets they kept are refused") {
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {2, 2, 2});
  kerf::CutSheet sheet(0.5);
  sheet.offer({{1.2, 0.37, 1.2}, {1.2, 0.37, -0.2}});
  sheet.offer({{-0.2, 0.37, 1.2}, {-0.2, 0.37, -0.2}}, true);
  const kerf::CutSurfaces cuts({sheet.surface()});
  const kerf::MeshPieces pieces = kerf::cut_mesh_into_pieces(mesh, cuts, std::make_shared<const kerf::TetNeighbours>(kerf::tet_neighbours(mesh)));
  const kerf::SurfaceEnrichment enrichment = kerf::make_surface_enrichment(mesh, pieces);
  const kerf::CutXfemModel model(mesh, tissue, pieces, enrichment, support::subtets);
  const kerf::SplitTetMasses masses(model, support::subtets);
  kerf::MeshPieces unsaid = pieces;
  unsaid.kept_from_previous.clear();
  CHECK_THROWS_AS(kerf::CutXfemModel(model, unsaid, enrichment), std::invalid_argument);
  const kerf::CutXfemModel from_scratch(mesh, tissue, unsaid, enrichment, support::subtets);
  CHECK_THROWS_AS(kerf::SplitTetMasses(from_scratch, support::subtets, &masses), std::invalid_argument);
  // cut_mesh_into_pieces says "none kept": every split tet is integrated again.
  const kerf::CutXfemModel again(model, pieces, enrichment);
  CHECK(kerf::SplitTetMasses(again, support::subtets, &masses).num_integrated() == masses.num_integrated());
  CHECK(masses.num_integrated() > 0);
}

TEST_CASE("an assembler grown from another refuses elements whose mesh nodes or numbering changed") {
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {2, 2, 2});
  const kerf::DofMap dofs = kerf::make_dof_map(mesh.num_nodes(), {});
  const kerf::SparseAssembler before(mesh.tets, dofs);
  // Another tet's nodes in row 0.
  kerf::TetMatrix swapped = mesh.tets;
  swapped.row(0) = mesh.tets.row(1);
  CHECK_THROWS_AS(kerf::SparseAssembler(before, swapped, dofs, 4), std::invalid_argument);
  // A node clamped now that was free before: its DOFs are numbered otherwise.
  kerf::DirichletNodes clamp{{0}, {0, 0, 0}};
  const kerf::DofMap clamped = kerf::make_dof_map(mesh.num_nodes(), {clamp});
  CHECK_THROWS_AS(kerf::SparseAssembler(before, mesh.tets, clamped, 4), std::invalid_argument);
  // The same elements and numbering: the same pattern.
  const kerf::SparseAssembler again(before, mesh.tets, dofs, 4);
  CHECK(again.num_stored_entries() == before.num_stored_entries());
}
