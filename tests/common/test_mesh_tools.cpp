// The box mesher, Tet10 promotion, boundary faces, node regions and point location.
#include "kerf/fem/evaluate_displacement.hpp"
#include "kerf/mesh/boundary_faces.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/check_tet_mesh.hpp"
#include "kerf/mesh/node_region.hpp"
#include "kerf/mesh/point_locator.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <set>

TEST_CASE("box mesh: counts, positive volumes that fill the box, conforming faces") {
  const Eigen::Vector3d lo(0, 0, 0), hi(0.03, 0.06, 0.2);
  const kerf::TetMesh mesh = kerf::make_box_mesh(lo, hi, {3, 6, 20});
  CHECK(mesh.num_nodes() == 4 * 7 * 21);
  CHECK(mesh.num_tets() == 6 * 3 * 6 * 20);
  double volume = 0.0;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const double v = kerf::signed_tet_volume(mesh, t);
    CHECK(v > 0.0);
    volume += v;
  }
  CHECK(volume == kerf_test::relative(0.03 * 0.06 * 0.2, 1e-13));
  // Conforming: the boundary of the mesh is exactly the box surface, 2 triangles per cell face.
  const kerf::BoundaryFaces boundary = kerf::boundary_faces(mesh);
  CHECK(boundary.faces.rows() == 2 * 2 * (3 * 6 + 3 * 20 + 6 * 20));
  double area = 0.0;
  for (Eigen::Index f = 0; f < boundary.faces.rows(); ++f) area += kerf::face_area(mesh, boundary, f);
  CHECK(area == kerf_test::relative(2 * (0.03 * 0.06 + 0.03 * 0.2 + 0.06 * 0.2), 1e-13));
}

TEST_CASE("boundary faces point outward") {
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {2, 2, 2});
  const kerf::BoundaryFaces boundary = kerf::boundary_faces(mesh);
  const Eigen::Vector3d centre(0.5, 0.5, 0.5);
  for (Eigen::Index f = 0; f < boundary.faces.rows(); ++f) {
    const Eigen::Vector3d x0 = mesh.nodes.row(boundary.faces(f, 0)).transpose();
    const Eigen::Vector3d x1 = mesh.nodes.row(boundary.faces(f, 1)).transpose();
    const Eigen::Vector3d x2 = mesh.nodes.row(boundary.faces(f, 2)).transpose();
    const Eigen::Vector3d normal = (x1 - x0).cross(x2 - x0);
    CHECK(normal.dot((x0 + x1 + x2) / 3.0 - centre) > 0.0);
  }
}

TEST_CASE("Tet10 from Tet4: shared mid-edge nodes at edge midpoints") {
  const kerf::TetMesh tet4 = kerf::make_box_mesh({0, 0, 0}, {1, 2, 3}, {2, 2, 2});
  const kerf::TetMesh tet10 = kerf::tet10_from_tet4(tet4);
  // Edges of a Kuhn box mesh: 3 axis directions, 3 face diagonals, 1 body diagonal per cell, plus the boundary ones.
  std::set<std::pair<int, int>> edges;
  for (Eigen::Index t = 0; t < tet4.num_tets(); ++t)
    for (const auto& e : kerf::tet_edge_corners)
      edges.insert(std::minmax(tet4.tets(t, e[0]), tet4.tets(t, e[1])));
  CHECK(tet10.num_nodes() == tet4.num_nodes() + static_cast<Eigen::Index>(edges.size()));
  for (Eigen::Index t = 0; t < tet10.num_tets(); ++t)
    for (int e = 0; e < 6; ++e) {
      const Eigen::RowVector3d mid = 0.5 * (tet10.nodes.row(tet10.tets(t, kerf::tet_edge_corners[e][0])) +
                                            tet10.nodes.row(tet10.tets(t, kerf::tet_edge_corners[e][1])));
      CHECK((tet10.nodes.row(tet10.tets(t, 4 + e)) - mid).norm() < 1e-15);
    }
  CHECK(kerf::boundary_faces(tet10).faces.cols() == 6);
}

TEST_CASE("node regions: a box catches the nodes on its faces despite round-off") {
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {0.03, 0.06, 0.2}, {3, 6, 20});
  kerf::NodeRegion bottom;
  bottom.box_min = {0, 0, 0};
  bottom.box_max = {0.03, 0.06, 0};
  CHECK(kerf::nodes_in_region(mesh, bottom).size() == 4 * 7);
  kerf::NodeRegion list;
  list.is_box = false;
  list.node_list = {5, 3, 5};
  CHECK(kerf::nodes_in_region(mesh, list) == std::vector<int>{3, 5});
}

TEST_CASE("point locator: nodes, interior points and outside points") {
  kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {3, 3, 3});
  mesh = kerf::tet10_from_tet4(mesh);
  const kerf::PointLocator locator(mesh);
  // A quadratic field is interpolated exactly by Tet10: evaluating at arbitrary points checks
  // the located tet and xi together.
  Eigen::VectorXd u(3 * mesh.num_nodes());
  const auto field = [](const Eigen::Vector3d& x) { return Eigen::Vector3d(x[0] * x[1], x[2] * x[2], x[0] - x[1] * x[2]); };
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) u.segment<3>(3 * v) = field(mesh.nodes.row(v).transpose());
  Eigen::MatrixXd points(5, 3);
  points << 0.1, 0.2, 0.3, 1.0, 1.0, 1.0, 0.0, 0.5, 0.25, 0.7, 0.7, 0.1, 1.5, 0.5, 0.5;
  Eigen::Index outside = 0;
  const Eigen::MatrixXd values = kerf::evaluate_displacement_at(mesh, u, points, outside);
  CHECK(outside == 1);
  CHECK(std::isnan(values(4, 0)));
  for (int p = 0; p < 4; ++p) CHECK((values.row(p).transpose() - field(points.row(p).transpose())).norm() < 1e-14);
}
