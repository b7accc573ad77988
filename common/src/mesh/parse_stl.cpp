#include "mesh/surface_parsers.hpp"

#include "kerf/app/input_error.hpp"
#include "mesh/text_lines.hpp"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <limits>

namespace kerf {
namespace {

constexpr std::size_t binary_header_bytes = 80 + 4; ///< the free header, then the triangle count
constexpr std::size_t binary_triangle_bytes = 50;   ///< normal, 3 vertices (12 floats), attribute

/// The little-endian unsigned 32-bit integer at `at`.
std::uint32_t little_endian_uint32(std::string_view bytes, std::size_t at) {
  std::uint32_t value = 0;
  for (int b = 3; b >= 0; --b) value = (value << 8) | static_cast<unsigned char>(bytes[at + static_cast<std::size_t>(b)]);
  return value;
}

/// The little-endian IEEE single at `at`.
float little_endian_float(std::string_view bytes, std::size_t at) {
  const std::uint32_t bits = little_endian_uint32(bytes, at);
  float value = 0.0f;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

/// Binary STL: the size has already been checked against the count.
TriangleSurface parse_binary_stl(std::string_view bytes, std::size_t count) {
  std::vector<std::array<double, 3>> vertices;
  std::vector<std::array<int, 3>> triangles;
  vertices.reserve(3 * count);
  triangles.reserve(count);
  for (std::size_t t = 0; t < count; ++t) {
    const std::size_t at = binary_header_bytes + t * binary_triangle_bytes + 12; // after the normal
    for (std::size_t corner = 0; corner < 3; ++corner) {
      std::array<double, 3> x{};
      for (std::size_t c = 0; c < 3; ++c) x[c] = little_endian_float(bytes, at + 12 * corner + 4 * c);
      vertices.push_back(x);
    }
    const int first = static_cast<int>(3 * t);
    triangles.push_back({first, first + 1, first + 2});
  }
  return surface_from_lists(vertices, triangles);
}

/// A word in lower case: ASCII STL keywords are written either way.
std::string lower(std::string_view word) {
  std::string result(word);
  std::transform(result.begin(), result.end(), result.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return result;
}

/// ASCII STL, statement by statement: `solid name`, then facets of the form
/// `facet normal nx ny nz` / `outer loop` / three `vertex x y z` / `endloop` / `endfacet`,
/// then `endsolid name`; several solids may follow each other.
TriangleSurface parse_ascii_stl(std::string_view text, const std::string& file) {
  TextLines lines(text, file, false);
  std::vector<std::array<double, 3>> vertices;
  std::vector<std::array<int, 3>> triangles;
  // Each statement must be the expected one, with `words` words in all.
  const auto expect = [&](const char* keyword, const char* second, std::size_t words, const std::string& inside) {
    if (!lines.next_line()) throw lines.end_error(inside);
    const std::vector<std::string_view>& w = lines.words();
    const bool matches = lower(w[0]) == keyword && (!second || (w.size() > 1 && lower(w[1]) == second));
    if (!matches || w.size() != words)
      throw lines.error("expected '" + std::string(keyword) + (second ? std::string(" ") + second : "") +
                        "' in " + inside + ", found " + TextLines::quote(w[0]) +
                        (matches ? " with " + std::to_string(w.size()) + " words, not " + std::to_string(words) : ""));
  };
  if (!lines.next_line()) throw lines.end_error("the 'solid' line");
  if (lower(lines.words()[0]) != "solid")
    throw lines.error("an ASCII STL file starts with 'solid'");
  bool in_solid = true;
  while (lines.next_line()) {
    const std::string keyword = lower(lines.words()[0]);
    if (!in_solid) {
      if (keyword != "solid") throw lines.error("expected 'solid' or the end of the file, found " + TextLines::quote(keyword));
      in_solid = true;
      continue;
    }
    if (keyword == "endsolid") {
      in_solid = false;
      continue;
    }
    const std::string facet = "facet " + std::to_string(triangles.size());
    if (keyword != "facet" || lines.words().size() != 5 || lower(lines.words()[1]) != "normal")
      throw lines.error("expected 'facet normal nx ny nz' or 'endsolid', found " + TextLines::quote(keyword));
    for (std::size_t c = 2; c < 5; ++c) lines.real(c, "the normal of " + facet);
    expect("outer", "loop", 2, facet);
    const int first = static_cast<int>(vertices.size());
    for (int corner = 0; corner < 3; ++corner) {
      const std::string what = "vertex " + std::to_string(corner) + " of " + facet;
      expect("vertex", nullptr, 4, facet);
      vertices.push_back({lines.real(1, "x of " + what), lines.real(2, "y of " + what), lines.real(3, "z of " + what)});
    }
    expect("endloop", nullptr, 1, facet + " (a facet has three vertices)");
    expect("endfacet", nullptr, 1, facet);
    triangles.push_back({first, first + 1, first + 2});
    if (vertices.size() > static_cast<std::size_t>(std::numeric_limits<int>::max() - 3))
      throw lines.error("more vertices than Kerf's 32-bit indices can number");
  }
  if (in_solid) throw lines.end_error("the solid, which has no 'endsolid'");
  return surface_from_lists(vertices, triangles);
}

/// True if the text starts with "solid" after optional whitespace, as ASCII STL does.
bool starts_like_ascii(std::string_view bytes) {
  const std::size_t first = bytes.find_first_not_of(" \t\r\n");
  return first != std::string_view::npos && lower(bytes.substr(first, 5)) == "solid";
}

} // namespace

TriangleSurface parse_stl(std::string_view bytes, const std::string& file) {
  if (bytes.size() >= binary_header_bytes) {
    const std::uint64_t count = little_endian_uint32(bytes, 80);
    const std::uint64_t expected = binary_header_bytes + binary_triangle_bytes * count;
    if (expected == bytes.size()) {
      if (3 * count > static_cast<std::uint64_t>(std::numeric_limits<int>::max()))
        throw InputError(file, "triangle count", "more vertices than Kerf's 32-bit indices can number");
      return parse_binary_stl(bytes, static_cast<std::size_t>(count));
    }
    // Text never holds a zero byte; a binary file whose header starts with "solid" often does.
    if (!starts_like_ascii(bytes) || bytes.find('\0') != std::string_view::npos)
      throw InputError(file, "triangle count",
                       "a binary STL file of " + std::to_string(count) + " triangles has 84 + 50 * " +
                           std::to_string(count) + " = " + std::to_string(expected) + " bytes, this one has " +
                           std::to_string(bytes.size()) + " (the file is truncated or the count is wrong)");
  } else if (!starts_like_ascii(bytes)) {
    throw InputError(file, "header", "neither ASCII STL (which starts with 'solid') nor binary STL (at least 84 bytes)");
  }
  return parse_ascii_stl(bytes, file);
}

} // namespace kerf
