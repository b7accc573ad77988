#include "mesh/surface_parsers.hpp"

#include "mesh/text_lines.hpp"

#include <array>
#include <limits>
#include <vector>

namespace kerf {
namespace {

/// The vertex an OBJ face index refers to, 0-based: `i` counts from 1, `-i` back from the last
/// vertex read so far. Only the part before the first '/' is the vertex (`i/t/n`).
int obj_vertex_index(const TextLines& lines, std::size_t word, std::size_t num_vertices) {
  const std::string_view whole = lines.words()[word];
  const std::string_view vertex = whole.substr(0, whole.find('/'));
  long long index = 0;
  const auto [end, status] = std::from_chars(vertex.data(), vertex.data() + vertex.size(), index);
  if (vertex.empty() || status != std::errc() || end != vertex.data() + vertex.size())
    throw lines.error("expected a vertex index (i, i/t, i//n or i/t/n) in corner " + std::to_string(word) +
                      " of the face, found " + TextLines::quote(whole));
  const auto count = static_cast<long long>(num_vertices);
  const long long zero_based = index > 0 ? index - 1 : count + index;
  if (index == 0 || zero_based < 0 || zero_based >= count)
    throw lines.error("vertex index " + std::to_string(index) + " is outside [1, " + std::to_string(count) +
                      "] and [-" + std::to_string(count) + ", -1] (OBJ counts from 1, or back from the "
                      "last vertex read, and a face may use only the vertices above it)");
  return static_cast<int>(zero_based);
}

/// True for the OBJ statements that carry nothing a cut surface needs.
bool is_skipped_statement(std::string_view keyword) {
  for (const std::string_view skipped : {"vt", "vn", "vp", "g", "o", "s", "usemtl", "mtllib", "l", "p"})
    if (keyword == skipped) return true;
  return false;
}

} // namespace

TriangleSurface parse_obj(std::string_view text, const std::string& file) {
  TextLines lines(text, file, true);
  std::vector<std::array<double, 3>> vertices;
  std::vector<std::array<int, 3>> triangles;
  while (lines.next_line()) {
    const std::string_view keyword = lines.words()[0];
    if (keyword == "v") {
      // x y z and an optional weight w or colour r g b, which we do not use.
      const std::size_t n = lines.words().size();
      if (n != 4 && n != 5 && n != 7)
        throw lines.error("a vertex has 3 coordinates (and an optional weight or colour), found " +
                          std::to_string(n - 1) + " numbers");
      const std::string what = "vertex " + std::to_string(vertices.size() + 1);
      for (std::size_t i = 4; i < n; ++i) lines.real(i, "the weight or colour of " + what);
      vertices.push_back({lines.real(1, "x of " + what), lines.real(2, "y of " + what), lines.real(3, "z of " + what)});
      if (vertices.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
        throw lines.error("more vertices than Kerf's 32-bit indices can number");
    } else if (keyword == "f") {
      const std::size_t corners = lines.words().size() - 1;
      if (corners < 3) throw lines.error("a face needs at least 3 vertices, found " + std::to_string(corners));
      const int first = obj_vertex_index(lines, 1, vertices.size());
      int previous = obj_vertex_index(lines, 2, vertices.size());
      // A polygon becomes a fan around its first corner, which keeps its orientation.
      for (std::size_t c = 3; c <= corners; ++c) {
        const int next = obj_vertex_index(lines, c, vertices.size());
        triangles.push_back({first, previous, next});
        previous = next;
      }
    } else if (!is_skipped_statement(keyword)) {
      throw lines.error("unknown statement " + TextLines::quote(keyword) +
                        " (Kerf reads v and f, and skips vt, vn, vp, g, o, s, usemtl, mtllib, l and p)");
    }
  }

  return surface_from_lists(vertices, triangles);
}

} // namespace kerf
