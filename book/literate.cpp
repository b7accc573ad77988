// kerf_literate: turns the chapters into Doxygen markdown pages.
//
// We write each chapter once, as a program that runs, and let this filter make the book page
// from it, so the prose cannot drift away from the code it explains. The idea is deal.II's
// (its tutorial programs are filtered the same way); the rules are ours:
//
//   - A run of whole-line `//` comments is prose. We strip the `//` (and `///`) and one space,
//     and keep the rest as markdown with Doxygen formulas (\f$ ... \f$, \f[ ... \f]).
//     A comment line that is only decoration (`// -----`, `// =====`) is a paragraph break.
//   - Everything else is code and goes, run by run, into fenced C++ blocks. Comments at the
//     end of a code line stay in the code. Blank lines at either end of a block are dropped.
//   - A leading `/* ... */` block, or a leading run of `//` lines that contains
//     "Sample runs:", is the file header (MFEM style). It is shown as it is, unparsed.
//   - `@sect3{Title}` on a line of its own (deal.II's marker; also @sect4, @sect5) is a
//     heading of that level. Markdown headings go one level down, so that an author's
//     `## Section` sits under the page's own `## The commented program` (or Introduction,
//     Results); nothing goes above level 3.
//   - Prose is made safe for Doxygen: a `#` or `%` before a word, a `<` that does not open an
//     HTML tag Doxygen knows, and a `\` or `@` that does not start a formula or a command we
//     allow (\ref, \cite, \image, \note, ...) are escaped, so they print as they are instead
//     of becoming links, commands or tags. Text inside `code spans`, fenced or indented code
//     blocks, formulas, link targets and HTML comments is left alone.
//   - In listings, an `\endcode` in the code gets a zero-width space, so it cannot end the
//     listing early, and the fence is longer than any run of backticks in the code.
//   - In an intro.md or results.md, a line `<!-- kernel: FILE NAME -->` (FILE relative to the
//     repository's top folder) becomes the listing of the library function NAME as FILE
//     defines it: its comment lines above it, its signature at the start of a line, and its
//     body to the first `}` at the start of a line. So a page shows the code that runs, not a
//     copy of it. A kernel that is not defined exactly once in FILE is an error naming the
//     page and line.
//   - An unterminated formula, fence or code span is an error with the file and line, not a
//     bad page. So is a chapter folder without main.cpp, intro.md, results.md, builds-on,
//     kind or tooltip, or a builds-on that names no earlier chapter.
//
// The chapter page is: "# Chapter N: title {#chapter_NN}" (title from the first "# " line of
// intro.md, else the folder name), the tooltip, what it builds on, then Introduction (intro.md),
// The commented program (main.cpp filtered), Results (results.md) and The plain program.
//
// Usage:
//   kerf_literate book SOURCE_DIR OUT_DIR   all chapter pages and the main page with its map
//   kerf_literate filter MAIN.cpp           the commented program of one file, on stdout
//   kerf_literate header FILE.hpp           a library header made safe for Doxygen, on stdout
//   kerf_literate page SOURCE_DIR FILE.md   an intro or results file as its chapter page shows it
//
// Plain C++20 and the standard library only: the book must build where Python is absent.

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

// An error in the input, reported as "file:line: message" and a non-zero exit status.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

[[noreturn]] void fail(const std::string& file, std::size_t line, const std::string& what) {
  throw InputError(file + ":" + std::to_string(line) + ": " + what);
}

std::vector<std::string> read_lines(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot be read");
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
  }
  return lines;
}

std::string read_text(const fs::path& path) {
  std::string text;
  for (const std::string& line : read_lines(path)) text += line + "\n";
  return text;
}

std::string trim(const std::string& s) {
  const auto begin = s.find_first_not_of(" \t");
  if (begin == std::string::npos) return "";
  const auto end = s.find_last_not_of(" \t");
  return s.substr(begin, end - begin + 1);
}

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

bool is_blank(const std::string& s) { return trim(s).empty(); }

bool is_word_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// ---------------------------------------------------------------------------------------------
// Code listings.

// Doxygen turns a fenced block into \code ... \endcode and ends it at the first \endcode or
// @endcode it meets, even inside the listing. A zero-width space after the backslash (or the
// @) keeps such text from ending the block; it is invisible on the page.
std::string defuse_endcode(std::string line) {
  static const std::string zwsp = "\xE2\x80\x8B";
  for (const std::string marker : {"\\endcode", "@endcode"}) {
    std::size_t pos = 0;
    while ((pos = line.find(marker, pos)) != std::string::npos) {
      line.insert(pos + 1, zwsp);
      pos += marker.size() + zwsp.size();
    }
  }
  return line;
}

// A fence longer than any run of backticks inside the code, so that no line can close it.
std::string fence_for(const std::vector<std::string>& lines) {
  std::size_t longest = 0;
  for (const std::string& line : lines) {
    std::size_t run = 0;
    for (char c : line) {
      run = (c == '`') ? run + 1 : 0;
      longest = std::max(longest, run);
    }
  }
  return std::string(std::max<std::size_t>(3, longest + 1), '`');
}

void write_code_block(std::ostream& out, std::vector<std::string> lines, const std::string& language) {
  while (!lines.empty() && is_blank(lines.back())) lines.pop_back();
  auto first = std::find_if(lines.begin(), lines.end(), [](const std::string& l) { return !is_blank(l); });
  lines.erase(lines.begin(), first);
  if (lines.empty()) return;
  const std::string fence = fence_for(lines);
  out << fence << language << "\n";
  for (const std::string& line : lines) out << defuse_endcode(line) << "\n";
  out << fence << "\n\n";
}

// ---------------------------------------------------------------------------------------------
// Prose.

// The Doxygen commands prose may use; any other backslash prints as a backslash. Prose is
// markdown, so its own markup (**bold**, `code`, fences) replaces \b, \c, \code and friends,
// and "a\b" stays a path.
const std::set<std::string>& allowed_commands() {
  static const std::set<std::string> commands = {
      "ref",  "anchor",  "cite",    "image",    "note",        "warning", "attention", "remark", "see",
      "sa",   "par",     "todo",    "link",     "endlink",     "subpage", "htmlonly",  "endhtmlonly"};
  return commands;
}

// The HTML tags Doxygen understands in markdown; any other `<word` is printed as text.
const std::set<std::string>& allowed_html_tags() {
  static const std::set<std::string> tags = {
      "a",     "b",       "blockquote", "br",    "caption", "center", "code",  "dd",         "del",
      "details", "div",   "dl",         "dt",    "em",      "h1",     "h2",    "h3",         "h4",
      "h5",    "h6",      "hr",         "i",     "img",     "ins",    "kbd",   "li",         "ol",
      "p",     "pre",     "s",          "small", "span",    "strike", "strong", "sub",       "summary",
      "sup",   "table",   "td",         "th",    "tr",      "tt",     "u",     "ul",         "var",
      "tbody", "thead",   "tfoot"};
  return tags;
}

// Where the prose scanner stands between lines: inside a formula, a code span, a fenced block
// or an HTML comment, the text is copied verbatim until the matching end. Indented code blocks
// (four spaces after a blank line, outside a list) are verbatim too.
struct ProseState {
  enum class Mode { text, inline_formula, display_formula, environment_formula, code_span, fence, html_comment };
  Mode mode = Mode::text;
  std::string closing;       // the backtick run that closes a code span, or the fence
  std::size_t opened_at = 0; // line where the current verbatim region opened
  bool previous_blank = true;
  bool indented_code = false;
  bool in_list = false;
};

std::size_t heading_level(const std::string& line) {
  const std::string stripped = trim(line);
  std::size_t level = 0;
  while (level < stripped.size() && stripped[level] == '#') ++level;
  const bool heading = level >= 1 && level <= 6 && (level == stripped.size() || stripped[level] == ' ');
  return heading ? level : 0;
}

// A fence line (``` or ~~~, three or more) opens or closes a block that is copied verbatim.
std::optional<std::string> fence_marker(const std::string& line) {
  const std::string stripped = trim(line);
  if (stripped.size() < 3 || (stripped[0] != '`' && stripped[0] != '~')) return std::nullopt;
  std::size_t n = 0;
  while (n < stripped.size() && stripped[n] == stripped[0]) ++n;
  if (n < 3) return std::nullopt;
  return stripped.substr(0, n);
}

bool is_list_item(const std::string& line) {
  const std::string s = trim(line);
  if (s.size() >= 2 && (s[0] == '-' || s[0] == '*' || s[0] == '+') && s[1] == ' ') return true;
  std::size_t d = 0;
  while (d < s.size() && std::isdigit(static_cast<unsigned char>(s[d]))) ++d;
  return d > 0 && d + 1 < s.size() && s[d] == '.' && s[d + 1] == ' ';
}

std::size_t indentation(const std::string& line) {
  std::size_t width = 0;
  for (char c : line) {
    if (c == ' ')
      ++width;
    else if (c == '\t')
      width += 4;
    else
      break;
  }
  return width;
}

// deal.II's section markers, `@sect3{Title}` (a section of the program) to `@sect5{...}`,
// become headings of that level: level and title.
std::optional<std::pair<std::size_t, std::string>> deal_ii_section(const std::string& line) {
  const std::string s = trim(line);
  if (s.size() < 8 || !starts_with(s, "@sect") || s[6] != '{' || s.back() != '}' || s[5] < '3' || s[5] > '6')
    return std::nullopt;
  return std::make_pair(static_cast<std::size_t>(s[5] - '0'), s.substr(7, s.size() - 8));
}

// Escapes one line of prose for Doxygen, carrying the verbatim regions across lines.
std::string escape_prose_line(const std::string& line, std::size_t line_number, ProseState& state) {
  using Mode = ProseState::Mode;
  const bool blank = is_blank(line);
  const bool previous_blank = state.previous_blank;
  state.previous_blank = blank;
  if (state.mode == Mode::fence) {
    const auto marker = fence_marker(line);
    if (marker && (*marker)[0] == state.closing[0] && marker->size() >= state.closing.size() && trim(line) == *marker)
      state.mode = Mode::text;
    return line;
  }
  std::string out;
  std::size_t i = 0;
  std::size_t n = line.size();
  if (state.mode == Mode::text) {
    if (blank) return line;
    // An indented code block starts after a blank line outside a list and runs while indented.
    if (indentation(line) >= 4 && !state.in_list && (previous_blank || state.indented_code)) {
      state.indented_code = true;
      return line;
    }
    state.indented_code = false;
    if (is_list_item(line)) state.in_list = true;
    else if (previous_blank && indentation(line) == 0) state.in_list = false;
    if (const auto marker = fence_marker(line)) {
      state.mode = Mode::fence;
      state.closing = *marker;
      state.opened_at = line_number;
      return line;
    }
    if (const auto section = deal_ii_section(line)) {
      // Only the title is left to escape: from after "{" to before the closing "}".
      out = std::string(section->first, '#') + " ";
      i = line.find('{') + 1;
      n = line.rfind('}');
    } else if (const std::size_t level = heading_level(line)) {
      out = std::string(std::min<std::size_t>(6, std::max<std::size_t>(3, level + 1)), '#');
      i = line.find('#') + level;
    }
  }

  auto open = [&](Mode mode, std::string closing = "") {
    state.mode = mode;
    state.closing = std::move(closing);
    state.opened_at = line_number;
  };
  auto copy_until = [&](const std::string& end, Mode after) {
    const std::size_t pos = line.find(end, i);
    if (pos == std::string::npos || pos + end.size() > n) {
      out += line.substr(i, n - i);
      i = n;
    } else {
      out += line.substr(i, pos + end.size() - i);
      i = pos + end.size();
      state.mode = after;
    }
  };
  while (i < n) {
    switch (state.mode) {
    case Mode::inline_formula: copy_until("\\f$", Mode::text); continue;
    case Mode::display_formula: copy_until("\\f]", Mode::text); continue;
    case Mode::environment_formula: copy_until("\\f}", Mode::text); continue;
    case Mode::html_comment: copy_until("-->", Mode::text); continue;
    case Mode::code_span: {
      // A code span ends at a backtick run of exactly the length that opened it.
      std::size_t j = i;
      bool closed = false;
      while (j < n && !closed) {
        if (line[j] != '`') {
          ++j;
          continue;
        }
        std::size_t run = 0;
        while (j + run < n && line[j + run] == '`') ++run;
        j += run;
        closed = run == state.closing.size();
      }
      out += line.substr(i, j - i);
      i = j;
      if (closed) state.mode = Mode::text;
      continue;
    }
    case Mode::fence: // whole lines only, handled above
    case Mode::text: break;
    }

    const char c = line[i];
    const char next = i + 1 < n ? line[i + 1] : '\0';
    if (c == '`') {
      std::size_t run = 0;
      while (i + run < n && line[i + run] == '`') ++run;
      out += line.substr(i, run);
      i += run;
      open(Mode::code_span, std::string(run, '`'));
    } else if (c == '\\' || c == '@') {
      // Doxygen commands start with either; we keep the formulas and the commands we allow.
      const std::string literal = c == '\\' ? "\\\\" : "\\@";
      const char third = i + 2 < n ? line[i + 2] : '\0';
      if (next == 'f' && (third == '$' || third == '[' || third == '{')) {
        out += line.substr(i, 3);
        i += 3;
        open(third == '$' ? Mode::inline_formula : third == '[' ? Mode::display_formula : Mode::environment_formula);
      } else if (std::isalpha(static_cast<unsigned char>(next))) {
        std::size_t j = i + 1;
        while (j < n && std::isalpha(static_cast<unsigned char>(line[j]))) ++j;
        const std::string word = line.substr(i + 1, j - i - 1);
        out += (allowed_commands().count(word) ? std::string(1, c) : literal) + word;
        i = j;
      } else if (c == '\\' && next != '\0' &&
                 std::string("\\@&$#<>%\".|-:{}[]*_`~!+").find(next) != std::string::npos) {
        out += line.substr(i, 2); // the author escaped it already
        i += 2;
      } else {
        out += literal;
        ++i;
      }
    } else if (c == '{' && next == '#') {
      copy_until("}", Mode::text); // a heading's {#label}
    } else if (c == ']' && next == '(') {
      copy_until(")", Mode::text); // a link target: an address or a #anchor
    } else if (line.compare(i, 7, "http://") == 0 || line.compare(i, 8, "https://") == 0) {
      const std::size_t end = line.find_first_of(" \t)>", i);
      const std::size_t stop = end == std::string::npos ? n : end;
      out += line.substr(i, stop - i);
      i = stop;
    } else if (c == '#' && (std::isalpha(static_cast<unsigned char>(next)) || next == '_' || next == ':')) {
      out += "\\#"; // "#V" would be an explicit link request to a symbol V
      ++i;
    } else if (c == '%' && is_word_char(next)) {
      out += "\\%"; // "%word" would print without its %
      ++i;
    } else if (c == '&' && next == '#') {
      out += "&#"; // a numeric character reference
      i += 2;
    } else if (c == '<') {
      if (line.compare(i, 4, "<!--") == 0) {
        out += "<!--";
        i += 4;
        open(Mode::html_comment);
        continue;
      }
      std::size_t j = i + 1;
      if (j < n && line[j] == '/') ++j;
      std::size_t k = j;
      while (k < n && std::isalnum(static_cast<unsigned char>(line[k]))) ++k;
      std::string tag = line.substr(j, k - j);
      std::transform(tag.begin(), tag.end(), tag.begin(), [](unsigned char ch) { return std::tolower(ch); });
      const bool starts_word = j < n && std::isalpha(static_cast<unsigned char>(line[j]));
      const bool known_tag =
          allowed_html_tags().count(tag) && (k == n || line[k] == '>' || line[k] == ' ' || line[k] == '/');
      out += (!starts_word || known_tag) ? "<" : "\\<";
      ++i;
    } else {
      out += c;
      ++i;
    }
  }
  return out;
}

void check_prose_closed(const ProseState& state, const std::string& file) {
  using Mode = ProseState::Mode;
  switch (state.mode) {
  case Mode::text: return;
  case Mode::inline_formula: fail(file, state.opened_at, "formula \\f$ is not closed by \\f$");
  case Mode::display_formula: fail(file, state.opened_at, "formula \\f[ is not closed by \\f]");
  case Mode::environment_formula: fail(file, state.opened_at, "formula \\f{ is not closed by \\f}");
  case Mode::code_span:
    fail(file, state.opened_at, "code span opened by " + state.closing + " is not closed (write \\` for a backtick)");
  case Mode::fence: fail(file, state.opened_at, "fenced block opened by " + state.closing + " is not closed");
  case Mode::html_comment: fail(file, state.opened_at, "HTML comment <!-- is not closed by -->");
  }
}

// Escapes a whole markdown text (an intro or results file, or a paragraph of a map cell).
std::string escape_markdown(const std::vector<std::string>& lines, std::size_t first_line_number,
                            const std::string& file) {
  ProseState state;
  std::string out;
  for (std::size_t k = 0; k < lines.size(); ++k) {
    // A code span does not survive a blank line in markdown, so neither does our state.
    if (is_blank(lines[k]) && state.mode == ProseState::Mode::code_span) check_prose_closed(state, file);
    out += escape_prose_line(lines[k], first_line_number + k, state) + "\n";
  }
  check_prose_closed(state, file);
  return out;
}

// ---------------------------------------------------------------------------------------------
// The commented program.

bool is_comment_line(const std::string& line) { return starts_with(trim(line), "//"); }

// The text of a `//` line: without the slashes and one space after them.
std::string comment_text(const std::string& line) {
  std::string s = trim(line).substr(2);
  if (starts_with(s, "/") || starts_with(s, "!")) s.erase(0, 1);
  if (starts_with(s, " ")) s.erase(0, 1);
  return s;
}

// A prose line that is only decoration, such as a row of dashes: a paragraph break.
bool is_decoration(const std::string& text) {
  const std::string s = trim(text);
  return s.size() >= 3 && s.find_first_not_of("-=*/#_") == std::string::npos;
}

struct Header {
  std::vector<std::string> lines; // the header's text, without comment markers
  std::size_t end = 0;            // index of the first line after it
};

// Finds the MFEM-style header: a leading /* */ block, or a leading // run with "Sample runs:".
std::optional<Header> find_header(const std::vector<std::string>& lines, const std::string& file) {
  std::size_t first = 0;
  while (first < lines.size() && is_blank(lines[first])) ++first;
  if (first == lines.size()) return std::nullopt;
  Header header;
  const std::string opening = trim(lines[first]);
  if (starts_with(opening, "/*")) {
    for (std::size_t k = first; k < lines.size(); ++k) {
      std::string text = lines[k];
      const bool last = text.find("*/") != std::string::npos;
      if (last) {
        if (!is_blank(text.substr(text.find("*/") + 2))) fail(file, k + 1, "code after the end of the header comment");
        text = text.substr(0, text.find("*/"));
      }
      if (k == first) text = trim(trim(text).substr(2));
      text = text.substr(0, text.find_last_not_of(" \t") + 1);
      const std::string t = trim(text);
      if (k != first && starts_with(t, "*")) // the " * " margin of a block comment
        text = t.size() > 1 && t[1] == ' ' ? t.substr(2) : t.substr(1);
      if (!(k == first && is_blank(text)) && !(last && is_blank(text))) header.lines.push_back(text);
      if (last) {
        header.end = k + 1;
        // Lines under the first keep their indentation relative to each other, not to the file.
        const std::size_t from = is_blank(trim(lines[first]).substr(2)) ? 0 : 1;
        std::size_t margin = std::string::npos;
        for (std::size_t h = from; h < header.lines.size(); ++h)
          if (!is_blank(header.lines[h])) margin = std::min(margin, header.lines[h].find_first_not_of(" \t"));
        for (std::size_t h = from; h < header.lines.size() && margin != std::string::npos; ++h)
          header.lines[h] = is_blank(header.lines[h]) ? "" : header.lines[h].substr(margin);
        return header;
      }
    }
    fail(file, first + 1, "the header comment /* is not closed by */");
  }
  std::size_t k = first;
  bool sample_runs = false;
  for (; k < lines.size() && is_comment_line(lines[k]); ++k) {
    header.lines.push_back(comment_text(lines[k]));
    sample_runs = sample_runs || lines[k].find("Sample runs:") != std::string::npos;
  }
  if (!sample_runs) return std::nullopt;
  header.end = k;
  return header;
}

// Drops the rows of dashes that frame a header, and the blank lines next to them.
std::vector<std::string> unframe(std::vector<std::string> lines) {
  auto frame = [](const std::string& l) { return is_blank(l) || is_decoration(l); };
  while (!lines.empty() && frame(lines.back())) lines.pop_back();
  while (!lines.empty() && frame(lines.front())) lines.erase(lines.begin());
  return lines;
}

std::string commented_program(const std::vector<std::string>& lines, const std::string& file) {
  std::ostringstream out;
  std::size_t k = 0;
  if (const auto header = find_header(lines, file)) {
    out << "The program opens with its header: what it is, how to run it, and what it computes.\n\n";
    write_code_block(out, unframe(header->lines), "{.unparsed}");
    k = header->end;
  }
  while (k < lines.size()) {
    // Blank lines between two runs belong to neither.
    while (k < lines.size() && is_blank(lines[k])) ++k;
    if (k == lines.size()) break;
    if (is_comment_line(lines[k])) {
      // Prose: comment lines, and the blank lines between them, up to the next code.
      std::vector<std::string> prose;
      ProseState state;
      std::size_t end = k;
      while (end < lines.size() && (is_comment_line(lines[end]) || is_blank(lines[end]))) {
        std::string text;
        if (is_blank(lines[end])) {
          std::size_t look = end;
          while (look < lines.size() && is_blank(lines[look])) ++look;
          if (look == lines.size() || !is_comment_line(lines[look])) break;
        } else {
          text = comment_text(lines[end]);
          if (state.mode == ProseState::Mode::text && is_decoration(text)) text.clear();
        }
        // A code span does not survive a paragraph break in markdown.
        if (is_blank(text) && state.mode == ProseState::Mode::code_span) check_prose_closed(state, file);
        prose.push_back(escape_prose_line(text, end + 1, state));
        ++end;
      }
      check_prose_closed(state, file);
      for (const std::string& p : prose) out << p << "\n";
      out << "\n";
      k = end;
    } else {
      std::vector<std::string> code;
      while (k < lines.size() && !is_comment_line(lines[k])) code.push_back(lines[k++]);
      write_code_block(out, code, "cpp");
    }
  }
  return out.str();
}

// ---------------------------------------------------------------------------------------------
// Library headers.

// Doxygen reads the library headers for the API reference, and our convention writes shapes
// as in libigl, `#V by 3`, where Doxygen would see an explicit link request to a symbol V.
// So the headers pass through this filter on their way into Doxygen (never into the
// compiler): inside comments, outside `code spans`, "quotes" and @code blocks, a `#` before a
// letter becomes `\#`. Lines are neither added nor removed, so Doxygen's line numbers stay right.
std::string filter_header(const std::vector<std::string>& lines) {
  std::string out;
  bool in_block_comment = false;
  bool in_code_block = false; // @code ... @endcode inside a comment
  for (const std::string& line : lines) {
    std::string result;
    bool in_string = false;
    char quote = 0;
    bool in_line_comment = false;
    std::size_t span = 0;      // the backtick run that opened a code span, or 0
    bool in_quote = false;     // Doxygen prints "quoted text" in comments as it is
    for (std::size_t i = 0; i < line.size(); ++i) {
      const char c = line[i];
      const char next = i + 1 < line.size() ? line[i + 1] : '\0';
      const bool in_comment = in_block_comment || in_line_comment;
      if (!in_comment) {
        if (in_string) {
          if (c == '\\') {
            result += line.substr(i, 2);
            ++i;
            continue;
          }
          if (c == quote) in_string = false;
        } else if (c == '"' || c == '\'') {
          in_string = true;
          quote = c;
        } else if (c == '/' && next == '/') {
          in_line_comment = true;
        } else if (c == '/' && next == '*') {
          in_block_comment = true;
          result += "/*";
          ++i;
          continue;
        }
        result += c;
        continue;
      }
      if (in_block_comment && c == '*' && next == '/') {
        in_block_comment = false;
        result += "*/";
        ++i;
        continue;
      }
      for (const std::string marker : {"code", "endcode", "verbatim", "endverbatim"})
        if ((c == '@' || c == '\\') && line.compare(i + 1, marker.size(), marker) == 0 &&
            (i + 1 + marker.size() == line.size() || !is_word_char(line[i + 1 + marker.size()])))
          in_code_block = marker == "code" || marker == "verbatim";
      if (c == '`' && !in_code_block) {
        std::size_t run = 0;
        while (i + run < line.size() && line[i + run] == '`') ++run;
        span = span == 0 ? run : (span == run ? 0 : span);
        result += line.substr(i, run);
        i += run - 1;
        continue;
      }
      if (c == '"' && span == 0) in_quote = !in_quote;
      const bool escaped = i > 0 && (line[i - 1] == '\\' || line[i - 1] == '&');
      if (c == '#' && span == 0 && !in_quote && !in_code_block && !escaped &&
          std::isalpha(static_cast<unsigned char>(next)))
        result += '\\';
      result += c;
    }
    out += result + "\n";
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Chapters.

struct Chapter {
  fs::path dir;
  std::string folder; // "01_linear_fem"
  std::string number; // "01"
  int index = 0;      // 1
  std::string title;  // "Linear finite elements"
  std::string tooltip;
  std::string kind;
  std::vector<std::string> builds_on; // chapter numbers, "00"
};

std::string one_line_file(const fs::path& path) {
  std::string text;
  for (const std::string& line : read_lines(path)) {
    if (is_blank(line)) continue;
    if (!text.empty()) text += ' ';
    text += trim(line);
  }
  return text;
}

void require_file(const fs::path& path) {
  if (!fs::is_regular_file(path))
    throw InputError(path.string() + ": missing; every chapter has main.cpp, intro.md, results.md, builds-on, kind "
                                     "and tooltip");
}

// Strips a trailing {#label} from a heading's text.
std::string heading_text(const std::string& line) {
  std::string s = trim(line);
  s = trim(s.substr(s.find_first_not_of('#')));
  const auto label = s.rfind("{#");
  if (label != std::string::npos && s.back() == '}') s = trim(s.substr(0, label));
  return s;
}

// The first level-1 heading, outside fenced blocks, if the file starts with one.
std::optional<std::size_t> title_line(const std::vector<std::string>& lines) {
  for (std::size_t k = 0; k < lines.size(); ++k) {
    if (is_blank(lines[k]) || starts_with(trim(lines[k]), "<!--")) continue;
    if (starts_with(trim(lines[k]), "# ")) return k;
    return std::nullopt;
  }
  return std::nullopt;
}

std::string pretty_slug(const std::string& folder) {
  std::string s = folder.size() > 3 ? folder.substr(3) : folder;
  std::replace(s.begin(), s.end(), '_', ' ');
  if (!s.empty()) s[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(s[0])));
  return s;
}

Chapter read_chapter(const fs::path& dir) {
  Chapter c;
  c.dir = dir;
  c.folder = dir.filename().string();
  c.number = c.folder.substr(0, 2);
  c.index = std::stoi(c.number);
  for (const char* name : {"main.cpp", "intro.md", "results.md", "builds-on", "kind", "tooltip"})
    require_file(dir / name);
  const auto intro = read_lines(dir / "intro.md");
  const auto title = title_line(intro);
  c.title = title ? heading_text(intro[*title]) : pretty_slug(c.folder);
  // The page says "Chapter N: " itself; an intro titled "Chapter 1: Linear FEM" keeps the rest.
  if (starts_with(c.title, "Chapter ")) {
    const std::size_t colon = c.title.find(':');
    if (colon != std::string::npos && c.title.find_first_not_of("0123456789 ", 8) == colon)
      c.title = trim(c.title.substr(colon + 1));
  }
  c.tooltip = one_line_file(dir / "tooltip");
  c.kind = one_line_file(dir / "kind");
  if (c.tooltip.empty()) throw InputError((dir / "tooltip").string() + ": empty; it holds one sentence");
  std::string builds_on = one_line_file(dir / "builds-on");
  std::replace(builds_on.begin(), builds_on.end(), ',', ' ');
  std::istringstream words(builds_on);
  for (std::string word; words >> word;) {
    if (word == "none") continue;
    if (word.size() < 2 || !std::isdigit(static_cast<unsigned char>(word[0])) ||
        !std::isdigit(static_cast<unsigned char>(word[1])))
      throw InputError((dir / "builds-on").string() + ": expected chapter numbers or folders (\"00\", "
                                                      "\"01_linear_fem\") or \"none\", got \"" + word + "\"");
    c.builds_on.push_back(word.substr(0, 2));
  }
  return c;
}

std::vector<Chapter> find_chapters(const fs::path& source_dir) {
  std::vector<Chapter> chapters;
  const fs::path root = source_dir / "chapters";
  if (!fs::is_directory(root)) return chapters;
  std::vector<fs::path> dirs;
  for (const auto& entry : fs::directory_iterator(root)) {
    const std::string name = entry.path().filename().string();
    if (entry.is_directory() && name.size() > 3 && std::isdigit(static_cast<unsigned char>(name[0])) &&
        std::isdigit(static_cast<unsigned char>(name[1])) && name[2] == '_')
      dirs.push_back(entry.path());
  }
  std::sort(dirs.begin(), dirs.end());
  for (const fs::path& dir : dirs) chapters.push_back(read_chapter(dir));
  std::set<std::string> numbers;
  for (const Chapter& c : chapters)
    if (!numbers.insert(c.number).second) throw InputError(c.dir.string() + ": two chapters numbered " + c.number);
  for (const Chapter& c : chapters)
    for (const std::string& n : c.builds_on)
      if (!numbers.count(n) || n >= c.number)
        throw InputError((c.dir / "builds-on").string() + ": names chapter " + n +
                         ", which is not an earlier chapter folder");
  return chapters;
}

std::string label(const Chapter& c) { return "chapter_" + c.number; }

std::string builds_on_text(const Chapter& c) {
  if (c.builds_on.empty()) return "";
  std::string text;
  for (std::size_t k = 0; k < c.builds_on.size(); ++k) {
    if (k > 0) text += ", ";
    text += "\\ref chapter_" + c.builds_on[k];
  }
  return text;
}

// Escapes a one-line text (a tooltip) as prose.
std::string escape_one_line(const std::string& text, const fs::path& file) {
  std::string out = escape_markdown({text}, 1, file.string());
  while (!out.empty() && out.back() == '\n') out.pop_back();
  return out;
}

// ---------------------------------------------------------------------------------------------
// Kernels: library functions shown on a page.

struct Kernel {
  std::string file;     // relative to the repository's top folder
  std::string function; // as it is spelled at its definition, e.g. "newmark_predict" or "Class::name"
};

// The kernel a line asks for, if it is a line `<!-- kernel: FILE NAME -->`.
std::optional<Kernel> kernel_directive(const std::string& line, std::size_t line_number, const std::string& page) {
  const std::string t = trim(line);
  const std::string open = "<!-- kernel:", close = "-->";
  if (!starts_with(t, open)) return std::nullopt;
  if (t.size() < open.size() + close.size() || t.compare(t.size() - close.size(), close.size(), close) != 0)
    fail(page, line_number, "a kernel line must be `<!-- kernel: FILE NAME -->` on one line");
  std::istringstream words(t.substr(open.size(), t.size() - open.size() - close.size()));
  Kernel kernel;
  std::string extra;
  if (!(words >> kernel.file >> kernel.function) || (words >> extra))
    fail(page, line_number, "a kernel line must name a file and a function: `<!-- kernel: FILE NAME -->`");
  return kernel;
}

// Whether `line` starts a definition of `name`: at the start of the line (no indentation), the
// name as a whole word followed by '('.
bool defines_at_line_start(const std::string& line, const std::string& name) {
  if (line.empty() || std::isspace(static_cast<unsigned char>(line[0])) || starts_with(line, "//")) return false;
  for (std::size_t at = line.find(name); at != std::string::npos; at = line.find(name, at + 1)) {
    const bool starts_word = at == 0 || !(is_word_char(line[at - 1]) || line[at - 1] == ':');
    const std::size_t after = at + name.size();
    if (starts_word && after < line.size() && line[after] == '(') return true;
  }
  return false;
}

// The lines of the kernel's definition, with the comment lines right above it.
std::vector<std::string> kernel_lines(const fs::path& source_root, const Kernel& kernel, std::size_t line_number,
                                      const std::string& page) {
  const fs::path file = source_root / kernel.file;
  if (!fs::is_regular_file(file)) fail(page, line_number, "kernel file " + kernel.file + " does not exist");
  const std::vector<std::string> lines = read_lines(file);
  std::vector<std::size_t> starts;
  for (std::size_t k = 0; k < lines.size(); ++k) {
    if (!defines_at_line_start(lines[k], kernel.function)) continue;
    // A definition, not a declaration: a '{' comes before any ';' from here on.
    for (std::size_t j = k; j < lines.size(); ++j) {
      const std::size_t brace = lines[j].find('{'), semicolon = lines[j].find(';');
      if (semicolon != std::string::npos && (brace == std::string::npos || semicolon < brace)) break;
      if (brace != std::string::npos) {
        starts.push_back(k);
        break;
      }
    }
  }
  if (starts.size() != 1)
    fail(page, line_number,
         "kernel " + kernel.function + " is defined " + std::to_string(starts.size()) + " times at the start of a line in " +
             kernel.file + " (it must be exactly once)");
  std::size_t begin = starts.front(), end = begin;
  while (end < lines.size() && lines[end] != "}") ++end;
  if (end == lines.size()) fail(page, line_number, "kernel " + kernel.function + " in " + kernel.file + " has no closing `}` at the start of a line");
  if (begin > 0 && starts_with(lines[begin - 1], "template")) --begin; // a template's parameter line
  while (begin > 0 && is_comment_line(lines[begin - 1]) && !std::isspace(static_cast<unsigned char>(lines[begin - 1][0]))) --begin;
  return std::vector<std::string>(lines.begin() + static_cast<long>(begin), lines.begin() + static_cast<long>(end) + 1);
}

// A markdown file's body with its title removed, its headings moved down one level and its
// kernel lines replaced by the kernels' listings.
std::string section_body(const fs::path& path, std::string* title, const fs::path& source_root) {
  auto lines = read_lines(path);
  std::size_t first = 0;
  if (const auto t = title_line(lines)) {
    if (title) *title = heading_text(lines[*t]);
    first = *t + 1;
  }
  std::string out;
  std::vector<std::string> prose;
  std::size_t prose_first = first + 1;
  for (std::size_t k = first; k < lines.size(); ++k) {
    const std::size_t line_number = k + 1;
    const auto kernel = kernel_directive(lines[k], line_number, path.string());
    if (!kernel) {
      prose.push_back(lines[k]);
      continue;
    }
    out += escape_markdown(prose, prose_first, path.string());
    prose.clear();
    prose_first = line_number + 1;
    std::ostringstream listing;
    listing << "From `" << kernel->file << "`:\n\n";
    write_code_block(listing, kernel_lines(source_root, *kernel, line_number, path.string()), "cpp");
    out += listing.str();
  }
  out += escape_markdown(prose, prose_first, path.string());
  return out;
}

std::string chapter_page(const Chapter& c) {
  std::ostringstream out;
  out << "# Chapter " << c.index << ": " << c.title << " {#" << label(c) << "}\n\n";
  out << "*" << escape_one_line(c.tooltip, c.dir / "tooltip") << "*\n\n";
  if (c.builds_on.empty())
    out << "This chapter builds on no other. ";
  else
    out << "This chapter builds on " << builds_on_text(c) << ". ";
  out << "Its program is `chapters/" << c.folder << "/main.cpp`, which builds the executable `" << c.folder
      << "`; its kind is *" << escape_one_line(c.kind, c.dir / "kind") << "*.\n\n";
  out << "[TOC]\n\n";

  out << "## Introduction {#" << label(c) << "_intro}\n\n";
  const fs::path source_root = c.dir.parent_path().parent_path();
  out << section_body(c.dir / "intro.md", nullptr, source_root) << "\n";

  const auto program = read_lines(c.dir / "main.cpp");
  out << "## The commented program {#" << label(c) << "_commented}\n\n";
  out << commented_program(program, (c.dir / "main.cpp").string());

  std::string results_title = "Results";
  const std::string results = section_body(c.dir / "results.md", &results_title, source_root);
  out << "## " << results_title << " {#" << label(c) << "_results}\n\n" << results << "\n";

  out << "## The plain program {#" << label(c) << "_plain}\n\n";
  out << "Here is `chapters/" << c.folder << "/main.cpp` without the book around it.\n\n";
  write_code_block(out, program, "cpp");
  out << "<!-- Generated by kerf_literate from chapters/" << c.folder << "/; edit those files, not this one. -->\n";
  return out.str();
}

// The chapter map: one row per chapter, linking to its page.
std::string chapter_map(const std::vector<Chapter>& chapters) {
  if (chapters.empty()) return "There are no chapters yet.\n";
  std::ostringstream out;
  out << "| Chapter | Builds on | Kind | What it teaches |\n";
  out << "|---------|-----------|------|-----------------|\n";
  for (const Chapter& c : chapters) {
    out << "| \\ref " << label(c) << " | " << (c.builds_on.empty() ? "none" : builds_on_text(c)) << " | "
        << escape_one_line(c.kind, c.dir / "kind") << " | " << escape_one_line(c.tooltip, c.dir / "tooltip")
        << " |\n";
  }
  return out.str();
}

const std::string map_placeholder = "<!-- KERF_CHAPTER_MAP -->";

std::string main_page(const fs::path& source, const std::vector<Chapter>& chapters) {
  const fs::path path = source / "book" / "mainpage.md";
  std::string out;
  bool placed = false;
  for (const std::string& line : read_lines(path)) {
    if (trim(line) == map_placeholder) {
      out += chapter_map(chapters);
      placed = true;
    } else {
      out += line + "\n";
    }
  }
  if (!placed) throw InputError(path.string() + ": has no line " + map_placeholder + " where the chapter map goes");
  return out;
}

void write_if_changed(const fs::path& path, const std::string& text) {
  if (fs::exists(path) && read_text(path) == text) return;
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw InputError(path.string() + ": cannot be written");
}

void build_book(const fs::path& source, const fs::path& out_dir) {
  const auto chapters = find_chapters(source);
  fs::create_directories(out_dir);
  // Pages of chapters that were renamed or removed must not linger in the book.
  std::set<fs::path> wanted = {out_dir / "mainpage.md"};
  for (const Chapter& c : chapters) wanted.insert(out_dir / (label(c) + ".md"));
  for (const auto& entry : fs::directory_iterator(out_dir))
    if (entry.path().extension() == ".md" && !wanted.count(entry.path())) fs::remove(entry.path());
  for (const Chapter& c : chapters) write_if_changed(out_dir / (label(c) + ".md"), chapter_page(c));
  write_if_changed(out_dir / "mainpage.md", main_page(source, chapters));
}

} // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  try {
    if (args.size() == 3 && args[0] == "book") {
      build_book(args[1], args[2]);
    } else if (args.size() == 2 && args[0] == "filter") {
      std::cout << commented_program(read_lines(args[1]), args[1]);
    } else if (args.size() == 2 && args[0] == "header") {
      std::cout << filter_header(read_lines(args[1]));
    } else if (args.size() == 3 && args[0] == "page") {
      std::cout << section_body(args[2], nullptr, args[1]);
    } else {
      std::cerr << "usage: kerf_literate book SOURCE_DIR OUT_DIR\n"
                   "       kerf_literate filter MAIN.cpp\n"
                   "       kerf_literate header FILE.hpp\n"
                   "       kerf_literate page SOURCE_DIR FILE.md\n";
      return 2;
    }
  } catch (const std::exception& e) {
    std::cerr << "kerf_literate: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
