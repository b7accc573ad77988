#include "kerf/cut/swept_quad.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

namespace kerf {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

Kernel::Point_3 to_cgal(const Eigen::Vector3d& x) { return {x[0], x[1], x[2]}; }

bool has_area(const SweptTriangle& t) { return !CGAL::collinear(to_cgal(t[0]), to_cgal(t[1]), to_cgal(t[2])); }

} // namespace

std::vector<SweptTriangle> swept_quad(const BladeEdge& from, const BladeEdge& to) {
  std::vector<SweptTriangle> sheet;
  for (const SweptTriangle& t : {SweptTriangle{from.start, from.end, to.end}, SweptTriangle{from.start, to.end, to.start}})
    if (has_area(t)) sheet.push_back(t);
  return sheet;
}

} // namespace kerf
