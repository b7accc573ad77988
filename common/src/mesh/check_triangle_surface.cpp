#include "kerf/mesh/check_triangle_surface.hpp"

#include "kerf/app/input_error.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <numeric>
#include <queue>
#include <sstream>
#include <tuple>
#include <utility>
#include <vector>

namespace kerf {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

/// "(0.5, 1, 0)", for messages.
std::string position_text(const Eigen::MatrixX3d& vertices, Eigen::Index v) {
  std::ostringstream text;
  text.precision(17);
  text << "(" << vertices(v, 0) << ", " << vertices(v, 1) << ", " << vertices(v, 2) << ")";
  return text.str();
}

/// Step 1: triangles exist, indices are in range, coordinates are finite.
void check_indices_and_coordinates(const TriangleSurface& surface, const std::string& file) {
  if (surface.num_triangles() == 0) throw InputError(file, "triangles", "the surface has no triangles");
  for (Eigen::Index t = 0; t < surface.num_triangles(); ++t)
    for (int a = 0; a < 3; ++a)
      if (surface.triangles(t, a) < 0 || surface.triangles(t, a) >= surface.num_vertices())
        throw InputError(file, "triangle " + std::to_string(t),
                         "vertex index " + std::to_string(surface.triangles(t, a)) + " is outside [0, " +
                             std::to_string(surface.num_vertices()) + ")");
  for (Eigen::Index v = 0; v < surface.num_vertices(); ++v)
    if (!surface.vertices.row(v).allFinite())
      throw InputError(file, "vertex " + std::to_string(v), "coordinate is not a finite number");
}

/// Step 2: merges vertices at exactly equal positions and drops the unused ones. The vertices
/// are sorted by position, so that equal ones become neighbours (n log n, no hashing of doubles,
/// and -0.0 == 0.0 as the comparison says); each group maps to the first vertex of the file in
/// it, and the kept vertices are renumbered in their file order.
void weld_vertices(TriangleSurface& surface, SurfaceCheck& check) {
  const Eigen::Index num_vertices = surface.num_vertices();
  std::vector<Eigen::Index> by_position(static_cast<std::size_t>(num_vertices));
  std::iota(by_position.begin(), by_position.end(), Eigen::Index{0});
  const auto position = [&](Eigen::Index v) {
    return std::tuple(surface.vertices(v, 0), surface.vertices(v, 1), surface.vertices(v, 2));
  };
  std::stable_sort(by_position.begin(), by_position.end(),
                   [&](Eigen::Index a, Eigen::Index b) { return position(a) < position(b); });
  std::vector<Eigen::Index> representative(static_cast<std::size_t>(num_vertices));
  for (std::size_t i = 0; i < by_position.size(); ++i) {
    const bool same_as_previous = i > 0 && position(by_position[i]) == position(by_position[i - 1]);
    // The sort is stable, so the first of a group is the one that comes first in the file.
    representative[static_cast<std::size_t>(by_position[i])] =
        same_as_previous ? representative[static_cast<std::size_t>(by_position[i - 1])] : by_position[i];
  }

  std::vector<bool> used(static_cast<std::size_t>(num_vertices), false);
  for (Eigen::Index t = 0; t < surface.num_triangles(); ++t)
    for (int a = 0; a < 3; ++a) {
      const std::size_t v = static_cast<std::size_t>(surface.triangles(t, a));
      used[static_cast<std::size_t>(representative[v])] = true;
    }
  std::vector<int> new_index(static_cast<std::size_t>(num_vertices), -1);
  int kept = 0;
  for (Eigen::Index v = 0; v < num_vertices; ++v) {
    const auto i = static_cast<std::size_t>(v);
    if (representative[i] != v) ++check.merged_vertices;
    else if (!used[i]) ++check.unused_vertices;
    else new_index[i] = kept++;
  }
  if (kept == num_vertices) return;

  Eigen::MatrixX3d welded(kept, 3);
  for (Eigen::Index v = 0; v < num_vertices; ++v)
    if (const int n = new_index[static_cast<std::size_t>(v)]; n >= 0) welded.row(n) = surface.vertices.row(v);
  for (Eigen::Index t = 0; t < surface.num_triangles(); ++t)
    for (int a = 0; a < 3; ++a) {
      const std::size_t v = static_cast<std::size_t>(surface.triangles(t, a));
      surface.triangles(t, a) = new_index[static_cast<std::size_t>(representative[v])];
    }
  surface.vertices = std::move(welded);
}

/// Step 3: refuses a triangle with a repeated corner or three collinear corners (exactly).
void refuse_degenerate_triangles(const TriangleSurface& surface, const std::string& file) {
  for (Eigen::Index t = 0; t < surface.num_triangles(); ++t) {
    const std::string field = "triangle " + std::to_string(t);
    for (int a = 0; a < 3; ++a) {
      const int b = (a + 1) % 3;
      if (surface.triangles(t, a) == surface.triangles(t, b))
        throw InputError(file, field,
                         "degenerate: corners " + std::to_string(std::min(a, b)) + " and " +
                             std::to_string(std::max(a, b)) + " are at the same position " +
                             position_text(surface.vertices, surface.triangles(t, a)));
    }
    std::array<Kernel::Point_3, 3> corners;
    for (int a = 0; a < 3; ++a) {
      const Eigen::Index v = surface.triangles(t, a);
      corners[static_cast<std::size_t>(a)] =
          Kernel::Point_3(surface.vertices(v, 0), surface.vertices(v, 1), surface.vertices(v, 2));
    }
    if (CGAL::collinear(corners[0], corners[1], corners[2]))
      throw InputError(file, field, "degenerate: its three corners are collinear (zero area, no normal)");
  }
}

/// The three corners of triangle t, sorted: the same for every orientation and order.
std::array<int, 3> corner_set(const TriangleSurface& surface, Eigen::Index t) {
  std::array<int, 3> set{surface.triangles(t, 0), surface.triangles(t, 1), surface.triangles(t, 2)};
  std::sort(set.begin(), set.end());
  return set;
}

/// Step 4: refuses two triangles with the same three corners.
void refuse_duplicate_triangles(const TriangleSurface& surface, const std::string& file) {
  std::vector<std::pair<std::array<int, 3>, Eigen::Index>> sets;
  sets.reserve(static_cast<std::size_t>(surface.num_triangles()));
  for (Eigen::Index t = 0; t < surface.num_triangles(); ++t) sets.emplace_back(corner_set(surface, t), t);
  std::sort(sets.begin(), sets.end());
  for (std::size_t i = 1; i < sets.size(); ++i)
    if (sets[i].first == sets[i - 1].first)
      throw InputError(file, "triangle " + std::to_string(sets[i].second),
                       "has the same three corners as triangle " + std::to_string(sets[i - 1].second));
}

/// One side of a triangle: the edge from corner `from` to the next corner, as the triangle
/// traverses it, keyed by its two vertices in increasing order.
struct HalfEdge {
  int low, high;      ///< the edge's vertices, low < high
  Eigen::Index tri;   ///< the triangle
  int side;           ///< the corner the side starts at: the side is corner side -> corner side+1
};

/// The sides of every triangle, sorted so that those of one edge are neighbours.
std::vector<HalfEdge> sorted_half_edges(const TriangleSurface& surface) {
  std::vector<HalfEdge> sides;
  sides.reserve(3 * static_cast<std::size_t>(surface.num_triangles()));
  for (Eigen::Index t = 0; t < surface.num_triangles(); ++t)
    for (int a = 0; a < 3; ++a) {
      const int from = surface.triangles(t, a), to = surface.triangles(t, (a + 1) % 3);
      sides.push_back({std::min(from, to), std::max(from, to), t, a});
    }
  std::sort(sides.begin(), sides.end(), [](const HalfEdge& x, const HalfEdge& y) {
    return std::tie(x.low, x.high, x.tri) < std::tie(y.low, y.high, y.tri);
  });
  return sides;
}

/// True if the triangle of `h` traverses the side from the edge's lower vertex to its higher
/// one, once it is flipped (`flipped`) or as it stands.
bool runs_upward(const TriangleSurface& surface, const HalfEdge& h, bool flipped) {
  const bool upward = surface.triangles(h.tri, h.side) == h.low;
  return upward != flipped;
}

} // namespace

SurfaceCheck check_triangle_surface(TriangleSurface& surface, const std::string& file) {
  SurfaceCheck check;
  check_indices_and_coordinates(surface, file);
  weld_vertices(surface, check);
  refuse_degenerate_triangles(surface, file);
  refuse_duplicate_triangles(surface, file);

  // Step 5: edges with one triangle are the boundary, with two they join the two, with more
  // they are refused. across[t][a] is the other triangle's side at side a of t (null on the boundary).
  const std::vector<HalfEdge> sides = sorted_half_edges(surface);
  std::vector<std::array<const HalfEdge*, 3>> across(static_cast<std::size_t>(surface.num_triangles()),
                                                     {nullptr, nullptr, nullptr});
  for (std::size_t first = 0; first < sides.size();) {
    std::size_t last = first + 1;
    while (last < sides.size() && sides[last].low == sides[first].low && sides[last].high == sides[first].high) ++last;
    if (last - first > 2)
      throw InputError(file, "edge (" + std::to_string(sides[first].low) + ", " + std::to_string(sides[first].high) + ")",
                       "non-manifold: shared by " + std::to_string(last - first) + " triangles (" +
                           std::to_string(sides[first].tri) + ", " + std::to_string(sides[first + 1].tri) + ", " +
                           std::to_string(sides[first + 2].tri) + (last - first > 3 ? ", ..." : "") +
                           ") at the edge from " + position_text(surface.vertices, sides[first].low) + " to " +
                           position_text(surface.vertices, sides[first].high) +
                           "; a cut surface has at most two triangles at an edge");
    if (last - first == 1) {
      ++check.boundary_edges;
    } else {
      across[static_cast<std::size_t>(sides[first].tri)][static_cast<std::size_t>(sides[first].side)] = &sides[first + 1];
      across[static_cast<std::size_t>(sides[first + 1].tri)][static_cast<std::size_t>(sides[first + 1].side)] = &sides[first];
    }
    first = last;
  }

  // Step 6: breadth-first over each component from its lowest triangle, which keeps its
  // orientation. Two consistently oriented neighbours run their shared edge in opposite directions.
  enum class State { unseen, kept, flipped };
  std::vector<State> state(static_cast<std::size_t>(surface.num_triangles()), State::unseen);
  std::queue<Eigen::Index> queue;
  for (Eigen::Index seed = 0; seed < surface.num_triangles(); ++seed) {
    if (state[static_cast<std::size_t>(seed)] != State::unseen) continue;
    ++check.components;
    state[static_cast<std::size_t>(seed)] = State::kept;
    queue.push(seed);
    while (!queue.empty()) {
      const Eigen::Index t = queue.front();
      queue.pop();
      const bool t_flipped = state[static_cast<std::size_t>(t)] == State::flipped;
      for (int a = 0; a < 3; ++a) {
        const HalfEdge* other = across[static_cast<std::size_t>(t)][static_cast<std::size_t>(a)];
        if (!other) continue;
        const bool t_upward = (surface.triangles(t, a) < surface.triangles(t, (a + 1) % 3)) != t_flipped;
        State& other_state = state[static_cast<std::size_t>(other->tri)];
        if (other_state == State::unseen) {
          other_state = runs_upward(surface, *other, false) == t_upward ? State::flipped : State::kept;
          queue.push(other->tri);
        } else if (runs_upward(surface, *other, other_state == State::flipped) == t_upward) {
          throw InputError(file, "triangle " + std::to_string(other->tri),
                           "the surface is not orientable (like a Moebius strip): walking from triangle " +
                               std::to_string(seed) + " over shared edges reaches it with both orientations, "
                               "so the cut would have one side only");
        }
      }
    }
  }
  for (Eigen::Index t = 0; t < surface.num_triangles(); ++t)
    if (state[static_cast<std::size_t>(t)] == State::flipped) {
      std::swap(surface.triangles(t, 1), surface.triangles(t, 2));
      ++check.flipped_triangles;
    }
  return check;
}

} // namespace kerf
