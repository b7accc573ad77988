#include "mesh/surface_parsers.hpp"

#include "mesh/text_lines.hpp"

#include <limits>

namespace kerf {
namespace {

/// Reads a count of the OFF header, which must not be negative and must fit in the file: each
/// of its entries takes a line of at least `bytes_per_entry` bytes ("0 0 0\n" for a vertex,
/// "3 0 1 2\n" for a face). Checking this before anything is allocated keeps a corrupt count
/// from asking for gigabytes the file cannot hold.
std::size_t off_count(const TextLines& lines, std::size_t word, const std::string& what,
                      std::size_t bytes_per_entry, std::size_t file_size) {
  const long long count = lines.integer(word, "the number of " + what);
  if (count < 0) throw lines.error("the number of " + what + " must not be negative, found " + std::to_string(count));
  if (static_cast<unsigned long long>(count) > (file_size + 1) / bytes_per_entry)
    throw lines.error("the number of " + what + ", " + std::to_string(count) + ", is more than the " +
                      std::to_string(file_size) + " bytes of the file can hold (the file is truncated or "
                      "the count is wrong)");
  return static_cast<std::size_t>(count);
}

} // namespace

TriangleSurface parse_off(std::string_view text, const std::string& file) {
  TextLines lines(text, file, true);
  if (!lines.next_line()) throw lines.end_error("the OFF header");
  // The counts may stand on the header's line ("OFF 4 4 6") or on the next one.
  if (lines.words()[0] != "OFF")
    throw lines.error("expected the header 'OFF', found " + TextLines::quote(lines.words()[0]) +
                      " (Kerf reads plain OFF, not COFF, NOFF or binary OFF)");
  std::size_t first_count = 1;
  if (lines.words().size() == 1) {
    if (!lines.next_line()) throw lines.end_error("the counts #V #F #E");
    first_count = 0;
  }
  if (lines.words().size() != first_count + 3)
    throw lines.error("expected the three counts '#vertices #faces #edges'");
  const std::size_t num_vertices = off_count(lines, first_count, "vertices", 6, text.size());
  const std::size_t num_faces = off_count(lines, first_count + 1, "faces", 8, text.size());
  lines.integer(first_count + 2, "the number of edges"); // not used, often 0
  if (num_vertices > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw lines.error("more vertices than Kerf's 32-bit indices can number");

  std::vector<std::array<double, 3>> vertices(num_vertices);
  for (std::size_t v = 0; v < num_vertices; ++v) {
    const std::string what = "vertex " + std::to_string(v);
    if (!lines.next_line()) throw lines.end_error(what + " of " + std::to_string(num_vertices));
    vertices[v] = {lines.real(0, "x of " + what), lines.real(1, "y of " + what), lines.real(2, "z of " + what)};
    if (lines.words().size() > 3 + 4)
      throw lines.error(what + " has more numbers than x y z and a colour");
  }
  std::vector<std::array<int, 3>> triangles;
  for (std::size_t f = 0; f < num_faces; ++f) {
    const std::string what = "face " + std::to_string(f);
    if (!lines.next_line()) throw lines.end_error(what + " of " + std::to_string(num_faces));
    const long long corners = lines.integer(0, "the number of corners of " + what);
    if (corners < 3 || static_cast<unsigned long long>(corners) > lines.words().size() - 1)
      throw lines.error(what + " announces " + std::to_string(corners) + " corners; a face needs at least 3, "
                        "and the line holds " + std::to_string(lines.words().size() - 1) + " numbers");
    const auto corner = [&](std::size_t c) {
      const long long index = lines.integer(1 + c, "corner " + std::to_string(c) + " of " + what);
      if (index < 0 || static_cast<unsigned long long>(index) >= num_vertices)
        throw lines.error(what + ": vertex index " + std::to_string(index) + " is outside [0, " +
                          std::to_string(num_vertices) + ") (OFF counts from 0)");
      return static_cast<int>(index);
    };
    // A polygon becomes a fan around its first corner, which keeps its orientation.
    const int first = corner(0);
    int previous = corner(1);
    for (std::size_t c = 2; c < static_cast<std::size_t>(corners); ++c) {
      const int next = corner(c);
      triangles.push_back({first, previous, next});
      previous = next;
    }
  }
  if (lines.next_line())
    throw lines.error("more lines after the " + std::to_string(num_faces) + " faces announced (the count is wrong)");
  return surface_from_lists(vertices, triangles);
}

} // namespace kerf
