#include "kerf/cut/cut_surfaces.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Tetrahedron_3.h>

#include <algorithm>
#include <utility>

namespace kerf {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Triangle = Kernel::Triangle_3;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, std::vector<Triangle>::const_iterator>;
using AabbTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

Kernel::Point_3 to_cgal(const Eigen::Vector3d& x) { return {x[0], x[1], x[2]}; }

} // namespace

struct CutSurfaces::Tree {
  std::vector<Triangle> triangles;                 // all surfaces' triangles, one after the other
  std::vector<std::pair<int, int>> owner;          // (surface, triangle) of each
  AabbTree tree;
};

TriangleSurface rectangle_surface(const RectangleCut& rectangle) {
  TriangleSurface surface;
  const Eigen::Vector3d& o = rectangle.origin();
  surface.vertices.resize(4, 3);
  surface.vertices.row(0) = o.transpose();
  surface.vertices.row(1) = (o + rectangle.edge1()).transpose();
  surface.vertices.row(2) = (o + rectangle.edge1() + rectangle.edge2()).transpose();
  surface.vertices.row(3) = (o + rectangle.edge2()).transpose();
  surface.triangles.resize(2, 3);
  surface.triangles << 0, 1, 2, 0, 2, 3; // both with normal edge1 x edge2
  return surface;
}

CutSurfaces::CutSurfaces(std::vector<TriangleSurface> surfaces)
    : surfaces_(std::move(surfaces)), tree_(std::make_unique<Tree>()) {
  for (std::size_t s = 0; s < surfaces_.size(); ++s) {
    const TriangleSurface& surface = surfaces_[s];
    for (Eigen::Index f = 0; f < surface.num_triangles(); ++f) {
      const auto corner = [&](int k) { return to_cgal(surface.vertices.row(surface.triangles(f, k)).transpose()); };
      tree_->triangles.emplace_back(corner(0), corner(1), corner(2));
      tree_->owner.emplace_back(static_cast<int>(s), static_cast<int>(f));
    }
  }
  // The tree refers to the triangles through iterators: build it once they no longer move.
  tree_->tree.insert(tree_->triangles.cbegin(), tree_->triangles.cend());
  tree_->tree.build();
}

CutSurfaces::~CutSurfaces() = default;
CutSurfaces::CutSurfaces(CutSurfaces&&) noexcept = default;
CutSurfaces& CutSurfaces::operator=(CutSurfaces&&) noexcept = default;

Eigen::Index CutSurfaces::num_triangles() const { return static_cast<Eigen::Index>(tree_->triangles.size()); }

std::vector<CutTriangle> CutSurfaces::triangles_near_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& q) const {
  std::vector<CutTriangle> found;
  if (tree_->triangles.empty()) return found;
  const CGAL::Bbox_3 box(std::min(p[0], q[0]), std::min(p[1], q[1]), std::min(p[2], q[2]), std::max(p[0], q[0]),
                         std::max(p[1], q[1]), std::max(p[2], q[2]));
  std::vector<Primitive::Id> candidates;
  tree_->tree.all_intersected_primitives(box, std::back_inserter(candidates));
  std::sort(candidates.begin(), candidates.end());
  for (const Primitive::Id& id : candidates) found.push_back(cut_triangle(static_cast<std::size_t>(id - tree_->triangles.cbegin())));
  return found;
}

CutTriangle CutSurfaces::cut_triangle(std::size_t k) const {
  const auto [s, f] = tree_->owner[k];
  const TriangleSurface& surface = surfaces_[static_cast<std::size_t>(s)];
  CutTriangle t;
  for (int c = 0; c < 3; ++c) t.corners[static_cast<std::size_t>(c)] = surface.vertices.row(surface.triangles(f, c)).transpose();
  t.surface = s;
  t.triangle = f;
  return t;
}

std::vector<CutTriangle> CutSurfaces::triangles_meeting_tet(const Eigen::Matrix<double, 4, 3>& X) const {
  std::vector<CutTriangle> found;
  if (tree_->triangles.empty()) return found;
  const Kernel::Tetrahedron_3 tet(to_cgal(X.row(0).transpose()), to_cgal(X.row(1).transpose()),
                                  to_cgal(X.row(2).transpose()), to_cgal(X.row(3).transpose()));
  // First the boxes (cheap), then the exact test on the few candidates.
  std::vector<Primitive::Id> candidates;
  tree_->tree.all_intersected_primitives(tet.bbox(), std::back_inserter(candidates));
  std::sort(candidates.begin(), candidates.end());
  for (const Primitive::Id& id : candidates) {
    if (!CGAL::do_intersect(tet, *id)) continue;
    found.push_back(cut_triangle(static_cast<std::size_t>(id - tree_->triangles.cbegin())));
  }
  return found;
}

} // namespace kerf
