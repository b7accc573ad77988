#include "mesh/vtk_legacy_mesh_part.hpp"

#include "kerf/app/input_error.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string_view>
#include <system_error>

namespace kerf {
namespace {

/// Walks the whitespace-separated words of a text from a given position, counting lines.
class WordCursor {
public:
  WordCursor(std::string_view text, std::size_t position, int line)
      : text_(text), position_(position), line_(line) {}

  /// The next word, or an empty view at the end of the text.
  std::string_view next() {
    while (position_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[position_]))) {
      if (text_[position_] == '\n') ++line_;
      ++position_;
    }
    const std::size_t start = position_;
    while (position_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[position_])))
      ++position_;
    return text_.substr(start, position_ - start);
  }

  /// Where the cursor stands: the byte after the last word read, and its line.
  std::size_t position() const { return position_; }
  int line() const { return line_; }

private:
  std::string_view text_;
  std::size_t position_;
  int line_;
};

/// A word in upper case, for VTK's case-blind keywords.
std::string upper(std::string_view word) {
  std::string result(word);
  std::transform(result.begin(), result.end(), result.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return result;
}

/// True if `word` starts with `start`: VTK compares keywords by their start ("CELLSx" is CELLS).
bool starts_with(std::string_view word, std::string_view start) { return word.rfind(start, 0) == 0; }

/// A quoted word for messages, cut short.
std::string quote(std::string_view word) {
  constexpr std::size_t max_length = 20;
  std::string quoted = "'";
  quoted.append(word.substr(0, max_length));
  quoted += word.size() > max_length ? "...'" : "'";
  return quoted;
}

/// Checks the data words of one section as VTK will read them.
class SectionChecker {
public:
  SectionChecker(WordCursor& words, const std::string& file, std::string section)
      : words_(words), file_(file), section_(std::move(section)) {}

  /// The next word, which must exist.
  std::string_view word(const std::string& what) {
    const std::string_view w = words_.next();
    if (w.empty()) fail("the file ends before " + what);
    return w;
  }

  /// The next word as an integer in [lowest, highest].
  long long integer(long long lowest, long long highest, const std::string& what) {
    const std::string_view w = word(what);
    long long value = 0;
    const auto [end, status] = std::from_chars(w.data(), w.data() + w.size(), value);
    if (status != std::errc() || end != w.data() + w.size() || value < lowest || value > highest)
      fail("expected " + what + " (an integer in [" + std::to_string(lowest) + ", " +
           std::to_string(highest) + "]), found " + quote(w));
    return value;
  }

  /// The next word as a finite number of magnitude at most `largest`.
  void real(double largest, const std::string& what) {
    std::string_view w = word(what);
    if (!w.empty() && w.front() == '+') w.remove_prefix(1);
    double value = 0.0;
    const auto [end, status] = std::from_chars(w.data(), w.data() + w.size(), value);
    if (status != std::errc() || end != w.data() + w.size() || !(std::abs(value) <= largest))
      fail("expected " + what + " (a finite number), found " + quote(w));
  }

  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(file_, "line " + std::to_string(words_.line()), section_ + ": " + problem);
  }

private:
  WordCursor& words_;
  const std::string& file_;
  std::string section_;
};

/// The largest id an integer array of VTK type `type` holds: 64-bit types name themselves.
long long largest_integer(std::string_view type) {
  return type.find("64") != std::string_view::npos ? std::numeric_limits<long long>::max()
                                                   : std::numeric_limits<int>::max();
}

/// Count-prefixed cell lists (formats before 5): `cells` lists of "n id id ...", `size` integers in all.
void check_legacy_cell_lists(SectionChecker& check, long long cells, long long size) {
  long long used = 0;
  for (long long c = 0; c < cells; ++c) {
    const std::string what = "cell " + std::to_string(c);
    if (used >= size)
      check.fail("the " + std::to_string(cells) + " cells need more than the " +
                 std::to_string(size) + " integers announced");
    const long long ids = check.integer(0, size - used - 1, "the point count of " + what);
    used += 1 + ids;
    for (long long a = 0; a < ids; ++a)
      check.integer(0, std::numeric_limits<int>::max(), "a point id of " + what);
  }
  if (used != size)
    check.fail("the " + std::to_string(cells) + " cells hold " + std::to_string(used) +
               " integers, not the " + std::to_string(size) + " announced");
}

/// OFFSETS and CONNECTIVITY (format 5): `num_offsets` offsets, then `num_ids` point ids.
void check_offsets_and_connectivity(SectionChecker& check, long long num_offsets, long long num_ids) {
  for (const auto& [keyword, count] : {std::pair{"OFFSETS", num_offsets}, std::pair{"CONNECTIVITY", num_ids}}) {
    const std::string_view found = check.word(std::string("the ") + keyword + " line");
    if (!starts_with(upper(found), keyword))
      check.fail(std::string("expected ") + keyword + ", found " + quote(found));
    const long long largest = largest_integer(check.word(std::string("the type of ") + keyword));
    for (long long i = 0; i < count; ++i)
      check.integer(0, largest, std::string("entry ") + std::to_string(i) + " of " + keyword);
  }
}

/// True for the array types VTK's legacy reader knows (it compares them in lower case, by start).
bool is_known_array_type(const std::string& lower_type) {
  constexpr std::string_view types[] = {"bit", "unsigned_char", "char", "signed_char", "unsigned_short",
                                        "short", "unsigned_int", "int", "unsigned_long", "long",
                                        "float", "double", "vtkidtype", "vtktypeint64", "vtktypeuint64",
                                        "string", "utf8_string"};
  for (const std::string_view type : types)
    if (lower_type == type) return true;
  return false;
}

/// The size in bytes of one value of a binary legacy array, 0 for the types whose binary
/// layout we do not walk (bits, strings, and the integers whose width VTK's writer chooses).
std::size_t binary_value_size(const std::string& lower_type) {
  if (lower_type == "char" || lower_type == "unsigned_char" || lower_type == "signed_char") return 1;
  if (lower_type == "short" || lower_type == "unsigned_short") return 2;
  if (lower_type == "int" || lower_type == "unsigned_int" || lower_type == "float") return 4;
  if (lower_type == "double" || lower_type == "vtktypeint64" || lower_type == "vtktypeuint64") return 8;
  return 0;
}

/// The arrays of a FIELD block: "name components tuples type", then the values (words in an
/// ASCII file, raw bytes in a binary one). VTK's legacy reader dereferences a null pointer
/// when an array of the field data cannot be read.
void check_field_arrays(SectionChecker& check, WordCursor& data, const std::string& text, bool ascii,
                        long long arrays, long long max_count) {
  for (long long a = 0; a < arrays; ++a) {
    const std::string what = "array " + std::to_string(a);
    if (upper(check.word("the name of " + what)) == "NULL_ARRAY") continue;
    const long long components = check.integer(0, max_count, "the number of components of " + what);
    const long long tuples = check.integer(0, max_count, "the number of tuples of " + what);
    std::string type(check.word("the type of " + what));
    std::transform(type.begin(), type.end(), type.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (!is_known_array_type(type)) check.fail("the type of " + what + ", " + quote(type) + ", is not a VTK array type");
    if (components > 0 && tuples > max_count / components)
      check.fail(what + " announces more values than the file can hold");
    if (!ascii) {
      const std::size_t value_size = binary_value_size(type);
      if (value_size == 0)
        check.fail("Kerf does not check binary field data of type " + quote(type) +
                   "; save the file as ASCII or as .vtu");
      // The values start after the newline that ends the type, and end before another one.
      const std::size_t start = data.position() + 1;
      const auto bytes = static_cast<unsigned long long>(components * tuples) * value_size;
      if (start > text.size() || text.size() - start < bytes)
        check.fail("the file ends inside the values of " + what);
      data = WordCursor(text, start + static_cast<std::size_t>(bytes), data.line() + 1);
      continue;
    }
    const bool numbers = type != "string" && type != "utf8_string";
    for (long long i = 0; i < components * tuples; ++i) {
      const std::string value = "value " + std::to_string(i) + " of " + what;
      if (numbers)
        check.real(std::numeric_limits<double>::max(), value);
      else
        check.word(value);
    }
  }
}

/// Count-prefixed cell lists in a binary file (formats before 5): `size` big-endian 32-bit
/// integers from `at`, which VTK walks list by list trusting each count.
void check_binary_cell_lists(const std::string& text, std::size_t at, long long cells, long long size,
                             const SectionChecker& check) {
  if (text.size() < at || static_cast<unsigned long long>(text.size() - at) < 4ULL * static_cast<unsigned long long>(size))
    check.fail("the file ends inside the " + std::to_string(size) + " integers of the cell lists");
  const auto integer_at = [&text, at](long long i) {
    std::uint32_t value = 0;
    for (int b = 0; b < 4; ++b)
      value = (value << 8) | static_cast<unsigned char>(text[at + 4 * static_cast<std::size_t>(i) + b]);
    return static_cast<std::int32_t>(value);
  };
  long long used = 0;
  for (long long c = 0; c < cells; ++c) {
    const long long ids = used < size ? integer_at(used) : -1;
    if (ids < 0 || ids > size - used - 1)
      check.fail("the point count of cell " + std::to_string(c) + " does not fit in the " +
                 std::to_string(size) + " integers announced");
    used += 1 + ids;
  }
  if (used != size)
    check.fail("the " + std::to_string(cells) + " cells hold " + std::to_string(used) +
               " integers, not the " + std::to_string(size) + " announced");
}

} // namespace

std::string vtk_legacy_mesh_part(const std::string& text, const std::string& file, VtkLegacyDataset datasets) {
  // The header is four lines: version, title, ASCII or BINARY, DATASET. We check the first
  // and the last, and read the encoding; VTK checks the rest.
  std::size_t line_start = 0;
  std::string header[4];
  for (auto& line : header) {
    const std::size_t line_end = std::min(text.find('\n', line_start), text.size());
    line = text.substr(line_start, line_end - line_start);
    line_start = std::min(line_end + 1, text.size());
  }
  // VTK reads the header word by word: a keyword glued to the dataset type ("UNSTRUCTURED_GRID`FIELD")
  // would reach it unchecked, so the DATASET line must be two words and nothing else.
  WordCursor dataset(header[3], 0, 4);
  dataset.next();
  const std::string dataset_type = upper(dataset.next());
  const bool polydata_allowed = datasets == VtkLegacyDataset::unstructured_grid_or_polydata;
  const bool is_polydata = dataset_type == "POLYDATA";
  if (!(dataset_type == "UNSTRUCTURED_GRID" || (is_polydata && polydata_allowed)) || !dataset.next().empty())
    throw InputError(file, "line 4", polydata_allowed ? "expected 'DATASET UNSTRUCTURED_GRID' or 'DATASET POLYDATA' alone on the line"
                                                      : "expected 'DATASET UNSTRUCTURED_GRID' alone on the line");
  const bool ascii = starts_with(upper(WordCursor(header[2], 0, 3).next()), "ASCII");
  // The version decides the cell layout, so it must read as "major.minor", as VTK parses it.
  const std::size_t version_at = upper(header[0]).find("VERSION");
  const std::string_view version =
      version_at == std::string::npos ? std::string_view() : WordCursor(header[0], version_at + 7, 1).next();
  int major = 0;
  int minor = 0;
  const auto [major_end, major_status] = std::from_chars(version.data(), version.data() + version.size(), major);
  const bool has_dot = major_status == std::errc() && major_end != version.data() + version.size() && *major_end == '.';
  const auto [minor_end, minor_status] =
      has_dot ? std::from_chars(major_end + 1, version.data() + version.size(), minor)
              : std::from_chars_result{major_end, std::errc::invalid_argument};
  if (!has_dot || minor_status != std::errc() || minor_end != version.data() + version.size())
    throw InputError(file, "line 1", "expected '# vtk DataFile Version MAJOR.MINOR', found " + quote(header[0]));
  const bool offsets_layout = major >= 5;

  const auto max_count = static_cast<long long>(text.size());
  // VTK's reader dereferences a null pointer when the points or the cells never come, so the
  // part it sees must hold all the sections a dataset needs (Kerf needs them anyway). For
  // polydata the cells are the POLYGONS or TRIANGLE_STRIPS (vertices and lines may come too).
  bool has_points = false, has_cells = false, has_cell_types = is_polydata;
  const char* cells_keyword = is_polydata ? "POLYGONS" : "CELLS";
  const auto checked_part = [&](std::size_t end) {
    for (const auto& [seen, keyword] : {std::pair{has_points, "POINTS"}, std::pair{has_cells, cells_keyword},
                                        std::pair{has_cell_types, "CELL_TYPES"}})
      if (!seen)
        throw InputError(file, keyword, std::string("the file has no ") + keyword +
                                            (is_polydata && !has_cells ? " or TRIANGLE_STRIPS" : "") + " line");
    return text.substr(0, end);
  };
  // The sections that hold cell lists laid out as CELLS: polydata has four of them.
  const auto is_cell_list = [&](const std::string& name) {
    return is_polydata ? name == "VERTICES" || name == "LINES" || name == "POLYGONS" || name == "TRIANGLE_STRIPS"
                       : name == "CELLS";
  };
  int line_number = 5;
  while (line_start < text.size()) {
    const std::size_t line_end = std::min(text.find('\n', line_start), text.size());
    WordCursor words(std::string_view(text).substr(0, line_end), line_start, line_number);
    const std::string keyword = upper(words.next());
    if (starts_with(keyword, "POINT_DATA") || starts_with(keyword, "CELL_DATA"))
      return checked_part(line_start);
    std::size_t next_line = line_end + 1;
    int next_line_number = line_number + 1;
    const auto section = [&](const char* name, int num_counts) {
      // The counts are on the keyword's line; the data follows on the next lines.
      SectionChecker on_line(words, file, name);
      long long counts[2] = {0, 0};
      for (int c = 0; c < num_counts; ++c)
        counts[c] = on_line.integer(0, max_count, "the count on the " + std::string(name) + " line");
      WordCursor data(text, std::min(line_end + 1, text.size()), line_number + 1);
      SectionChecker check(data, file, name);
      if (ascii) {
        if (std::string(name) == "POINTS") {
          const std::string type = upper(on_line.word("the type of the coordinates"));
          if (!starts_with(type, "FLOAT") && !starts_with(type, "DOUBLE"))
            on_line.fail("the coordinates must be float or double, not " + quote(type));
          const double largest = starts_with(type, "FLOAT") ? std::numeric_limits<float>::max()
                                                             : std::numeric_limits<double>::max();
          for (long long i = 0; i < 3 * counts[0]; ++i)
            check.real(largest, "coordinate " + std::to_string(i % 3) + " of point " + std::to_string(i / 3));
        } else if (is_cell_list(name)) {
          if (offsets_layout)
            check_offsets_and_connectivity(check, counts[0], counts[1]);
          else
            check_legacy_cell_lists(check, counts[0], counts[1]);
        } else {
          for (long long c = 0; c < counts[0]; ++c)
            check.integer(0, 255, "the type of cell " + std::to_string(c));
        }
        next_line = data.position();
        next_line_number = data.line();
      } else if (is_cell_list(name) && !offsets_layout) {
        check_binary_cell_lists(text, line_end + 1, counts[0], counts[1], check);
      }
    };
    if (starts_with(keyword, "FIELD")) {
      SectionChecker on_line(words, file, "FIELD");
      on_line.word("the name of the field data");
      const long long arrays = on_line.integer(0, max_count, "the number of arrays");
      WordCursor data(text, std::min(line_end + 1, text.size()), line_number + 1);
      SectionChecker check(data, file, "FIELD");
      check_field_arrays(check, data, text, ascii, arrays, max_count);
      next_line = data.position();
      next_line_number = data.line();
    }
    if (starts_with(keyword, "POINTS")) {
      section("POINTS", 1);
      has_points = true;
    } else if (is_polydata) {
      for (const char* list : {"VERTICES", "LINES", "POLYGONS", "TRIANGLE_STRIPS"})
        if (starts_with(keyword, list)) {
          section(list, 2);
          has_cells = has_cells || std::string(list) == "POLYGONS" || std::string(list) == "TRIANGLE_STRIPS";
          break;
        }
    } else if (starts_with(keyword, "CELLS")) {
      section("CELLS", 2);
      has_cells = true;
    } else if (starts_with(keyword, "CELL_TYPES")) {
      section("CELL_TYPES", 1);
      has_cell_types = true;
    }
    line_start = next_line;
    line_number = next_line_number;
  }
  return checked_part(text.size());
}

} // namespace kerf
