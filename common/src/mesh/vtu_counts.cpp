#include "mesh/vtu_counts.hpp"

#include "kerf/app/input_error.hpp"

#include <algorithm>
#include <charconv>
#include <limits>
#include <string_view>
#include <system_error>

namespace kerf {

void check_vtu_counts(const std::string& text, const std::string& file) {
  // Appended data is raw bytes that may hold anything, attribute-like text included.
  const std::string_view xml = std::string_view(text).substr(0, text.find("<AppendedData"));
  for (const char* attribute : {"NumberOfComponents", "NumberOfPoints", "NumberOfCells", "NumberOfTuples",
                                "NumberOfVerts", "NumberOfLines", "NumberOfStrips", "NumberOfPolys"}) {
    const std::string opening = std::string(attribute) + "=\"";
    const long long largest = std::string_view(attribute) == "NumberOfComponents"
                                  ? std::min<long long>(static_cast<long long>(text.size()),
                                                        std::numeric_limits<int>::max())
                                  : std::numeric_limits<int>::max();
    for (std::size_t at = xml.find(opening); at != std::string_view::npos; at = xml.find(opening, at + 1)) {
      const std::size_t first = at + opening.size();
      const std::size_t last = xml.find('"', first);
      const std::string_view value = xml.substr(first, last == std::string_view::npos ? 0 : last - first);
      long long count = -1;
      const auto [end, status] = std::from_chars(value.data(), value.data() + value.size(), count);
      if (status != std::errc() || end != value.data() + value.size() || count < 0 || count > largest)
        throw InputError(file, attribute,
                         "expected an integer in [0, " + std::to_string(largest) + "], found \"" +
                             std::string(value.substr(0, 24)) + "\"");
    }
  }
}

} // namespace kerf
