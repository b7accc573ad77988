#include "kerf/solve/unknown_blocks.hpp"

#include <algorithm>
#include <span>

namespace kerf {

std::vector<int> unknown_blocks(const Eigen::SparseMatrix<double>& A) {
  const int n = static_cast<int>(A.cols());
  // The row indices of column j, sorted (Eigen keeps each column's rows in order).
  const auto rows_of = [&](int j) {
    const int begin = A.outerIndexPtr()[j];
    const int count = A.isCompressed() ? A.outerIndexPtr()[j + 1] - begin : A.innerNonZeroPtr()[j];
    return std::span<const int>(A.innerIndexPtr() + begin, static_cast<std::size_t>(count));
  };
  std::vector<int> starts;
  for (int j = 0; j < n; ++j) {
    const bool same_as_previous = j > 0 && std::ranges::equal(rows_of(j - 1), rows_of(j));
    if (!same_as_previous) starts.push_back(j);
  }
  starts.push_back(n);
  return starts;
}

} // namespace kerf
