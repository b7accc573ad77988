// A tet cut by triangles into pieces (cut/tet_pieces.hpp): against chapter 3's plane clipping
// for random planes, a plane given as two triangles, a cut that ends inside the tet, cuts
// exactly through a corner, along an edge and along a face, a fold that makes three pieces, a
// right-angled kink, and the closed boundary of every piece (the divergence theorem).
#include "common/random_fan.hpp"
#include "kerf/cut/clip_tet.hpp"
#include "kerf/cut/convex_cell.hpp"
#include "kerf/cut/tet_pieces.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <optional>
#include <random>
#include <vector>

namespace {

using Corners = Eigen::Matrix<double, 4, 3>;
using kerf::CutTriangle;

Corners unit_tet() {
  Corners X;
  X << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  return X;
}

CutTriangle triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, int index = 0) {
  return {{a, b, c}, 0, index};
}

// The square {origin + s e1 + t e2 : 0 <= s, t <= 1} as two triangles, normal e1 x e2.
std::vector<CutTriangle> square(const Eigen::Vector3d& origin, const Eigen::Vector3d& e1, const Eigen::Vector3d& e2,
                                int first_index = 0) {
  return {triangle(origin, origin + e1, origin + e1 + e2, first_index),
          triangle(origin, origin + e1 + e2, origin + e2, first_index + 1)};
}

// (1/3) sum of x . A over the boundary of a piece (the divergence theorem for div x = 3): the
// piece's volume computed from its boundary alone, and the sum of its area vectors (0 for a
// closed surface).
struct BoundaryCheck {
  double volume = 0.0;
  double open_area = 0.0;
  double area = 0.0;
};
BoundaryCheck check_boundary(const kerf::TetPiece& piece) {
  BoundaryCheck check;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const kerf::PieceBoundaryPolygon& b : piece.boundary) {
    const Eigen::Vector3d a = kerf::polygon_area_vector(b.polygon);
    check.volume += b.polygon.front().dot(a) / 3.0;
    check.area += a.norm();
    sum += a;
  }
  check.open_area = sum.norm();
  return check;
}

// Round-off in a volume (an area) is relative to the cube (the square) of the tet's size d, not
// to the piece's own (a sliver's volume is a small difference of large products): 1e-14 d^3 is
// some 50 epsilon.
void require_closed_pieces(const kerf::TetPieces& pieces) {
  double diameter = 0.0;
  for (const kerf::ConvexCell& cell : pieces.cells)
    for (const kerf::CellFace& face : cell.faces)
      for (const Eigen::Vector3d& x : face.polygon)
        diameter = std::max(diameter, (x - pieces.cells.front().faces.front().polygon.front()).norm());
  double total = 0.0;
  for (const kerf::TetPiece& piece : pieces.pieces) {
    const BoundaryCheck check = check_boundary(piece);
    // Each area vector carries round-off of about epsilon d^2, more where a plane grazes an edge
    // and the crossing point is ill-determined: 1e-12 d^2 bounds it over a few dozen faces.
    CHECK(check.open_area <= 1e-12 * diameter * diameter);
    // The same round-off on the volume of a sliver that grazing plane leaves is relatively larger
    // (measured: 1.3e-11 at worst).
    CHECK(check.volume == kerf_test::relative(piece.volume, 1e-10));
    CHECK(piece.volume > 0.0);
    total += piece.volume;
  }
  // Summed over N cells the independent round-offs grow like sqrt(N): a tet split into 28000
  // cells (the fine icosphere) is allowed 17 times more than one of 100.
  const double cells = static_cast<double>(pieces.cells.size());
  CHECK(std::abs(total - pieces.volume) <= 1e-14 * std::pow(diameter, 3) * std::max(1.0, std::sqrt(cells / 100.0)));
}

} // namespace

TEST_CASE("a tet cut by one large triangle has the pieces of chapter 3's plane clipping") {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  int cut = 0;
  for (int trial = 0; trial < 200; ++trial) {
    Corners X;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 3; ++j) X(i, j) = uniform(random);
    Eigen::Vector3d n(uniform(random), uniform(random), uniform(random));
    n.normalize();
    const Eigen::Vector3d x0(0.3 * uniform(random), 0.3 * uniform(random), 0.3 * uniform(random));
    const Eigen::Vector3d u = n.unitOrthogonal() * 10.0, v = n.cross(n.unitOrthogonal()) * 10.0;
    const CutTriangle T = triangle(x0 - u - v, x0 + 2.0 * u - v, x0 - u + 2.0 * v);
    const kerf::TetPieces pieces = kerf::split_tet_by_triangles(X, {T});
    Eigen::Vector4d lambda;
    for (int i = 0; i < 4; ++i) lambda[i] = n.dot(X.row(i).transpose() - x0);
    const kerf::ClippedTet reference = kerf::clip_tet(X, lambda);
    require_closed_pieces(pieces);
    if (reference.V_a > 0.0 && reference.V_b > 0.0) {
      ++cut;
      REQUIRE(pieces.num_pieces() == 2);
      CHECK(pieces.state == kerf::SurfaceCutState::completely_cut);
      // Which piece is above: the one holding a corner with lambda > 0.
      int above_corner = 0;
      while (lambda[above_corner] <= 0.0) ++above_corner;
      const int above = pieces.corner_pieces[above_corner].front();
      // Against the clipping of chapter 3, another formula: 1e-10 relative for the random tets'
      // thinnest pieces (measured: 1.6e-11).
      CHECK(pieces.pieces[above].volume == kerf_test::relative(reference.V_a, 1e-10));
      CHECK(pieces.pieces[1 - above].volume == kerf_test::relative(reference.V_b, 1e-10));
    } else {
      CHECK(pieces.num_pieces() == 1);
    }
  }
  CHECK(cut > 50);
}

TEST_CASE("a plane given as two triangles whose shared edge crosses the tet cuts it as one plane") {
  const Corners X = unit_tet();
  // The plane x + y + z = 0.6 as a square whose diagonal runs through the tet.
  const Eigen::Vector3d n = Eigen::Vector3d(1, 1, 1).normalized();
  const Eigen::Vector3d c(0.2, 0.2, 0.2);
  const Eigen::Vector3d e1 = n.unitOrthogonal() * 3.0, e2 = n.cross(e1);
  const kerf::TetPieces pieces = kerf::split_tet_by_triangles(X, square(c - 0.5 * e1 - 0.5 * e2, e1, e2));
  REQUIRE(pieces.num_pieces() == 2);
  require_closed_pieces(pieces);
  const int corner_piece = pieces.corner_pieces[0].front();
  CHECK(pieces.pieces[corner_piece].volume == kerf_test::relative(std::pow(0.6, 3) / 6.0, 1e-13));
}

TEST_CASE("a cut that ends inside the tet leaves it in one piece: partially cut") {
  const Corners X = unit_tet();
  // The plane z = 0.2, but only for x <= 0.3: the front x = 0.3 runs through the tet.
  const kerf::TetPieces pieces =
      kerf::split_tet_by_triangles(X, square({-1.0, -1.0, 0.2}, {1.3, 0.0, 0.0}, {0.0, 3.0, 0.0}));
  CHECK(pieces.num_pieces() == 1);
  CHECK(pieces.state == kerf::SurfaceCutState::partially_cut);
  require_closed_pieces(pieces);
  // Its boundary holds both sides of the cut: the cut's area counted twice.
  double cut_area = 0.0;
  for (const kerf::PieceBoundaryPolygon& b : pieces.pieces[0].boundary)
    if (b.on_cut) cut_area += kerf::polygon_area_vector(b.polygon).norm();
  // The section z = 0.2 is the triangle x, y >= 0, x + y <= 0.8; its part x <= 0.3 has area
  // 0.8^2 / 2 - 0.5^2 / 2.
  CHECK(cut_area == kerf_test::relative(2.0 * (0.32 - 0.125), 1e-12));
}

TEST_CASE("a cut exactly through corners, along an edge and along a face is decided exactly") {
  const Corners X = unit_tet();
  SUBCASE("the plane y = x through corners 0 and 3 (the edge 0-3 lies in the cut)") {
    const kerf::TetPieces pieces =
        kerf::split_tet_by_triangles(X, square({-1.0, -1.0, -1.0}, {3.0, 3.0, 0.0}, {0.0, 0.0, 3.0}));
    REQUIRE(pieces.num_pieces() == 2);
    require_closed_pieces(pieces);
    CHECK(pieces.corner_pieces[0].size() == 2);
    CHECK(pieces.corner_pieces[3].size() == 2);
    CHECK(pieces.corner_pieces[1].size() == 1);
    CHECK(pieces.corner_pieces[2].size() == 1);
    CHECK(pieces.pieces[0].volume == kerf_test::relative(1.0 / 12.0, 1e-14));
  }
  SUBCASE("the plane x = 0, the tet's own face: touched, one piece") {
    const kerf::TetPieces pieces =
        kerf::split_tet_by_triangles(X, square({0.0, -1.0, -1.0}, {0.0, 3.0, 0.0}, {0.0, 0.0, 3.0}));
    CHECK(pieces.num_pieces() == 1);
    CHECK(pieces.state == kerf::SurfaceCutState::touched);
    require_closed_pieces(pieces);
  }
  SUBCASE("a plane through a corner that misses the rest: uncut") {
    // x + y + z = 0 touches the tet at corner 0 only.
    const Eigen::Vector3d n = Eigen::Vector3d(1, 1, 1).normalized();
    const Eigen::Vector3d e1 = n.unitOrthogonal() * 2.0, e2 = n.cross(e1);
    const kerf::TetPieces pieces = kerf::split_tet_by_triangles(X, square(-0.5 * e1 - 0.5 * e2, e1, e2));
    CHECK(pieces.num_pieces() == 1);
    CHECK(pieces.state == kerf::SurfaceCutState::uncut);
  }
  SUBCASE("a corner one double above the plane stays above: the predicate is exact") {
    Corners Y = X;
    Y(0, 2) = 0.3; // a corner exactly on z = 0.3 ...
    const kerf::TetPieces on_plane =
        kerf::split_tet_by_triangles(Y, square({-1.0, -1.0, 0.3}, {3.0, 0.0, 0.0}, {0.0, 3.0, 0.0}));
    CHECK(on_plane.corner_pieces[0].size() == 2);
    Y(0, 2) = std::nextafter(0.3, 1.0); // ... and the next double above it
    const kerf::TetPieces above =
        kerf::split_tet_by_triangles(Y, square({-1.0, -1.0, 0.3}, {3.0, 0.0, 0.0}, {0.0, 3.0, 0.0}));
    CHECK(above.corner_pieces[0].size() == 1);
  }
}

TEST_CASE("a surface folded back through the tet cuts it into three pieces") {
  const Corners X = unit_tet();
  // Two sheets z = 0.1 and z = 0.2, joined by a wall at x = 2 outside the tet, oriented
  // consistently (a fold): the lower sheet faces up, the wall faces +x, the upper sheet down.
  std::vector<CutTriangle> fold = square({-1.0, -1.0, 0.1}, {3.0, 0.0, 0.0}, {0.0, 3.0, 0.0}, 0);
  const std::vector<CutTriangle> wall = square({2.0, -1.0, 0.1}, {0.0, 0.0, 0.1}, {0.0, 3.0, 0.0}, 2);
  const std::vector<CutTriangle> upper = square({2.0, -1.0, 0.2}, {-3.0, 0.0, 0.0}, {0.0, 3.0, 0.0}, 4);
  fold.insert(fold.end(), wall.begin(), wall.end());
  fold.insert(fold.end(), upper.begin(), upper.end());
  const kerf::TetPieces pieces = kerf::split_tet_by_triangles(X, fold);
  REQUIRE(pieces.num_pieces() == 3);
  CHECK(pieces.state == kerf::SurfaceCutState::completely_cut);
  require_closed_pieces(pieces);
  // The slabs of the unit tet: volume below z = t is (1 - (1 - t)^3) / 6.
  const auto below = [](double t) { return (1.0 - std::pow(1.0 - t, 3)) / 6.0; };
  std::vector<double> volumes;
  for (const kerf::TetPiece& piece : pieces.pieces) volumes.push_back(piece.volume);
  std::sort(volumes.begin(), volumes.end());
  CHECK(volumes[0] == kerf_test::relative(below(0.2) - below(0.1), 1e-13));
  CHECK(volumes[1] == kerf_test::relative(below(0.1), 1e-13));
  CHECK(volumes[2] == kerf_test::relative(1.0 / 6.0 - below(0.2), 1e-13));
}

TEST_CASE("a right-angled kink cuts out the piece that two plane clippings give") {
  const Corners X = unit_tet();
  // The floor z = 0.3 for x >= 0.2 and the wall x = 0.2 for z <= 0.3, meeting along the kink
  // x = 0.2, z = 0.3: the piece {x > 0.2, z < 0.3} is cut out. The wall's plane is the plane of
  // the floor's kink edge, which is the case a face made for one triangle lies in another's plane.
  std::vector<CutTriangle> kink = square({0.2, -1.0, 0.3}, {0.0, 3.0, 0.0}, {3.0, 0.0, 0.0}, 0);
  const std::vector<CutTriangle> wall = square({0.2, -1.0, -1.0}, {0.0, 3.0, 0.0}, {0.0, 0.0, 1.3}, 2);
  kink.insert(kink.end(), wall.begin(), wall.end());
  const kerf::TetPieces pieces = kerf::split_tet_by_triangles(X, kink);
  REQUIRE(pieces.num_pieces() == 2);
  require_closed_pieces(pieces);
  // Independent reference: clip by x = 0.2 (chapter 3), then the part x >= 0.2 by z = 0.3.
  Eigen::Vector4d lambda;
  for (int i = 0; i < 4; ++i) lambda[i] = X(i, 0) - 0.2;
  double reference = 0.0;
  for (const Corners& sub : kerf::clip_tet(X, lambda).above) {
    Eigen::Vector4d mu;
    for (int i = 0; i < 4; ++i) mu[i] = sub(i, 2) - 0.3;
    reference += kerf::clip_tet(sub, mu).V_b;
  }
  const int corner_piece = pieces.corner_pieces[1].front(); // corner (1, 0, 0) is in the cut-out piece
  CHECK(pieces.pieces[corner_piece].volume == kerf_test::relative(reference, 1e-13));
}

TEST_CASE("convex cells: the unit tet's cell and its fan of tetrahedra") {
  const kerf::ConvexCell cell = kerf::tet_cell(unit_tet());
  CHECK(kerf::convex_cell_volume(cell) == kerf_test::relative(1.0 / 6.0));
  double sum = 0.0;
  for (const Corners& T : kerf::convex_cell_tetrahedra(cell)) {
    CHECK(kerf::signed_tet_volume(T) > 0.0);
    sum += kerf::signed_tet_volume(T);
  }
  CHECK(sum == kerf_test::relative(1.0 / 6.0));
}

TEST_CASE("random surfaces on a coarse grid, full of exact coincidences, always give closed pieces that fill the tet") {
  // The random fans of random_fan.hpp: cuts through corners, along edges and in faces are
  // common, and some tets are cut completely, some partially. Whatever happens, the pieces must
  // close, have positive volume, and add up to the tet.
  std::mt19937 random(2024);
  int cases = 0, split = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const std::optional<random_fan::Case> fan = random_fan::next(random);
    if (!fan) continue;
    const auto& [X, centre, rim, surface] = *fan;
    const kerf::TetPieces pieces = kerf::split_tet_by_triangles(X, surface);
    ++cases;
    split += pieces.num_pieces() > 1 ? 1 : 0;
    CAPTURE(trial);
    require_closed_pieces(pieces);
    // Every corner lies in at least one piece.
    for (int k = 0; k < 4; ++k) CHECK(!pieces.corner_pieces[static_cast<std::size_t>(k)].empty());
  }
  CHECK(cases > 1000);
  CHECK(split > 100);
}

namespace {

// An icosphere of radius r about c: the icosahedron subdivided `levels` times, vertices pushed
// onto the sphere, triangles facing out.
std::vector<CutTriangle> icosphere(const Eigen::Vector3d& c, double r, int levels) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Eigen::Vector3d> v{{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                 {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<int, 3>> f{{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                    {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                                    {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for (Eigen::Vector3d& x : v) x.normalize();
  for (int level = 0; level < levels; ++level) {
    std::vector<std::array<int, 3>> finer;
    const auto middle = [&](int a, int b) {
      v.push_back((v[static_cast<std::size_t>(a)] + v[static_cast<std::size_t>(b)]).normalized());
      return static_cast<int>(v.size()) - 1;
    };
    for (const auto& [a, b, d] : f) {
      const int ab = middle(a, b), bd = middle(b, d), da = middle(d, a);
      finer.push_back({a, ab, da});
      finer.push_back({b, bd, ab});
      finer.push_back({d, da, bd});
      finer.push_back({ab, bd, da});
    }
    f = finer;
  }
  std::vector<CutTriangle> triangles;
  for (std::size_t k = 0; k < f.size(); ++k) {
    const auto& [a, b, d] = f[k];
    triangles.push_back(triangle(c + r * v[static_cast<std::size_t>(a)], c + r * v[static_cast<std::size_t>(b)],
                                 c + r * v[static_cast<std::size_t>(d)], static_cast<int>(k)));
  }
  return triangles;
}

} // namespace

TEST_CASE("a closed polyhedral ball cuts out of the tet exactly its intersection with the ball") {
  // Koschier's spherical cut: the ball of radius 0.5 at the corner (0, 0, 0) of the unit tet,
  // as an icosphere (1280 triangles; turned so that no vertex sits on the tet's faces). The
  // independent reference: the tet clipped by every triangle's plane in turn, keeping the
  // inside, with chapter 3's clip_tet (a convex polyhedron is the intersection of its faces'
  // half-spaces).
  const Corners X = unit_tet();
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  std::vector<CutTriangle> ball = icosphere(Eigen::Vector3d::Zero(), 0.5, 3);
  for (CutTriangle& t : ball)
    for (Eigen::Vector3d& x : t.corners) x = turn * x;
  const kerf::TetPieces pieces = kerf::split_tet_by_triangles(X, ball);
  REQUIRE(pieces.num_pieces() == 2);
  CHECK(pieces.state == kerf::SurfaceCutState::completely_cut);
  require_closed_pieces(pieces);
  std::vector<Corners> inside{X};
  for (const CutTriangle& t : ball) {
    const Eigen::Vector3d n = (t.corners[1] - t.corners[0]).cross(t.corners[2] - t.corners[0]).normalized();
    std::vector<Corners> kept;
    for (const Corners& sub : inside) {
      Eigen::Vector4d lambda;
      for (int i = 0; i < 4; ++i) lambda[i] = n.dot(sub.row(i).transpose() - t.corners[0]);
      const kerf::ClippedTet clipped = kerf::clip_tet(sub, lambda);
      kept.insert(kept.end(), clipped.below.begin(), clipped.below.end());
    }
    inside = kept;
  }
  double reference = 0.0;
  for (const Corners& sub : inside) reference += std::abs(kerf::signed_tet_volume(sub));
  const int ball_piece = pieces.corner_pieces[0].front();
  CHECK(pieces.pieces[static_cast<std::size_t>(ball_piece)].volume == kerf_test::relative(reference, 1e-12));
  // And the polyhedral ball is close to the round one: pi r^3 / 6 within the tessellation's error.
  CHECK(reference == kerf_test::relative(M_PI * 0.125 / 6.0, 0.01));
}

TEST_CASE("a fine icosphere (20480 triangles) still cuts out its ball: the case that once leaked") {
  // Level 5: 4451 triangles reach the tet, their edge planes nearly parallel near the sphere's
  // vertices. The reference: the tet as one convex cell split by every triangle's plane in turn,
  // keeping the inside (split_cell alone, without the edge planes, the coverage and the gluing
  // that split_tet_by_triangles adds), to 1e-12.
  const Corners X = unit_tet();
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  std::vector<CutTriangle> ball = icosphere(Eigen::Vector3d::Zero(), 0.5, 5);
  for (CutTriangle& t : ball)
    for (Eigen::Vector3d& x : t.corners) x = turn * x;
  const kerf::TetPieces pieces = kerf::split_tet_by_triangles(X, ball);
  REQUIRE(pieces.num_pieces() == 2);
  require_closed_pieces(pieces);
  std::vector<kerf::ConvexCell> cells{kerf::tet_cell(X)};
  int inside = 0;
  for (const CutTriangle& t : ball) {
    const Eigen::Vector3d n = (t.corners[1] - t.corners[0]).cross(t.corners[2] - t.corners[0]).normalized();
    const kerf::Plane plane{n, n.dot(t.corners[0])};
    const auto side = [&plane](const Eigen::Vector3d& x) {
      const double v = plane.evaluate(x);
      return std::abs(v) <= 1e-14 ? 0.0 : v;
    };
    const int below = kerf::split_cell(cells, inside, side, plane, {kerf::FaceOrigin::Kind::cut_plane, t.triangle});
    if (below >= 0) inside = below;
  }
  const int ball_piece = pieces.corner_pieces[0].front();
  CHECK(pieces.pieces[static_cast<std::size_t>(ball_piece)].volume ==
        kerf_test::relative(kerf::convex_cell_volume(cells[static_cast<std::size_t>(inside)]), 1e-12));
}
