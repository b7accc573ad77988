#include "kerf/mesh/read_gmsh.hpp"

#include "kerf/app/input_error.hpp"
#include "kerf/mesh/check_tet_mesh.hpp"

#include <array>
#include <cctype>
#include <charconv>
#include <fstream>
#include <istream>
#include <string>
#include <string_view>
#include <system_error>
#include <unordered_map>
#include <utility>
#include <vector>

namespace kerf {
namespace {

/// What we need to know about one Gmsh element type: its dimension, its node count and a
/// name for messages. Types not in this table are rejected as unknown.
struct GmshElementType {
  int type;
  int dimension;
  int num_nodes;
  const char* name;
};

/// The element types of the Gmsh reference manual ("MSH file format", element types 1-31, 92, 93).
constexpr GmshElementType gmsh_element_types[] = {
    {15, 0, 1, "point"},
    {1, 1, 2, "2-node line"},
    {8, 1, 3, "3-node line"},
    {26, 1, 4, "4-node line"},
    {27, 1, 5, "5-node line"},
    {28, 1, 6, "6-node line"},
    {2, 2, 3, "3-node triangle"},
    {9, 2, 6, "6-node triangle"},
    {20, 2, 9, "9-node triangle"},
    {21, 2, 10, "10-node triangle"},
    {22, 2, 12, "12-node triangle"},
    {23, 2, 15, "15-node triangle"},
    {24, 2, 15, "15-node incomplete triangle"},
    {25, 2, 21, "21-node triangle"},
    {3, 2, 4, "4-node quadrangle"},
    {10, 2, 9, "9-node quadrangle"},
    {16, 2, 8, "8-node quadrangle"},
    {4, 3, 4, "4-node tetrahedron"},
    {11, 3, 10, "10-node tetrahedron"},
    {29, 3, 20, "20-node tetrahedron"},
    {30, 3, 35, "35-node tetrahedron"},
    {31, 3, 56, "56-node tetrahedron"},
    {5, 3, 8, "8-node hexahedron"},
    {12, 3, 27, "27-node hexahedron"},
    {17, 3, 20, "20-node hexahedron"},
    {92, 3, 64, "64-node hexahedron"},
    {93, 3, 125, "125-node hexahedron"},
    {6, 3, 6, "6-node prism"},
    {13, 3, 18, "18-node prism"},
    {18, 3, 15, "15-node prism"},
    {7, 3, 5, "5-node pyramid"},
    {14, 3, 14, "14-node pyramid"},
    {19, 3, 13, "13-node pyramid"},
};

constexpr int gmsh_tet4 = 4;
constexpr int gmsh_tet10 = 11;

/// Gmsh numbers the mid-edge nodes of a 10-node tet on the edges (0,1), (1,2), (2,0), (3,0),
/// (3,2), (3,1) (MTetrahedron10 in Gmsh's sources); Kerf and VTK on (0,1), (1,2), (0,2), (0,3),
/// (1,3), (2,3). The first four edges agree (a mid-edge node does not care about the
/// direction of its edge); the last two are swapped. Entry a is the Gmsh position of Kerf node a.
constexpr std::array<int, 10> kerf_from_gmsh_tet10 = {0, 1, 2, 3, 4, 5, 6, 7, 9, 8};

/// Reads a text file one line at a time, skipping blank lines and counting all lines, so
/// that every message can say where the problem is.
class LineReader {
public:
  LineReader(std::istream& in, std::string file) : in_(in), file_(std::move(file)) {}

  /// Moves to the next non-blank line, without its surrounding whitespace (and without the
  /// '\r' of a file written on Windows); returns false at the end of the file.
  bool next(std::string& line) {
    while (std::getline(in_, line)) {
      ++line_number_;
      const auto first = line.find_first_not_of(" \t\r");
      if (first == std::string::npos) continue;
      const auto last = line.find_last_not_of(" \t\r");
      line = line.substr(first, last - first + 1);
      return true;
    }
    return false;
  }

  /// The next non-blank line; at the end of the file, an error saying what we were reading.
  std::string expect_line(const std::string& reading) {
    std::string line;
    if (!next(line))
      throw InputError(file_, "line " + std::to_string(line_number_ + 1),
                       "unexpected end of file while reading " + reading +
                           " (the file is truncated)");
    return line;
  }

  /// The current line for messages, "line N".
  std::string where() const { return "line " + std::to_string(line_number_); }

  /// An InputError located at the current line.
  InputError error(const std::string& problem) const { return InputError(file_, where(), problem); }

  /// The file name used in messages.
  const std::string& file() const { return file_; }

private:
  std::istream& in_;
  std::string file_;
  int line_number_ = 0;
};

/// A line cut short for quoting in a one-line message.
std::string quote(std::string_view line) {
  constexpr std::size_t max_length = 40;
  if (line.size() <= max_length) return "'" + std::string(line) + "'";
  return "'" + std::string(line.substr(0, max_length)) + "...'";
}

/// The whitespace-separated words of a line, as copies (so they outlive the line).
std::vector<std::string> split(std::string_view line) {
  std::vector<std::string> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    const std::size_t start = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > start) words.emplace_back(line.substr(start, i - start));
  }
  return words;
}

/// Parses a whole word as an integer; `what` names it in the message if it is not one.
long long parse_integer(std::string_view word, const LineReader& reader, const std::string& what) {
  long long value = 0;
  const auto [end, status] = std::from_chars(word.data(), word.data() + word.size(), value);
  if (status != std::errc() || end != word.data() + word.size())
    throw reader.error("expected an integer for " + what + ", found " + quote(word));
  return value;
}

/// Parses a whole word as a count, which must not be negative.
std::size_t parse_count(std::string_view word, const LineReader& reader, const std::string& what) {
  const long long value = parse_integer(word, reader, what);
  if (value < 0) throw reader.error(what + " must not be negative, found " + quote(word));
  return static_cast<std::size_t>(value);
}

/// Parses a whole word as a real number. "nan" and "inf" are accepted here and rejected by
/// check_tet_mesh(), which names the node.
double parse_real(std::string_view word, const LineReader& reader, const std::string& what) {
  if (!word.empty() && word.front() == '+') word.remove_prefix(1);
  double value = 0.0;
  const auto [end, status] = std::from_chars(word.data(), word.data() + word.size(), value);
  if (status != std::errc() || end != word.data() + word.size())
    throw reader.error("expected a number for " + what + ", found " + quote(word));
  return value;
}

/// Compares two ASCII strings ignoring case: format 1 writes `$ENDNOD`, format 2 `$EndNodes`.
bool same_ignoring_case(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) !=
        std::tolower(static_cast<unsigned char>(b[i])))
      return false;
  return true;
}

/// A tetrahedron as the file gives it: Gmsh's type and its node tags.
struct GmshTet {
  int type;
  std::array<long long, 10> tags;
  int num_tags;
};

/// What the sections of the file add up to before the tags are renumbered.
struct GmshContents {
  std::vector<std::array<double, 3>> positions;   ///< in file order
  std::unordered_map<long long, int> index_of_tag; ///< node tag -> row in `positions`
  std::vector<GmshTet> tets;                      ///< in file order
  std::vector<std::string> tet_lines;              ///< "line N" of each tet, for messages
  bool has_nodes = false;                          ///< a node section was read
  bool has_elements = false;                       ///< an element section was read
};

/// Adds one node, refusing a tag that was already used.
void add_node(GmshContents& contents, long long tag, const std::array<double, 3>& x,
              const LineReader& reader) {
  const bool inserted =
      contents.index_of_tag.emplace(tag, static_cast<int>(contents.positions.size())).second;
  if (!inserted) throw reader.error("node tag " + std::to_string(tag) + " is used twice");
  contents.positions.push_back(x);
}

/// The line of a node or an element, or an error if the section ends before `count` of them.
std::string data_line(LineReader& reader, const std::string& section, std::size_t count,
                      std::size_t read_so_far, const std::string& items) {
  std::string line = reader.expect_line(section);
  if (line.front() == '$')
    throw reader.error(section + " announces " + std::to_string(count) + " " + items +
                       " but ends after " + std::to_string(read_so_far));
  return line;
}

/// Reads the closing line of a section, which must follow the announced number of items.
void expect_end(LineReader& reader, const std::string& section, const std::string& end_marker,
                std::size_t count, const std::string& items) {
  const std::string line = reader.expect_line(section);
  if (!same_ignoring_case(line, end_marker))
    throw reader.error("expected " + end_marker + " after the " + std::to_string(count) + " " +
                       items + " that " + section + " announces, found " + quote(line));
}

/// Reads "x y z" from three words.
std::array<double, 3> parse_position(const std::vector<std::string>& words, std::size_t first,
                                     const LineReader& reader) {
  return {parse_real(words[first], reader, "x"), parse_real(words[first + 1], reader, "y"),
          parse_real(words[first + 2], reader, "z")};
}

/// Node section of formats 1 and 2: a count, then one "tag x y z" line per node.
void read_nodes_v1_v2(LineReader& reader, const std::string& section, const std::string& end_marker,
                      GmshContents& contents) {
  const auto header = split(reader.expect_line(section));
  if (header.size() != 1) throw reader.error("expected the number of nodes alone on the line");
  const std::size_t count = parse_count(header[0], reader, "the number of nodes");
  for (std::size_t i = 0; i < count; ++i) {
    const auto words = split(data_line(reader, section, count, i, "nodes"));
    if (words.size() != 4)
      throw reader.error("expected a node tag and 3 coordinates, found " +
                         std::to_string(words.size()) + " values");
    add_node(contents, parse_integer(words[0], reader, "the node tag"),
             parse_position(words, 1, reader), reader);
  }
  expect_end(reader, section, end_marker, count, "nodes");
}

/// Looks a Gmsh element type up in the table; nullptr if it is unknown.
const GmshElementType* find_element_type(long long type) {
  for (const auto& known : gmsh_element_types)
    if (known.type == type) return &known;
  return nullptr;
}

/// Decides what to do with one element: keep a tet (returns true), skip a lower-dimensional
/// element (returns false), or reject anything else with a message.
bool keep_element(long long type, const LineReader& reader) {
  const GmshElementType* known = find_element_type(type);
  if (!known)
    throw reader.error("unknown Gmsh element type " + std::to_string(type) +
                       "; Kerf reads 4-node (type 4) and 10-node (type 11) tetrahedra");
  if (known->dimension < 3) return false;
  if (type == gmsh_tet4 || type == gmsh_tet10) return true;
  throw reader.error(std::string("element type ") + std::to_string(type) + " (" + known->name +
                     ") is not supported; Kerf reads 4-node (type 4) and 10-node (type 11) "
                     "tetrahedra");
}

/// Stores one tet given by its type and node tags, refusing a mix of Tet4 and Tet10.
void add_tet(GmshContents& contents, int type, const std::vector<std::string>& words,
             std::size_t first_tag, const LineReader& reader) {
  const int num_tags = find_element_type(type)->num_nodes;
  if (words.size() != first_tag + static_cast<std::size_t>(num_tags))
    throw reader.error("expected " + std::to_string(num_tags) + " node tags for a " +
                       find_element_type(type)->name + ", found " +
                       std::to_string(static_cast<long long>(words.size()) -
                                      static_cast<long long>(first_tag)));
  if (!contents.tets.empty() && contents.tets.front().type != type)
    throw reader.error("the mesh mixes 4-node and 10-node tetrahedra; Kerf needs one order");
  GmshTet tet{type, {}, num_tags};
  for (int a = 0; a < num_tags; ++a)
    tet.tags[a] = parse_integer(words[first_tag + a], reader, "a node tag");
  contents.tets.push_back(tet);
  contents.tet_lines.push_back(reader.where());
}

/// Element section of format 1 ("tag type physical elementary n-nodes nodes...") and of
/// format 2 ("tag type n-tags tags... nodes...").
void read_elements_v1_v2(LineReader& reader, int format, const std::string& section,
                         const std::string& end_marker, GmshContents& contents) {
  const auto header = split(reader.expect_line(section));
  if (header.size() != 1) throw reader.error("expected the number of elements alone on the line");
  const std::size_t count = parse_count(header[0], reader, "the number of elements");
  for (std::size_t i = 0; i < count; ++i) {
    const auto words = split(data_line(reader, section, count, i, "elements"));
    if (words.size() < 3) throw reader.error("expected an element tag, a type and node tags");
    const long long type = parse_integer(words[1], reader, "the element type");
    if (!keep_element(type, reader)) continue;
    // Format 1 gives the node count after two region numbers; format 2 gives a tag count
    // and that many tags before the nodes.
    std::size_t first_node = 0;
    if (format == 1) {
      first_node = 5;
    } else {
      first_node = 3 + parse_count(words[2], reader, "the number of tags");
    }
    if (words.size() < first_node) throw reader.error("the element line ends too early");
    add_tet(contents, static_cast<int>(type), words, first_node, reader);
  }
  expect_end(reader, section, end_marker, count, "elements");
}

/// Node section of format 4.1: a header, then blocks of "dim tag parametric n", n tags, n
/// coordinate lines.
void read_nodes_v4(LineReader& reader, GmshContents& contents) {
  const std::string section = "$Nodes";
  const auto header = split(reader.expect_line(section));
  if (header.size() != 4)
    throw reader.error("expected 4 numbers (blocks, nodes, smallest tag, largest tag), found " +
                       std::to_string(header.size()));
  const std::size_t num_blocks = parse_count(header[0], reader, "the number of node blocks");
  const std::size_t count = parse_count(header[1], reader, "the number of nodes");
  std::size_t read = 0;
  for (std::size_t b = 0; b < num_blocks; ++b) {
    const auto block = split(data_line(reader, section, count, read, "nodes"));
    if (block.size() != 4)
      throw reader.error("expected a node block header (dimension, entity, parametric, count)");
    const std::size_t dimension = parse_count(block[0], reader, "the entity dimension");
    const bool parametric = parse_integer(block[2], reader, "the parametric flag") != 0;
    const std::size_t in_block = parse_count(block[3], reader, "the number of nodes in the block");
    if (read + in_block > count)
      throw reader.error("the node blocks hold more nodes than the " + std::to_string(count) +
                         " that $Nodes announces");
    // The tags of a block come first, one per line, then the coordinates in the same order.
    // They grow as they are read, not to the block's count at once: a corrupt count must end
    // in a message about the file, not in an allocation of gigabytes.
    std::vector<long long> tags;
    for (std::size_t i = 0; i < in_block; ++i) {
      const auto words = split(data_line(reader, section, count, read, "nodes"));
      if (words.size() != 1) throw reader.error("expected one node tag on the line");
      tags.push_back(parse_integer(words[0], reader, "the node tag"));
    }
    const std::size_t num_values = 3 + (parametric ? dimension : 0);
    for (const long long tag : tags) {
      const auto words = split(data_line(reader, section, count, read, "nodes"));
      if (words.size() != num_values)
        throw reader.error("expected " + std::to_string(num_values) + " coordinates, found " +
                           std::to_string(words.size()));
      add_node(contents, tag, parse_position(words, 0, reader), reader);
      ++read;
    }
  }
  if (read != count)
    throw reader.error("$Nodes announces " + std::to_string(count) + " nodes but its blocks hold " +
                       std::to_string(read));
  expect_end(reader, section, "$EndNodes", count, "nodes");
}

/// Element section of format 4.1: a header, then blocks of "dim tag type n" and n lines of
/// "element-tag node-tags...".
void read_elements_v4(LineReader& reader, GmshContents& contents) {
  const std::string section = "$Elements";
  const auto header = split(reader.expect_line(section));
  if (header.size() != 4)
    throw reader.error("expected 4 numbers (blocks, elements, smallest tag, largest tag), found " +
                       std::to_string(header.size()));
  const std::size_t num_blocks = parse_count(header[0], reader, "the number of element blocks");
  const std::size_t count = parse_count(header[1], reader, "the number of elements");
  std::size_t read = 0;
  for (std::size_t b = 0; b < num_blocks; ++b) {
    const auto block = split(data_line(reader, section, count, read, "elements"));
    if (block.size() != 4)
      throw reader.error("expected an element block header (dimension, entity, type, count)");
    const long long type = parse_integer(block[2], reader, "the element type");
    const std::size_t in_block = parse_count(block[3], reader, "the number of elements in the block");
    if (read + in_block > count)
      throw reader.error("the element blocks hold more elements than the " +
                         std::to_string(count) + " that $Elements announces");
    const bool keep = keep_element(type, reader);
    for (std::size_t e = 0; e < in_block; ++e, ++read) {
      const auto words = split(data_line(reader, section, count, read, "elements"));
      if (keep) add_tet(contents, static_cast<int>(type), words, 1, reader);
    }
  }
  if (read != count)
    throw reader.error("$Elements announces " + std::to_string(count) +
                       " elements but its blocks hold " + std::to_string(read));
  expect_end(reader, section, "$EndElements", count, "elements");
}

/// Reads `$MeshFormat` and returns the major version (2 or 4); rejects binary files and 4.0.
int read_mesh_format(LineReader& reader) {
  const auto words = split(reader.expect_line("$MeshFormat"));
  if (words.size() != 3)
    throw reader.error("expected 'version file-type data-size' after $MeshFormat");
  const std::string version(words[0]);
  if (parse_integer(words[1], reader, "the file type") != 0)
    throw reader.error("binary .msh files are not supported; save the mesh as ASCII "
                       "(gmsh -save -format msh22 or msh41 without -bin)");
  int major = 0;
  if (version.rfind("2", 0) == 0) {
    major = 2;
  } else if (version.rfind("4.1", 0) == 0) {
    major = 4;
  } else {
    throw reader.error("Gmsh format " + version +
                       " is not supported; Kerf reads formats 1, 2.x and 4.1 "
                       "(re-save with gmsh -format msh41 or msh22)");
  }
  expect_end(reader, "$MeshFormat", "$EndMeshFormat", 1, "format line");
  return major;
}

/// Skips a section we do not need ($PhysicalNames, $Entities, $NodeData, ...).
void skip_section(LineReader& reader, const std::string& name) {
  const std::string end_marker = "$End" + name.substr(1);
  std::string line;
  do {
    line = reader.expect_line(name);
  } while (!same_ignoring_case(line, end_marker));
}

/// Turns tags into 0-based indices and Gmsh's Tet10 order into Kerf's.
TetMesh assemble_mesh(const GmshContents& contents, const std::string& file) {
  if (!contents.has_nodes) throw InputError(file, "$Nodes", "the file has no node section");
  if (!contents.has_elements)
    throw InputError(file, "$Elements", "the file has no element section");
  TetMesh mesh;
  mesh.nodes.resize(static_cast<Eigen::Index>(contents.positions.size()), 3);
  for (std::size_t v = 0; v < contents.positions.size(); ++v)
    for (int c = 0; c < 3; ++c)
      mesh.nodes(static_cast<Eigen::Index>(v), c) = contents.positions[v][c];

  const int per_tet = contents.tets.empty() ? 4 : contents.tets.front().num_tags;
  mesh.tets.resize(static_cast<Eigen::Index>(contents.tets.size()), per_tet);
  for (std::size_t t = 0; t < contents.tets.size(); ++t) {
    const GmshTet& tet = contents.tets[t];
    for (int a = 0; a < per_tet; ++a) {
      const long long tag = tet.tags[per_tet == 10 ? kerf_from_gmsh_tet10[a] : a];
      const auto found = contents.index_of_tag.find(tag);
      if (found == contents.index_of_tag.end())
        throw InputError(file, contents.tet_lines[t],
                         "node tag " + std::to_string(tag) + " is not in the node section");
      mesh.tets(static_cast<Eigen::Index>(t), a) = found->second;
    }
  }
  return mesh;
}

} // namespace

TetMesh read_gmsh(const std::filesystem::path& file, std::ostream* warnings) {
  const std::string name = file.string();
  if (!std::filesystem::exists(file)) throw InputError(name, "file", "does not exist");
  std::ifstream in(file);
  if (!in || std::filesystem::is_directory(file))
    throw InputError(name, "file", "cannot be opened for reading");
  LineReader reader(in, name);

  // Format 1 starts directly with $NOD; formats 2 and 4 start with $MeshFormat.
  std::string line = reader.expect_line("the first section");
  int format = 1;
  if (line == "$MeshFormat") {
    format = read_mesh_format(reader);
  } else if (!same_ignoring_case(line, "$NOD")) {
    throw reader.error("expected $MeshFormat (Gmsh 2 and 4) or $NOD (Gmsh 1), found " + quote(line) +
                       "; is this a Gmsh ASCII .msh file?");
  }

  GmshContents contents;
  bool have_line = format == 1; // in format 1, `line` already holds the $NOD we just saw
  while (have_line || reader.next(line)) {
    have_line = false;
    if (line.front() != '$')
      throw reader.error("expected a section name starting with '$', found " + quote(line));
    const bool is_nodes = format == 1 ? same_ignoring_case(line, "$NOD") : line == "$Nodes";
    const bool is_elements = format == 1 ? same_ignoring_case(line, "$ELM") : line == "$Elements";
    if (is_nodes) {
      if (contents.has_nodes) throw reader.error("a second node section");
      contents.has_nodes = true;
      if (format == 4)
        read_nodes_v4(reader, contents);
      else
        read_nodes_v1_v2(reader, line, format == 1 ? "$ENDNOD" : "$EndNodes", contents);
    } else if (is_elements) {
      if (contents.has_elements) throw reader.error("a second element section");
      contents.has_elements = true;
      if (format == 4)
        read_elements_v4(reader, contents);
      else
        read_elements_v1_v2(reader, format, line, format == 1 ? "$ENDELM" : "$EndElements",
                            contents);
    } else {
      skip_section(reader, line);
    }
  }

  TetMesh mesh = assemble_mesh(contents, name);
  check_tet_mesh(mesh, name, warnings);
  return mesh;
}

} // namespace kerf
