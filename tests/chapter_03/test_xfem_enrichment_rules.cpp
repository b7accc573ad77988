// Which nodes get enriched, under Kerf's rule and under the two papers': the three
// sets differ at the cut's front, and the enrichment header says how. Here they are listed on
// the demo beam with a front that really runs through tets (x1 = 15.3 mm, plane z = 0.1003),
// each paper's set computed from its own definition in the test.
#include "xfem_test_support.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <iterator>
#include <set>

namespace {

using NodeSet = std::set<int>;

NodeSet nodes_of_tets_in_state(const kerf::TetMesh& mesh, const kerf::Enrichment& e, std::initializer_list<kerf::ElementCutState> states) {
  NodeSet nodes;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const kerf::ElementCutState state = e.classification.state[static_cast<std::size_t>(t)];
    if (std::find(states.begin(), states.end(), state) != states.end())
      for (int a = 0; a < 4; ++a) nodes.insert(mesh.tets(t, a));
  }
  return nodes;
}

NodeSet minus(const NodeSet& a, const NodeSet& b) {
  NodeSet d;
  std::set_difference(a.begin(), a.end(), b.begin(), b.end(), std::inserter(d, d.end()));
  return d;
}

bool includes(const NodeSet& a, const NodeSet& b) { return std::includes(a.begin(), a.end(), b.begin(), b.end()); }

} // namespace

TEST_CASE("enrichment rules: Kerf's sign-enriched nodes beside Schoch et al.'s and Paulus et al.'s sets") {
  const kerf::TetMesh mesh = xfem_test::beam({3, 6, 19});
  const kerf::Enrichment e = kerf::make_enrichment(mesh, kerf::RectangleCut({0, 0, 0.1003}, {0.0153, 0, 0}, {0, 0.06, 0}));
  using State = kerf::ElementCutState;
  // Schoch et al. (eq. 73, section 4.3): every node of every element the cut reaches.
  const NodeSet schoch_nodes = nodes_of_tets_in_state(mesh, e, {State::partially_cut, State::completely_cut});
  // Paulus et al. (section 3.3): branch functions on the nodes of partially cut elements, signs on
  // the other nodes of completely cut ones.
  const NodeSet paulus_branch = nodes_of_tets_in_state(mesh, e, {State::partially_cut});
  const NodeSet paulus_sign = minus(nodes_of_tets_in_state(mesh, e, {State::completely_cut}), paulus_branch);
  const NodeSet kerf(e.enriched_nodes.begin(), e.enriched_nodes.end());
  NodeSet touching_beyond;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    if (e.tet_side[static_cast<std::size_t>(t)] == kerf::TetSide::beyond)
      for (int a = 0; a < 4; ++a) touching_beyond.insert(mesh.tets(t, a));

  MESSAGE("Schoch et al.: " << schoch_nodes.size() << " nodes; Paulus et al.: " << paulus_sign.size() << " sign + "
                            << paulus_branch.size() << " branch; Kerf: " << kerf.size() << " sign, " << e.front_nodes
                            << " front nodes left for chapter 5");
  REQUIRE(e.classification.count(State::partially_cut) > 0); // the front does run through tets
  // Kerf enriches a subset of Schoch et al.'s nodes: those with no tet beyond the front.
  CHECK(includes(schoch_nodes, kerf));
  CHECK(kerf == minus(schoch_nodes, touching_beyond));
  // Every node Paulus et al. sign-enrich, Kerf does too ...
  CHECK(includes(kerf, paulus_sign));
  // ... and Kerf also sign-enriches some nodes Paulus et al. give branch functions: the nodes of
  // partially cut tets on the cut's side of the front.
  const NodeSet branch_but_kerf_sign = minus(paulus_branch, minus(paulus_branch, kerf));
  CHECK_FALSE(branch_but_kerf_sign.empty());
  // ... and leaves the others unenriched, for chapter 5: the nodes of partially cut tets that
  // also touch a tet beyond the front.
  CHECK_FALSE(minus(paulus_branch, kerf).empty());
  CHECK(includes(touching_beyond, minus(paulus_branch, kerf)));
}
