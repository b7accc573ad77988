// The two halves of the semi-progressive crossing test (semi_progressive_cut.hpp), in a file of
// their own so that chapter 7's assignment can hand them out; SemiProgressiveCut keeps the
// bookkeeping (the edges, the tree, which edges and tets are crossed) in semi_progressive_cut.cpp.
#include "kerf/cut/semi_progressive_cut.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>

namespace kerf {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

Kernel::Point_3 to_cgal(const Eigen::Vector3d& x) { return {x[0], x[1], x[2]}; }

} // namespace

EdgeTriangleContact edge_triangle_contact(const SweptTriangle& triangle, const Eigen::Vector3d& x_a, const Eigen::Vector3d& x_b) {
  const Kernel::Triangle_3 t(to_cgal(triangle[0]), to_cgal(triangle[1]), to_cgal(triangle[2]));
  const std::array<Kernel::Point_3, 2> ends{to_cgal(x_a), to_cgal(x_b)};
  EdgeTriangleContact contact;
  std::array<CGAL::Orientation, 2> side{};
  for (int k = 0; k < 2; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    side[kk] = CGAL::orientation(t[0], t[1], t[2], ends[kk]);
    // An end in the closed triangle is on the sheet (the edge through it is not crossed there).
    contact.end_on_sheet[kk] = side[kk] == CGAL::COPLANAR && t.has_on(ends[kk]);
  }
  // Crossed: the ends strictly on opposite sides of the plane, and the point where the segment
  // meets the plane in the closed triangle, i.e. the segment's line passes the triangle's three
  // edges all on one side or on them: no two of the three orientations strictly opposite.
  if (side[0] == CGAL::COPLANAR || side[1] == CGAL::COPLANAR || side[0] == side[1]) return contact;
  std::array<int, 3> around{};
  for (int k = 0; k < 3; ++k) around[static_cast<std::size_t>(k)] = CGAL::orientation(ends[0], ends[1], t[k], t[(k + 1) % 3]);
  const bool any_positive = std::count(around.begin(), around.end(), 1) > 0, any_negative = std::count(around.begin(), around.end(), -1) > 0;
  if (any_positive && any_negative) return contact;
  // The signed heights of the ends over the plane (inexact; the side was decided exactly).
  const Eigen::Vector3d normal = (triangle[1] - triangle[0]).cross(triangle[2] - triangle[0]);
  const double ha = normal.dot(x_a - triangle[0]), hb = normal.dot(x_b - triangle[0]);
  contact.crossed = true;
  contact.parameter = std::clamp(ha / (ha - hb), 0.0, 1.0);
  return contact;
}

bool tet_corners_separated(const std::array<bool, 6>& edge_crossed, const std::array<bool, 4>& corner_on_sheet) {
  // Union-find over the (at most 4) corners off the sheet.
  std::array<int, 4> group{0, 1, 2, 3};
  const auto root = [&](int a) {
    while (group[static_cast<std::size_t>(a)] != a) a = group[static_cast<std::size_t>(a)];
    return a;
  };
  for (int j = 0; j < 6; ++j) {
    const int a = tet_edge_corners[j][0], b = tet_edge_corners[j][1];
    if (corner_on_sheet[static_cast<std::size_t>(a)] || corner_on_sheet[static_cast<std::size_t>(b)]) continue;
    if (edge_crossed[static_cast<std::size_t>(j)]) continue;
    group[static_cast<std::size_t>(root(a))] = root(b);
  }
  int groups = 0;
  for (int a = 0; a < 4; ++a)
    if (!corner_on_sheet[static_cast<std::size_t>(a)] && root(a) == a) ++groups;
  return groups >= 2;
}

} // namespace kerf
