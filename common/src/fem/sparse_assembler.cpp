#include "kerf/fem/sparse_assembler.hpp"

#include <algorithm>

namespace kerf {

SparseAssembler::SparseAssembler(const TetMatrix& tets, const DofMap& dofs) : tets_(tets), dofs_(dofs) {
  const auto num_nodes = static_cast<Eigen::Index>(dofs.free_index.size() / 3);
  const int n = static_cast<int>(tets.cols());

  // 0. The slots each element uses: up to its last non-empty one.
  slots_used_.assign(static_cast<std::size_t>(tets.rows()), 0);
  scatter_offset_.assign(static_cast<std::size_t>(tets.rows()) + 1, 0);
  for (Eigen::Index t = 0; t < tets.rows(); ++t) {
    int used = 0;
    for (int a = 0; a < n; ++a)
      if (tets(t, a) >= 0) used = a + 1;
    slots_used_[static_cast<std::size_t>(t)] = used;
    scatter_offset_[static_cast<std::size_t>(t) + 1] = scatter_offset_[static_cast<std::size_t>(t)] + static_cast<std::size_t>(9 * used * used);
  }

  // 1. Node adjacency: node j's neighbours are the nodes it shares a tet with (itself included).
  std::vector<std::vector<int>> neighbours(static_cast<std::size_t>(num_nodes));
  for (Eigen::Index t = 0; t < tets.rows(); ++t)
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b)
        if (tets(t, a) >= 0 && tets(t, b) >= 0) neighbours[static_cast<std::size_t>(tets(t, a))].push_back(tets(t, b));
  for (auto& list : neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }

  // 2. The column-major pattern of K_ff. Free indices increase with the global DOF, so walking
  //    the sorted neighbours and their three components yields each column's rows in order.
  const int num_free = dofs.num_free;
  std::vector<int> outer(static_cast<std::size_t>(num_free) + 1, 0);
  std::vector<int> inner;
  for (Eigen::Index j = 0; j < num_nodes; ++j)
    for (int q = 0; q < 3; ++q) {
      const int col = dofs.free_index[static_cast<std::size_t>(3 * j + q)];
      if (col < 0) continue;
      for (int i : neighbours[static_cast<std::size_t>(j)])
        for (int p = 0; p < 3; ++p) {
          const int row = dofs.free_index[static_cast<std::size_t>(3 * i + p)];
          if (row >= 0) inner.push_back(row);
        }
      outer[static_cast<std::size_t>(col) + 1] = static_cast<int>(inner.size());
    }
  K_.resize(num_free, num_free);
  K_.resizeNonZeros(static_cast<Eigen::Index>(inner.size()));
  std::copy(outer.begin(), outer.end(), K_.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), K_.innerIndexPtr());
  set_zero();

  // 3. The scatter map: for each element entry (r, c), the position of (row, col) in the value
  //    array, found once by binary search in the column.
  scatter_.assign(scatter_offset_.back(), -1);
  for (Eigen::Index t = 0; t < tets.rows(); ++t) {
    const int m = 3 * slots_used_[static_cast<std::size_t>(t)];
    int* scatter = scatter_.data() + scatter_offset_[static_cast<std::size_t>(t)];
    for (int c = 0; c < m; ++c) {
      if (tets(t, c / 3) < 0) continue;
      const int col = dofs.free_index[static_cast<std::size_t>(3 * tets(t, c / 3) + c % 3)];
      if (col < 0) continue;
      const int* begin = K_.innerIndexPtr() + K_.outerIndexPtr()[col];
      const int* end = K_.innerIndexPtr() + K_.outerIndexPtr()[col + 1];
      for (int r = 0; r < m; ++r) {
        if (tets(t, r / 3) < 0) continue;
        const int row = dofs.free_index[static_cast<std::size_t>(3 * tets(t, r / 3) + r % 3)];
        if (row < 0) continue;
        const int* position = std::lower_bound(begin, end, row);
        scatter[c * m + r] = static_cast<int>(position - K_.innerIndexPtr());
      }
    }
  }
}

void SparseAssembler::set_zero() { std::fill(K_.valuePtr(), K_.valuePtr() + K_.nonZeros(), 0.0); }

} // namespace kerf
