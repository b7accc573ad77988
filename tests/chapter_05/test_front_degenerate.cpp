// Degenerate crack fronts: a front exactly through a node, along mesh edges,
// lying in mesh faces, a cut in a plane of nodes (the front in its faces), a cut whose boundary
// leaves the mesh, and two fronts in one tet (a narrow slit whose two ends share tets; two cuts
// whose fronts pass the same tets). Each must give a solvable system with finite answers that
// are right: the front's length and the tets it passes through, against counts made from the
// mesh alone; a linear field whose stress leaves the cut traction-free (the patch test: the
// space holds it with every enrichment coefficient zero, so the solve must return it); and, for
// a single straight front, Williams's field with every node branch enriched (the space holds it
// exactly).
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/point_locator.hpp"

#include "support/tip_body.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>
#include <string>
#include <tuple>
#include <vector>

namespace {

const kerf::LinearMaterial material{1.0e6, 0.3, 1000.0};

// The slab [-0.3, 0.3]^2 x [0, 0.2] in 3 x 3 x 2 cells: nodes at x, y in {-0.3, -0.1, 0.1, 0.3},
// z in {0, 0.1, 0.2}.
const Eigen::Vector3d slab_min(-0.3, -0.3, 0.0), slab_max(0.3, 0.3, 0.2);
kerf::TetMesh slab() { return kerf::make_box_mesh(slab_min, slab_max, {3, 3, 2}); }

bool on_slab_boundary(const Eigen::Vector3d& x) {
  for (int p = 0; p < 3; ++p)
    if (std::abs(x[p] - slab_min[p]) < 1e-12 || std::abs(x[p] - slab_max[p]) < 1e-12) return true;
  return false;
}

// Cheaper rules than the model's defaults (4 points per direction, degree 6, depth 3), which
// cost 2 s per body here: 3 points, degree 4, graded once, 17 times fewer points. On the regular
// slab (the front x = y = 0 through the middle of elements) they leave 3.5e-5 of the Williams
// field at the nodes against 1.3e-6 with the defaults: the bounds below are set from that.
constexpr int front_points = 3, blending_degree = 4, blending_depth = 1;

// A field at x; `cut_side` is +1 (or -1) at a node the model puts on the cut
// (BranchEnrichment::cut_side), where a field discontinuous across the cut takes that face's
// value (support::williams says why), and 0 elsewhere.
using Field = std::function<Eigen::Vector3d(const Eigen::Vector3d& x, int cut_side)>;

// The side of the cut the model gives node v (0 if it is not on a cut or not a branch node).
int node_cut_side(const support::TipBody& body, Eigen::Index v) { return body.branch.cut_side[static_cast<std::size_t>(v)]; }

// Every boundary node takes u = exact; its branch DOFs (if any) the constant coefficients c_l
// when given, else 0 (make_cut_xfem_dof_map fixes the enrichments of gripped nodes at 0).
Eigen::VectorXd solve_with_boundary(const support::TipBody& body, const Field& exact, const std::array<Eigen::Vector3d, 4>* branch) {
  std::vector<kerf::DirichletNodes> conditions;
  for (Eigen::Index v = 0; v < body.mesh.num_nodes(); ++v) {
    const Eigen::Vector3d x = body.mesh.nodes.row(v).transpose();
    if (!on_slab_boundary(x)) continue;
    conditions.push_back({{static_cast<int>(v)}, exact(x, node_cut_side(body, v))});
    if (const int k = body.branch.branch_slot[static_cast<std::size_t>(v)]; k >= 0 && branch)
      for (int l = 0; l < 4; ++l) conditions.push_back({{static_cast<int>(body.model.branch_dof_node(k)) + l}, (*branch)[static_cast<std::size_t>(l)]});
  }
  const kerf::DofMap dofs = kerf::make_cut_xfem_dof_map(body.model, conditions);
  return kerf::solve_linear_cut_xfem(body.model, dofs, Eigen::VectorXd::Zero(3 * body.model.num_dof_nodes()), kerf::SolverSettings{});
}

// The largest |u_h - exact| at the nodes and at 5 x 5 x 3 points strewn through the slab (off
// the nodes' planes), over the largest |exact| there.
double largest_relative_error(const support::TipBody& body, const Eigen::VectorXd& u, const Field& exact) {
  double error = 0.0, size = 0.0;
  for (Eigen::Index v = 0; v < body.mesh.num_nodes(); ++v) {
    const Eigen::Vector3d e = exact(body.mesh.nodes.row(v).transpose(), node_cut_side(body, v));
    error = std::max(error, (u.segment<3>(3 * v) - e).norm());
    size = std::max(size, e.norm());
  }
  const kerf::PointLocator locator(body.mesh);
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j)
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d s((i + 0.37) / 5.0, (j + 0.41) / 5.0, (k + 0.29) / 3.0);
        const Eigen::Vector3d x = slab_min + s.cwiseProduct(slab_max - slab_min);
        const kerf::PointLocation where = locator.locate(x);
        REQUIRE(where.tet >= 0);
        error = std::max(error, (body.model.displacement_at(u, where.tet, x) - exact(x, 0)).norm());
      }
  return error / size;
}

// A homogeneous stress with sigma b = 0 on a cut of normal b (sigma_aa, sigma_cc, sigma_ac only),
// and its displacement plus a translation: the patch test field of a cut of that normal.
Field traction_free_linear_field(const Eigen::Vector3d& a, const Eigen::Vector3d& c) {
  const double s = 1.0e4; // Pa
  const Eigen::Matrix3d sigma = s * (a * a.transpose() + 0.5 * c * c.transpose() + 0.3 * (a * c.transpose() + c * a.transpose()));
  const Eigen::Matrix3d H = support::strain_of_stress(sigma, material);
  return [H](const Eigen::Vector3d& x, int) { return Eigen::Vector3d(H * x + Eigen::Vector3d(1e-3, -2e-3, 0.5e-3)); };
}

// The patch test with the topological rule (sign nodes and branch nodes side by side).
double patch_test_error(const kerf::TetMesh& mesh, std::vector<kerf::TriangleSurface> cuts, const Eigen::Vector3d& a, const Eigen::Vector3d& c) {
  const support::TipBody body(mesh, std::move(cuts), material, kerf::TipEnrichmentRule::topological, 0.0, kerf::FrontRule::collapsed, front_points, blending_degree,
                              blending_depth);
  REQUIRE(body.branch.num_branch_nodes() > 0);
  const Field exact = traction_free_linear_field(a, c);
  const Eigen::VectorXd u = solve_with_boundary(body, exact, nullptr);
  REQUIRE(u.allFinite());
  return largest_relative_error(body, u, exact);
}

// Williams's mixed-mode field about `front` with every node branch enriched.
double williams_error(const support::StraightFront& front) {
  // A radius beyond the slab's diagonal: every node is branch enriched.
  const support::TipBody body(slab(), {support::half_plane_behind(front)}, material, kerf::TipEnrichmentRule::geometric, 2.0, kerf::FrontRule::collapsed, front_points,
                              blending_degree, blending_depth);
  REQUIRE(body.branch.num_branch_nodes() == body.mesh.num_nodes());
  // The model's frame is the test's (a ahead, b the normal): a test of the degenerate front's frame.
  const kerf::FrontPolar polar = body.fronts.polar(front.origin + 0.05 * front.b - 0.02 * front.a);
  CHECK((polar.a - front.a).norm() < 1e-12);
  CHECK((polar.b - front.b).norm() < 1e-12);
  const double K_I = 1.0e4, K_II = -0.6e4; // mixed mode (Pa sqrt(m))
  const Field exact = [&](const Eigen::Vector3d& x, int cut_side) { return support::williams(front, K_I, K_II, material, x, cut_side); };
  // A node the model puts on the cut must lie on it, up to round-off: behind the front (or on it),
  // in the cut's plane.
  for (Eigen::Index v = 0; v < body.mesh.num_nodes(); ++v)
    if (node_cut_side(body, v) != 0) {
      const Eigen::Vector3d y = body.mesh.nodes.row(v).transpose() - front.origin;
      CHECK(std::abs(y.dot(front.b)) <= 1e-12 * y.norm());
      CHECK(y.dot(front.a) <= 1e-12 * y.norm());
    }
  const std::array<Eigen::Vector3d, 4> c = support::williams_branch_coefficients(front, K_I, K_II, material);
  const Eigen::VectorXd u = solve_with_boundary(body, exact, &c);
  REQUIRE(u.allFinite());
  return largest_relative_error(body, u, exact);
}

// The length of the fronts inside each tet, summed over the tets (a front in a face counts twice).
double summed_front_in_tets(const kerf::TetMesh& mesh, const kerf::CrackFronts& fronts) {
  double sum = 0.0;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    for (const kerf::FrontPiece& p : kerf::front_in_tet(fronts, kerf::tet_corners(mesh, t))) sum += (p.end - p.start).norm();
  return sum;
}

// The number of tets that hold pieces of two different fronts.
int tets_holding_two_fronts(const kerf::TetMesh& mesh, const kerf::CrackFronts& fronts) {
  int shared = 0;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    std::set<int> lines;
    for (const kerf::FrontPiece& p : kerf::front_in_tet(fronts, kerf::tet_corners(mesh, t))) lines.insert(p.polyline);
    shared += lines.size() == 2;
  }
  return shared;
}

// Tolerances. With the cheap rules the regular front (the first test case) leaves 7.4e-5 of the
// Williams field and 5.7e-5 of the patch field: quadrature error of the branch test functions'
// rows (the space holds both fields exactly). The degenerate fronts measured 5e-5 to 5e-4 (the
// front through a node the largest on Williams) and up to 1.3e-3 on the patch test (the L-shaped
// front of a cut leaving the mesh: a tet holding both of its segments is collapsed onto one,
// front_quadrature.hpp's limitation). A wrong frame, side or shift gives errors of order 1 (the
// front in faces did, 0.5, before the fix of branch_enrichment.cpp and cut_xfem_model.cpp; a cut
// in a plane of nodes 1.2 to 1.3 with Williams's field taken on the face below at the nodes the
// model puts on the cut), so 3e-3 separates the two.
constexpr double williams_tolerance = 3e-3, patch_tolerance = 3e-3;

// The patch test (topological rule) and Williams's field (every node enriched) about a single
// straight front on the slab, each within its bound.
void check_both_fields(const char* name, const support::StraightFront& front) {
  const double patch = patch_test_error(slab(), {support::half_plane_behind(front)}, front.a, front.c);
  const double williams = williams_error(front);
  MESSAGE(std::string(name) << ": patch test " << patch << ", Williams " << williams);
  CHECK(patch < patch_tolerance);
  CHECK(williams < williams_tolerance);
}

} // namespace

TEST_CASE("a front along mesh edges: its tets are those around the edges, Williams's field and the patch test are reproduced") {
  // The front is the column of vertical mesh edges x = y = 0.1; the cut behind it leaves at 30
  // degrees to x (through no other node).
  const double alpha = M_PI / 6.0;
  const support::StraightFront front =
      support::StraightFront({0.1, 0.1, 0.0}, {std::cos(alpha), std::sin(alpha), 0.0}, {-std::sin(alpha), std::cos(alpha), 0.0});
  const kerf::TetMesh mesh = slab();
  const kerf::CutSurfaces cuts({support::half_plane_behind(front)});
  const kerf::CrackFronts fronts = kerf::find_crack_fronts(mesh, cuts);
  REQUIRE(fronts.polylines.size() == 1);
  CHECK(fronts.length() == kerf_test::relative(0.2, 1e-12));
  // Every tet holding a whole vertical edge of the column holds the front along it.
  double expected = 0.0;
  std::set<int> around_edges;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    int on_column = 0;
    for (int a = 0; a < 4; ++a) {
      const Eigen::Vector3d x = mesh.nodes.row(mesh.tets(t, a)).transpose();
      on_column += std::abs(x[0] - 0.1) < 1e-12 && std::abs(x[1] - 0.1) < 1e-12;
    }
    if (on_column == 2) {
      expected += 0.1;
      for (int a = 0; a < 4; ++a) around_edges.insert(mesh.tets(t, a));
    }
  }
  CHECK(summed_front_in_tets(mesh, fronts) == kerf_test::relative(expected, 1e-12));
  const kerf::MeshPieces pieces = kerf::cut_mesh_into_pieces(mesh, cuts);
  const kerf::BranchEnrichment topological = kerf::make_branch_enrichment(mesh, pieces, fronts, kerf::TipEnrichmentRule::topological);
  CHECK(std::set<int>(topological.branch_node.begin(), topological.branch_node.end()) == around_edges);

  check_both_fields("front along edges", front);
}

TEST_CASE("a front exactly through a node: its length and tets are right, F = 0 at the node, and the fields are reproduced") {
  // A front in a direction along no mesh line, through the interior node (0.1, 0.1, 0.1).
  const Eigen::Vector3d c = Eigen::Vector3d(0.3, -0.2, 1.0).normalized();
  const Eigen::Vector3d b = (Eigen::Vector3d::UnitY() - c.y() * c).normalized();
  const support::StraightFront front = support::StraightFront({0.1, 0.1, 0.1}, b.cross(c), b);
  const kerf::TetMesh mesh = slab();
  const kerf::CutSurfaces cuts({support::half_plane_behind(front)});
  const kerf::CrackFronts fronts = kerf::find_crack_fronts(mesh, cuts);
  REQUIRE(fronts.polylines.size() == 1);
  // It leaves through the top and the bottom: length 0.2 / c_z.
  CHECK(fronts.length() == kerf_test::relative(0.2 / c.z(), 1e-12));
  // A line in general position meets each tet in a segment of its own: the pieces add up to the length.
  CHECK(summed_front_in_tets(mesh, fronts) == kerf_test::relative(0.2 / c.z(), 1e-12));
  const kerf::MeshPieces pieces = kerf::cut_mesh_into_pieces(mesh, cuts);
  const kerf::BranchEnrichment topological = kerf::make_branch_enrichment(mesh, pieces, fronts, kerf::TipEnrichmentRule::topological);
  int node = -1;
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v)
    if ((mesh.nodes.row(v).transpose() - front.origin).norm() < 1e-12) node = static_cast<int>(v);
  REQUIRE(node >= 0);
  const int slot = topological.branch_slot[static_cast<std::size_t>(node)];
  REQUIRE(slot >= 0);
  // r = 0 up to the round-off of the clipped front's ends (1e-17 m): every F_l(x_i) ~ sqrt(r)
  // vanishes to 1e-8, and is finite.
  CHECK(topological.node_values[static_cast<std::size_t>(slot)].norm() < 1e-7);

  check_both_fields("front through a node", front);
}

TEST_CASE("the regular front through the middle of elements: the reference for the bounds below") {
  const support::StraightFront front({0.0, 0.0, 0.0}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY());
  check_both_fields("regular front", front);
}

TEST_CASE("a front lying in mesh faces: the tets on both sides hold it, and the fields are reproduced") {
  // The cut y = 0, x < 0.1: the front x = 0.1, y = 0 lies in the plane of faces x = 0.1 (crossing
  // their diagonals).
  const support::StraightFront front({0.1, 0.0, 0.0}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY());
  const kerf::TetMesh mesh = slab();
  const kerf::CutSurfaces cuts({support::half_plane_behind(front)});
  const kerf::CrackFronts fronts = kerf::find_crack_fronts(mesh, cuts);
  REQUIRE(fronts.polylines.size() == 1);
  CHECK(fronts.length() == kerf_test::relative(0.2, 1e-12));
  // A point of a face lies in the two tets beside it: twice the length.
  CHECK(summed_front_in_tets(mesh, fronts) == kerf_test::relative(0.4, 1e-12));
  // The front tets are the tets with a face in the squares x = 0.1, y in [-0.1, 0.1] (one on
  // each side of each of their triangles): the branch nodes are their nodes.
  std::set<int> beside_faces;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    int in_square = 0;
    for (int a = 0; a < 4; ++a) {
      const Eigen::Vector3d x = mesh.nodes.row(mesh.tets(t, a)).transpose();
      in_square += std::abs(x[0] - 0.1) < 1e-12 && std::abs(x[1]) < 0.1 + 1e-12;
    }
    if (in_square == 3)
      for (int a = 0; a < 4; ++a) beside_faces.insert(mesh.tets(t, a));
  }
  const kerf::MeshPieces pieces = kerf::cut_mesh_into_pieces(mesh, cuts);
  const kerf::BranchEnrichment topological = kerf::make_branch_enrichment(mesh, pieces, fronts, kerf::TipEnrichmentRule::topological);
  CHECK(std::set<int>(topological.branch_node.begin(), topological.branch_node.end()) == beside_faces);

  check_both_fields("front in faces", front);
}

TEST_CASE("a cut in a plane of nodes: the nodes on it take the side above, and the fields are reproduced") {
  // The cut y = 0.1 holds the slab's row of nodes y = 0.1 behind the front: in floating point
  // they lie at 0.09999999999999998, 2.8e-17 below the cut, which chapter 4's snap (a tet face
  // within 1e-12 of the tet's size of a cut plane is covered) and the model count as on it, the
  // side above. The front x = x_f, y = 0.1 lies in the plane of faces y = 0.1, crossing the
  // diagonals of its squares, for x_f = 0.05 and x_f = 0; the cut at the nodes' own y, exactly
  // through them, once more for x_f = 0.05. The Williams field evaluated at a node on the cut
  // with atan2 of x_b = -2.8e-17 took the face below, which the node's standard DOF does not
  // hold: the Dirichlet values of the boundary nodes on the cut were then off by the crack
  // opening, and the solve missed the field by 40-50 % at the nodes (failures.md) and 1.2-1.3
  // of its size over the slab; with the node's side (support::williams's cut_side) it is the
  // space's own field (its interpolant is exact to 6e-16), and the errors are those of the
  // other cases.
  const double row_y = slab().nodes(8, 1); // node (i, j, k) = (0, 2, 0): x = -0.3, y = 0.1 - 2.8e-17
  REQUIRE(row_y != 0.1);
  REQUIRE(std::abs(row_y - 0.1) < 1e-16);
  for (const auto& [name, x_f, y] : {std::tuple<const char*, double, double>{"cut in a plane of nodes, front at x = 0.05", 0.05, 0.1},
                                     {"cut in a plane of nodes, front at x = 0", 0.0, 0.1},
                                     {"cut exactly through a plane of nodes, front at x = 0.05", 0.05, row_y}}) {
    const std::string label = name;
    CAPTURE(label);
    const support::StraightFront front({x_f, y, 0.0}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY());
    // The nodes on the cut: the row y = 0.1 behind the front, x in {-0.3, -0.1}, z in {0, 0.1, 0.2}.
    const kerf::TetMesh mesh = slab();
    const kerf::CutSurfaces cuts({support::half_plane_behind(front)});
    const kerf::MeshPieces pieces = kerf::cut_mesh_into_pieces(mesh, cuts);
    const kerf::BranchEnrichment all = kerf::make_branch_enrichment(mesh, pieces, kerf::find_crack_fronts(mesh, cuts), kerf::TipEnrichmentRule::geometric, 2.0);
    int on_cut = 0, expected = 0;
    for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) {
      on_cut += all.cut_side[static_cast<std::size_t>(v)] == 1;
      expected += std::abs(mesh.nodes(v, 1) - 0.1) < 1e-12 && mesh.nodes(v, 0) < x_f;
    }
    CHECK(expected == 6);
    CHECK(on_cut == expected);

    check_both_fields(name, front);
  }
}

TEST_CASE("a cut whose boundary leaves the mesh: only the inside part is front, an L of length 0.45 ending on the skin") {
  // The rectangle y = 0, x in [-1, 0], z in [0.05, 1]: its edges x = -1 and z = 1 lie outside the
  // slab, the edge z = 0.05 is inside for x in [-0.3, 0] only, the edge x = 0 for z in [0.05, 0.2].
  const kerf::TriangleSurface cut = kerf::rectangle_surface(kerf::RectangleCut({-1.0, 0.0, 1.0}, {1.0, 0.0, 0.0}, {0.0, 0.0, -0.95}));
  const kerf::TetMesh mesh = slab();
  const kerf::CrackFronts fronts = kerf::find_crack_fronts(mesh, kerf::CutSurfaces({cut}));
  REQUIRE(fronts.polylines.size() == 1);
  const kerf::FrontPolyline& line = fronts.polylines[0];
  CHECK_FALSE(line.closed);
  CHECK(line.segments.size() == 2);
  CHECK(fronts.length() == kerf_test::relative(0.45, 1e-12));
  // Its ends lie on the skin, where the rectangle's boundary leaves the slab.
  const Eigen::Vector3d end_1(-0.3, 0.0, 0.05), end_2(0.0, 0.0, 0.2);
  const Eigen::Vector3d first = line.points.front(), last = line.points.back();
  CHECK(std::min((first - end_1).norm() + (last - end_2).norm(), (first - end_2).norm() + (last - end_1).norm()) < 1e-12);

  const double patch = patch_test_error(mesh, {cut}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ());
  MESSAGE("cut leaving the mesh: patch test " << patch);
  CHECK(patch < patch_tolerance);
}

TEST_CASE("two fronts in one tet: a narrow slit whose two ends share tets, solvable and passing the patch test") {
  // The slit y = 0, x in [0.02, 0.08], through the thickness: both fronts lie in the middle
  // column of cells (x in [-0.1, 0.1]), on the same side of its tets' diagonal planes x = y, so
  // that some tet holds both (a tet of a box cell is where its coordinates keep one order).
  const kerf::TriangleSurface slit = kerf::rectangle_surface(kerf::RectangleCut({0.02, 0.0, -1.0}, {0.0, 0.0, 2.0}, {0.06, 0.0, 0.0}));
  const kerf::TetMesh mesh = slab();
  const kerf::CrackFronts fronts = kerf::find_crack_fronts(mesh, kerf::CutSurfaces({slit}));
  REQUIRE(fronts.polylines.size() == 2);
  CHECK(fronts.length() == kerf_test::relative(0.4, 1e-12));
  const int shared = tets_holding_two_fronts(mesh, fronts);
  MESSAGE("slit: " << shared << " tets hold both fronts");
  CHECK(shared > 0);

  const double patch = patch_test_error(mesh, {slit}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ());
  MESSAGE("slit: patch test " << patch);
  CHECK(patch < patch_tolerance);
}

TEST_CASE("two fronts in one tet: two cuts whose fronts pass the same tets: solvable, a rigid motion exact, the patch test missed by 10 %") {
  // Cut A: y = 0, x < 0; cut B: y = 0.05, x > 0.03 (its front faces -x). Both fronts run along z
  // through the middle column of cells; the cuts do not meet.
  const kerf::TriangleSurface cut_a = kerf::rectangle_surface(kerf::RectangleCut({-2.0, 0.0, -1.0}, {0.0, 0.0, 2.0}, {2.0, 0.0, 0.0}));
  const kerf::TriangleSurface cut_b = kerf::rectangle_surface(kerf::RectangleCut({0.03, 0.05, -1.0}, {0.0, 0.0, 2.0}, {2.0, 0.0, 0.0}));
  const kerf::TetMesh mesh = slab();
  const kerf::CrackFronts fronts = kerf::find_crack_fronts(mesh, kerf::CutSurfaces({cut_a, cut_b}));
  REQUIRE(fronts.polylines.size() == 2);
  CHECK(fronts.length() == kerf_test::relative(0.4, 1e-12));
  const int shared = tets_holding_two_fronts(mesh, fronts);
  MESSAGE("two cuts: " << shared << " tets hold both fronts");
  CHECK(shared > 0);

  // A rigid motion has no strain anywhere, whatever the enrichment: the solve returns it to round-off.
  const support::TipBody body(mesh, {cut_a, cut_b}, material, kerf::TipEnrichmentRule::topological, 0.0, kerf::FrontRule::collapsed, front_points, blending_degree,
                              blending_depth);
  const Field rigid = [](const Eigen::Vector3d& x, int) { return Eigen::Vector3d(Eigen::Vector3d(1e-3, -2e-3, 0.5e-3) + Eigen::Vector3d(0.01, 0.02, -0.03).cross(x)); };
  const Eigen::VectorXd u = solve_with_boundary(body, rigid, nullptr);
  REQUIRE(u.allFinite());
  const double rigid_error = largest_relative_error(body, u, rigid);
  MESSAGE("two cuts: rigid motion " << rigid_error);
  CHECK(rigid_error < 1e-10);
  // The patch test is NOT passed: a point takes the branch functions of its nearest front
  // (CrackFronts::polar), so a node's functions jump where the nearest front changes, on the
  // surface halfway between the fronts, inside tets near both; the discrete equations then miss
  // the linear field by 10 % (measured 0.099). A documented limitation (failures.md): tying each
  // branch node to one front would cure it. The bound pins the measured size, so that a change
  // either way is seen.
  const double patch = patch_test_error(mesh, {cut_a, cut_b}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ());
  MESSAGE("two cuts: patch test " << patch);
  CHECK(patch > 0.05);
  CHECK(patch < 0.2);
}
