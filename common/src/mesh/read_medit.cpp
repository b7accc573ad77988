#include "kerf/mesh/read_medit.hpp"

#include "kerf/app/input_error.hpp"
#include "kerf/mesh/check_tet_mesh.hpp"

#include <cctype>
#include <charconv>
#include <cstdint>
#include <fstream>
#include <istream>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>

namespace kerf {
namespace {

/// Reads a free-format text file one word at a time, dropping `#` comments and remembering
/// the line of the last word, so that every message can say where the problem is.
class WordReader {
public:
  WordReader(std::istream& in, std::string file) : in_(in), file_(std::move(file)) {}

  /// Moves to the next word; returns false at the end of the file.
  bool next(std::string& word) {
    word.clear();
    char c = 0;
    while (in_.get(c)) {
      if (c == '\n') ++line_number_;
      if (c == '#') {
        while (in_.get(c) && c != '\n') {
        }
        ++line_number_;
        continue;
      }
      if (!std::isspace(static_cast<unsigned char>(c))) break;
    }
    if (!in_) return false;
    word_line_ = line_number_;
    do {
      word.push_back(c);
    } while (in_.get(c) && !std::isspace(static_cast<unsigned char>(c)) && c != '#');
    if (in_) in_.unget(); // leave the separator, so that a newline is still counted
    return true;
  }

  /// The next word; at the end of the file, an error saying what we were reading.
  std::string expect(const std::string& reading) {
    std::string word;
    if (!next(word))
      throw InputError(file_, "line " + std::to_string(line_number_),
                       "unexpected end of file while reading " + reading +
                           " (the file is truncated)");
    return word;
  }

  /// The next word as an integer.
  long long expect_integer(const std::string& reading) {
    const std::string word = expect(reading);
    long long value = 0;
    const auto [end, status] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (status != std::errc() || end != word.data() + word.size())
      throw error("expected an integer in " + reading + ", found '" + word + "'");
    return value;
  }

  /// The next word as a real number; "nan" passes here and check_tet_mesh() names the node.
  double expect_real(const std::string& reading) {
    const std::string word = expect(reading);
    std::string_view digits = word;
    if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
    double value = 0.0;
    const auto [end, status] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (status != std::errc() || end != digits.data() + digits.size())
      throw error("expected a number in " + reading + ", found '" + word + "'");
    return value;
  }

  /// An InputError located at the line of the last word read.
  InputError error(const std::string& problem) const {
    return InputError(file_, "line " + std::to_string(word_line_), problem);
  }

private:
  std::istream& in_;
  std::string file_;
  int line_number_ = 1;
  int word_line_ = 1;
};

/// The number of values per entry of the Medit sections we skip (each entry ends with a
/// reference number, except in the lists of single indices); -1 for a keyword we do not know.
int skipped_section_width(const std::string& keyword) {
  struct Section {
    const char* keyword;
    int width;
  };
  constexpr Section sections[] = {
      {"Edges", 3},           {"Triangles", 4},        {"Quadrilaterals", 5},
      {"Corners", 1},         {"Ridges", 1},           {"RequiredVertices", 1},
      {"RequiredEdges", 1},   {"RequiredTriangles", 1}, {"Normals", 3},
      {"Tangents", 3},        {"NormalAtVertices", 2}, {"TangentAtVertices", 2}};
  for (const auto& section : sections)
    if (keyword == section.keyword) return section.width;
  return -1;
}

/// Reads a section count, which must not be negative and must fit in the file: each of its
/// entries has `words_per_entry` words of at least one character and a separator. Checking
/// this before the section is read keeps a corrupt count from allocating gigabytes (or, times
/// the width, from overflowing) for data the file cannot hold.
Eigen::Index read_count(WordReader& reader, const std::string& section, int words_per_entry,
                        std::uintmax_t file_size) {
  const long long count = reader.expect_integer("the number of " + section);
  if (count < 0) throw reader.error(section + ": the count must not be negative");
  const std::uintmax_t max_count = (file_size + 1) / (2 * static_cast<std::uintmax_t>(words_per_entry));
  if (static_cast<std::uintmax_t>(count) > max_count)
    throw reader.error(section + ": the count " + std::to_string(count) + " is more than the " +
                       std::to_string(file_size) + " bytes of the file can hold (the file is "
                       "truncated or the count is wrong)");
  return static_cast<Eigen::Index>(count);
}

} // namespace

TetMesh read_medit(const std::filesystem::path& file, std::ostream* warnings) {
  const std::string name = file.string();
  if (!std::filesystem::exists(file)) throw InputError(name, "file", "does not exist");
  std::ifstream in(file);
  if (!in || std::filesystem::is_directory(file))
    throw InputError(name, "file", "cannot be opened for reading");
  WordReader reader(in, name);
  const std::uintmax_t file_size = std::filesystem::file_size(file);

  const std::string first = reader.expect("the header");
  if (first != "MeshVersionFormatted")
    throw reader.error("expected MeshVersionFormatted, found '" + first +
                       "'; is this an ASCII Medit .mesh file?");
  reader.expect_integer("the MeshVersionFormatted number");

  TetMesh mesh;
  bool has_vertices = false;
  bool has_tetrahedra = false;
  for (;;) {
    const std::string keyword = reader.expect("the next section keyword (or End)");
    if (keyword == "End") break;
    if (keyword == "Dimension") {
      const long long dimension = reader.expect_integer("Dimension");
      if (dimension != 3)
        throw reader.error("Dimension is " + std::to_string(dimension) + "; Kerf needs 3");
    } else if (keyword == "Vertices") {
      if (has_vertices) throw reader.error("a second Vertices section");
      has_vertices = true;
      mesh.nodes.resize(read_count(reader, "Vertices", 4, file_size), 3);
      for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) {
        const std::string what = "vertex " + std::to_string(v + 1) + " of Vertices";
        for (int c = 0; c < 3; ++c) mesh.nodes(v, c) = reader.expect_real(what);
        reader.expect_integer("the reference number of " + what);
      }
    } else if (keyword == "Tetrahedra") {
      if (has_tetrahedra) throw reader.error("a second Tetrahedra section");
      has_tetrahedra = true;
      mesh.tets.resize(read_count(reader, "Tetrahedra", 5, file_size), 4);
      for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
        const std::string what = "tetrahedron " + std::to_string(t + 1) + " of Tetrahedra";
        for (int a = 0; a < 4; ++a) {
          // Medit counts vertices from 1; we check here, where the line is known, because
          // after the shift to 0-based indices a 0 in the file would read as -1.
          const long long index = reader.expect_integer(what);
          if (!has_vertices || index < 1 || index > mesh.num_nodes())
            throw reader.error(what + ": vertex index " + std::to_string(index) +
                               " is outside [1, " + std::to_string(mesh.num_nodes()) +
                               "] (Medit counts from 1, Vertices must come first)");
          mesh.tets(t, a) = static_cast<int>(index - 1);
        }
        reader.expect_integer("the reference number of " + what);
      }
    } else if (keyword == "Hexahedra" || keyword == "Prisms" || keyword == "Pyramids") {
      throw reader.error("the mesh has " + keyword + "; Kerf reads tetrahedra only");
    } else if (const int width = skipped_section_width(keyword); width > 0) {
      // Normals and tangents hold real numbers, the rest integers: a real number reads both.
      const Eigen::Index count = read_count(reader, keyword, width, file_size);
      for (Eigen::Index i = 0; i < count * width; ++i) reader.expect_real(keyword);
    } else {
      throw reader.error("unknown keyword '" + keyword +
                         "' (a wrong count in the section before would also lead here)");
    }
  }
  if (!has_vertices) throw InputError(name, "Vertices", "the file has no Vertices section");
  if (!has_tetrahedra) throw InputError(name, "Tetrahedra", "the file has no Tetrahedra section");
  check_tet_mesh(mesh, name, warnings);
  return mesh;
}

} // namespace kerf
