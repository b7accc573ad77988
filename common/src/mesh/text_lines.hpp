// Private to the kerf library (not under include/): the line-by-line tokenizer of the small
// text formats of cut surfaces (OBJ, OFF, ASCII STL), whose messages name the line.
#pragma once

#include "kerf/app/input_error.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

namespace kerf {

/// Walks a text line by line and splits each line into its whitespace-separated words, with
/// `#` comments dropped if the format has them; every error it makes names the file and the line.
class TextLines {
public:
  TextLines(std::string_view text, std::string file, bool hash_comments)
      : text_(text), file_(std::move(file)), hash_comments_(hash_comments) {}

  /// Moves to the next line that holds a word; false at the end of the text.
  bool next_line() {
    while (position_ < text_.size()) {
      const std::size_t end = std::min(text_.find('\n', position_), text_.size());
      std::string_view line = text_.substr(position_, end - position_);
      position_ = end + 1;
      ++line_number_;
      if (hash_comments_) line = line.substr(0, line.find('#'));
      words_.clear();
      for (std::size_t at = 0; at < line.size();) {
        while (at < line.size() && std::isspace(static_cast<unsigned char>(line[at]))) ++at;
        const std::size_t start = at;
        while (at < line.size() && !std::isspace(static_cast<unsigned char>(line[at]))) ++at;
        if (at > start) words_.push_back(line.substr(start, at - start));
      }
      if (!words_.empty()) return true;
    }
    words_.clear();
    return false;
  }

  /// The words of the current line.
  const std::vector<std::string_view>& words() const { return words_; }
  /// The number of the current line, from 1.
  int line_number() const { return line_number_; }

  /// Word i of the current line as a real number; "nan" and "inf" pass, and the surface check
  /// names the vertex. `what` says what the word is, for the message.
  double real(std::size_t i, const std::string& what) const {
    std::string_view word = required(i, what);
    if (word.front() == '+') word.remove_prefix(1);
    double value = 0.0;
    const auto [end, status] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (status != std::errc() || end != word.data() + word.size())
      throw error("expected a number for " + what + ", found " + quote(words_[i]));
    return value;
  }

  /// Word i of the current line as an integer.
  long long integer(std::size_t i, const std::string& what) const {
    const std::string_view word = required(i, what);
    long long value = 0;
    const auto [end, status] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (status != std::errc() || end != word.data() + word.size())
      throw error("expected an integer for " + what + ", found " + quote(word));
    return value;
  }

  /// Word i of the current line, which must exist.
  std::string_view required(std::size_t i, const std::string& what) const {
    if (i >= words_.size()) throw error("the line ends before " + what);
    return words_[i];
  }

  /// An InputError at the current line.
  InputError error(const std::string& problem) const {
    return InputError(file_, "line " + std::to_string(line_number_), problem);
  }

  /// An InputError at the end of the text: the file is truncated. An empty file ends on line 1.
  InputError end_error(const std::string& reading) const {
    return InputError(file_, "line " + std::to_string(std::max(line_number_, 1)),
                      "unexpected end of file while reading " + reading + " (the file is truncated)");
  }

  /// A word in quotes for messages, cut short.
  static std::string quote(std::string_view word) {
    constexpr std::size_t max_length = 20;
    // Built by appending: GCC 12 warns falsely (-Wrestrict) about "'" + std::string(...).
    std::string quoted = "'";
    quoted.append(word.substr(0, max_length));
    quoted += word.size() > max_length ? "...'" : "'";
    return quoted;
  }

private:
  std::string_view text_;
  std::string file_;
  bool hash_comments_;
  std::size_t position_ = 0;
  int line_number_ = 0;
  std::vector<std::string_view> words_;
};

} // namespace kerf
