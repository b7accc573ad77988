// Where a cut meets the boundary conditions: a cut running into the clamped face (the clamp
// must hold both flaps, on the whole face, not only at the nodes), a cut that frees a piece (it
// must be refused, by name, before any solver sees the singular matrix, whichever solver the
// scene asks for), and a node that belongs to no tet (held, as chapters 1 and 2 do).
#include "xfem_test_support.hpp"

#include "kerf/app/input_error.hpp"
#include "kerf/corotation/quasi_static_solver.hpp"
#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/scene/scene.hpp"
#include "kerf/scene/scene_mesh.hpp"
#include "kerf/scene/scene_xfem_dofs.hpp"
#include "kerf/scene/xfem_loads.hpp"
#include "kerf/xfem/xfem_field.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

// The demo beam (3 x 6 x 19 cells, gravity along +x, clamped at z = 0) with one rectangle
// cut and a solver; `mesh` replaces the box when given.
std::string beam_scene(const std::string& rectangle, const std::string& solver, const std::string& mesh = "") {
  return R"({"mesh": )" + (mesh.empty() ? R"({"box": {"min": [0,0,0], "max": [0.03,0.06,0.2], "cells": [3,6,19]}, "order": 1})" : mesh) +
         R"(, "material": {"young": 300e3, "poisson": 0.35, "density": 1070}, "gravity": [9.81, 0, 0],
             "dirichlet": [{"region": {"box": {"min": [0,0,0], "max": [0.03,0.06,0]}}}],
             "cuts": [{"rectangle": )" + rectangle + R"(}], "solver": {"type": ")" + solver + R"("}})";
}

// Everything chapter 3's program builds from a scene, kept alive together.
struct CutBody {
  kerf::Scene scene;
  kerf::TetMesh mesh;
  kerf::Enrichment enrichment;
  std::unique_ptr<kerf::XfemModel> model;

  explicit CutBody(const std::string& json) : scene(kerf::parse_scene(json, "test.json", ".")) {
    mesh = kerf::make_scene_mesh(scene, nullptr);
    const kerf::CutSpec& cut = scene.cuts.at(0);
    enrichment = kerf::make_enrichment(mesh, kerf::RectangleCut(cut.origin, cut.edge1, cut.edge2));
    model = std::make_unique<kerf::XfemModel>(mesh, scene.material, enrichment);
  }
  Eigen::VectorXd loads() const { return kerf::xfem_scene_loads(scene, *model, kerf::boundary_faces(mesh)); }
};

// The vertical cut x = 0.015 over the whole width, from below the clamped face z = 0 up to
// z = 0.11: it runs into the clamp.
const std::string cut_into_clamp = R"({"origin": [0.015,-0.01,-0.01], "edge1": [0,0.08,0], "edge2": [0,0,0.11]})";

} // namespace

TEST_CASE("xfem boundary conditions: a clamp the cut runs into holds both flaps on the whole face, linear and corotational") {
  const CutBody body(beam_scene(cut_into_clamp, "cholmod"));
  std::ostringstream warnings;
  const kerf::DofMap dofs = kerf::scene_xfem_dof_map(body.scene, *body.model, &warnings);
  CHECK(warnings.str().empty());
  // Points of the clamped face inside the tets the cut crosses (x = 0.015 +- 0.0005) and away
  // from it; before the clamp held a_i too, the two flaps slid by +-0.62 mm here (linear) and
  // 0.48 mm (corotational) under a tip deflection of 69 mm.
  Eigen::MatrixXd face_points(6, 3);
  face_points << 0.0145, 0.035, 0, 0.0155, 0.035, 0, 0.0149, 0.012, 0, 0.0151, 0.052, 0, 0.005, 0.035, 0, 0.025, 0.035, 0;
  const Eigen::VectorXd f = body.loads();

  const auto check_clamp = [&](const Eigen::VectorXd& u, const std::string& model) {
    CAPTURE(model);
    REQUIRE(u.allFinite());
    Eigen::Index outside = 0;
    const Eigen::MatrixXd values = kerf::xfem_displacement_at(*body.model, u, face_points, outside);
    REQUIRE(outside == 0);
    const double tip = u.head(3 * body.mesh.num_nodes()).cwiseAbs().maxCoeff();
    MESSAGE(model << ": tip " << tip << " m, largest |u| on the clamped face " << values.cwiseAbs().maxCoeff() << " m");
    CHECK(tip > 0.05); // the beam does bend: the check below is not about a beam at rest
    // The prescribed value is exactly 0 at every node of the face, so u there is a sum of zeros:
    // round-off alone, far below 1e-12 of the tip deflection.
    CHECK(values.cwiseAbs().maxCoeff() <= 1e-12 * tip);
  };
  check_clamp(kerf::solve_linear_xfem(*body.model, dofs, f, body.scene.solver), "linear");

  kerf::QuasiStaticSettings settings;
  settings.load_steps = 4;
  const kerf::QuasiStaticResult result = kerf::solve_quasi_static(*body.model, dofs, f, settings);
  CHECK(result.converged);
  check_clamp(result.u, "corotational");
}

TEST_CASE("xfem boundary conditions: a piece the cut frees is refused by name before any solver, with every solver") {
  // A rectangle over the whole section at z = 0.1: the upper half floats.
  const std::string through = R"({"origin": [-1,-1,0.1], "edge1": [3,0,0], "edge2": [0,3,0]})";
  for (const std::string solver : {"cholmod", "ldlt", "cg-jacobi", "cg-ichol"}) {
    CAPTURE(solver);
    const CutBody body(beam_scene(through, solver));
    std::string message;
    try {
      kerf::scene_xfem_dof_map(body.scene, *body.model, nullptr);
    } catch (const kerf::InputError& error) {
      message = error.what();
    }
    MESSAGE(message);
    // The message names the file, the field and the piece: its volume (the upper half is
    // 0.03 x 0.06 x 0.1 = 1.8e-4 m^3) and a point in it (z > 0.1).
    CHECK(message.find("test.json") != std::string::npos);
    CHECK(message.find("dirichlet") != std::string::npos);
    CHECK(message.find("0.00018 m^3") != std::string::npos);
    CHECK(message.find("6 rigid motions free") != std::string::npos);
    // The library call refuses it too, whichever solver: LDLT used to return max |u| = 3e10 m.
    const kerf::DofMap dofs = kerf::make_xfem_dof_map(*body.model, kerf::scene_dirichlet_nodes(body.scene, body.mesh));
    const std::vector<kerf::UnheldPiece> unheld = kerf::xfem_unheld_pieces(*body.model, dofs);
    REQUIRE(unheld.size() == 1);
    CHECK(unheld[0].volume == kerf_test::relative(0.03 * 0.06 * 0.1, 1e-12));
    CHECK(unheld[0].point.z() > 0.1);
    CHECK_THROWS_AS(kerf::solve_linear_xfem(*body.model, dofs, body.loads(), body.scene.solver), std::runtime_error);
  }

  // A rectangle that stops 4.9 mm short of the far face x = 0.03: with the front resolved to
  // whole elements (see the enrichment's header), the body is already cut in two.
  const CutBody nearly(beam_scene(R"({"origin": [0,0,0.1], "edge1": [0.0251,0,0], "edge2": [0,0.06,0]})", "ldlt"));
  CHECK_THROWS_AS(kerf::scene_xfem_dof_map(nearly.scene, *nearly.model, nullptr), kerf::InputError);
  // ... while one that stops 10 mm short leaves it whole.
  const CutBody two_thirds(beam_scene(R"({"origin": [0,0,0.1], "edge1": [0.02,0,0], "edge2": [0,0.06,0]})", "ldlt"));
  CHECK_NOTHROW(kerf::scene_xfem_dof_map(two_thirds.scene, *two_thirds.model, nullptr));
}

TEST_CASE("xfem boundary conditions: a node that belongs to no tet is held with a warning, as in chapter 1") {
  // The demo beam written as a Medit file with one extra vertex that no tet uses.
  const kerf::TetMesh box = xfem_test::beam({3, 6, 19});
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "kerf_xfem_stray_node";
  std::filesystem::create_directories(dir);
  const std::filesystem::path file = dir / "beam_with_stray_node.mesh";
  {
    std::ofstream out(file);
    out.precision(17);
    out << "MeshVersionFormatted 2\nDimension 3\nVertices\n" << box.num_nodes() + 1 << '\n';
    for (Eigen::Index v = 0; v < box.num_nodes(); ++v) out << box.nodes(v, 0) << ' ' << box.nodes(v, 1) << ' ' << box.nodes(v, 2) << " 0\n";
    out << "0.5 0.5 0.5 0\nTetrahedra\n" << box.num_tets() << '\n';
    for (Eigen::Index t = 0; t < box.num_tets(); ++t)
      out << box.tets(t, 0) + 1 << ' ' << box.tets(t, 1) + 1 << ' ' << box.tets(t, 2) + 1 << ' ' << box.tets(t, 3) + 1 << " 0\n";
    out << "End\n";
  }
  const std::string half_depth = R"({"origin": [0,0,0.1], "edge1": [0.015,0,0], "edge2": [0,0.06,0]})";
  const CutBody body(beam_scene(half_depth, "ldlt", R"({"file": ")" + file.string() + R"(", "order": 1})"));
  std::ostringstream warnings;
  const kerf::DofMap dofs = kerf::scene_xfem_dof_map(body.scene, *body.model, &warnings);
  CHECK(warnings.str().find("1 nodes belong to no tetrahedron and are held fixed") != std::string::npos);
  const Eigen::VectorXd u = kerf::solve_linear_xfem(*body.model, dofs, body.loads(), body.scene.solver);
  REQUIRE(u.allFinite());
  CHECK(u.segment<3>(3 * box.num_nodes()).norm() == 0.0); // the stray node stays put
  // The same beam from the box mesher, which has no stray node, gives the same answer.
  const CutBody plain(beam_scene(half_depth, "cholmod"));
  const Eigen::VectorXd u_plain =
      kerf::solve_linear_xfem(*plain.model, kerf::scene_xfem_dof_map(plain.scene, *plain.model, nullptr), plain.loads(), {});
  const double tip = u_plain.head(3 * box.num_nodes()).cwiseAbs().maxCoeff();
  // Two direct solvers on the same matrix up to one extra prescribed node: 1e-10 of the tip
  // leaves room for their different orderings (condition number about 1e6).
  CHECK((u.head(3 * box.num_nodes()) - u_plain.head(3 * box.num_nodes())).cwiseAbs().maxCoeff() <= 1e-10 * tip);
  std::filesystem::remove_all(dir);
}
