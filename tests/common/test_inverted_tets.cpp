// An inverted tet built in code never passes through check_tet_mesh(), so every integral that
// weights with det J refuses it itself (positive_jacobian.hpp): the element functions, the
// gravity load, the stiffness assembly and the corotational model, each with a message that
// names the function and, where the mesh is known, the element.
#include "kerf/corotation/corotational_model.hpp"
#include "kerf/fem/assemble_loads.hpp"
#include "kerf/fem/assemble_stiffness.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/linear_material.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/fem/tet_mass.hpp"
#include "kerf/fem/tet_stiffness.hpp"
#include "kerf/mesh/check_tet_mesh.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"
#include "kerf/mesh/tet_mesh.hpp"

#include <doctest/doctest.h>

#include <functional>
#include <stdexcept>
#include <string>
#include <utility>

namespace {

/// Two tets sharing the face 1-2-3; the second is listed in the negative orientation.
kerf::TetMesh two_tets_second_inverted() {
  kerf::TetMesh mesh;
  mesh.nodes.resize(5, 3);
  mesh.nodes << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1;
  mesh.tets.resize(2, 4);
  mesh.tets << 0, 1, 2, 3, //
      2, 1, 3, 4;
  return mesh;
}

/// The std::invalid_argument message of `integrate`, or "" if it throws none.
std::string invalid_argument_of(const std::function<void()>& integrate) {
  try {
    integrate();
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

/// `integrate` is refused with a message that contains every one of `expected`.
void check_refused(const std::function<void()>& integrate, std::initializer_list<std::string> expected) {
  const std::string message = invalid_argument_of(integrate);
  CAPTURE(message);
  CHECK(!message.empty());
  for (const std::string& part : expected) CHECK(message.find(part) != std::string::npos);
}

/// The node positions of tet t, n rows.
template <int n>
Eigen::Matrix<double, n, 3> element_nodes(const kerf::TetMesh& mesh, Eigen::Index t) {
  Eigen::Matrix<double, n, 3> X;
  for (int a = 0; a < n; ++a) X.row(a) = mesh.nodes.row(mesh.tets(t, a));
  return X;
}

} // namespace

TEST_CASE("the test mesh has one good and one inverted tet") {
  const kerf::TetMesh mesh = two_tets_second_inverted();
  REQUIRE(kerf::signed_tet_volume(mesh, 0) > 0.0);
  REQUIRE(kerf::signed_tet_volume(mesh, 1) < 0.0);
}

TEST_CASE("the element functions refuse an inverted tet and still take a good one") {
  const kerf::LinearMaterial material;
  const kerf::TetMesh tet4 = two_tets_second_inverted();
  const kerf::TetMesh tet10 = kerf::tet10_from_tet4(tet4);
  CHECK_NOTHROW(kerf::tet4_stiffness(element_nodes<4>(tet4, 0), material));
  CHECK_NOTHROW(kerf::tet10_stiffness(element_nodes<10>(tet10, 0), material));
  check_refused([&] { kerf::tet4_stiffness(element_nodes<4>(tet4, 1), material); }, {"tet4_stiffness: ", "det J = -", "<= 0"});
  check_refused([&] { kerf::tet10_stiffness(element_nodes<10>(tet10, 1), material); }, {"tet10_stiffness: ", "det J = -"});
  check_refused([&] { kerf::tet4_mass(element_nodes<4>(tet4, 1), material.density); }, {"tet4_mass: ", "det J = -"});
  check_refused([&] { kerf::tet10_mass(element_nodes<10>(tet10, 1), material.density); }, {"tet10_mass: ", "det J = -"});

  // A flat tet (all corners in a plane) has det J = 0 and is refused too.
  Eigen::Matrix<double, 4, 3> flat = element_nodes<4>(tet4, 0);
  flat(3, 2) = 0.0;
  check_refused([&] { kerf::tet4_stiffness(flat, material); }, {"tet4_stiffness: ", "det J = 0"});
}

TEST_CASE("the mesh-wide integrals refuse an inverted tet and name it") {
  const kerf::LinearMaterial material;
  for (const kerf::TetMesh& mesh : {two_tets_second_inverted(), kerf::tet10_from_tet4(two_tets_second_inverted())}) {
    CAPTURE(mesh.nodes_per_tet());
    check_refused([&] { kerf::assemble_gravity(mesh, material.density, {0, 0, -9.81}); },
                  {"assemble_gravity: element 1: ", "det J = -"});
    check_refused([&] { kerf::CorotationalModel model(mesh, material); }, {"CorotationalModel: element 1: ", "det J = -"});
    const kerf::DofMap dofs = kerf::make_dof_map(mesh.num_nodes(), {{{0, 1, 2}, {0, 0, 0}}});
    kerf::SparseAssembler assembler(mesh.tets, dofs);
    Eigen::VectorXd rhs_free = Eigen::VectorXd::Zero(dofs.num_free);
    check_refused([&] { kerf::assemble_linear_stiffness(mesh, material, assembler, rhs_free); },
                  {"assemble_linear_stiffness: element 1: ", "det J = -"});
  }
}

TEST_CASE("a Tet10 built in code whose mid-edge node folds it is refused at the quadrature point") {
  // Corners positively oriented, but the node on edge (0, 1) pulled far across the thin tet:
  // det J changes sign inside, which the corner volume cannot see.
  kerf::TetMesh tet4;
  tet4.nodes.resize(4, 3);
  tet4.nodes << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0.1;
  tet4.tets.resize(1, 4);
  tet4.tets << 0, 1, 2, 3;
  kerf::TetMesh folded = kerf::tet10_from_tet4(tet4);
  folded.nodes.row(folded.tets(0, 4)) += Eigen::RowVector3d(0, 0, 0.2);
  const kerf::LinearMaterial material;
  check_refused([&] { kerf::tet10_stiffness(element_nodes<10>(folded, 0), material); }, {"tet10_stiffness: ", "det J = -"});
  check_refused([&] { kerf::CorotationalModel model(folded, material); }, {"CorotationalModel: element 0: ", "det J = -"});
}
