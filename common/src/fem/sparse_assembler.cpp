#include "kerf/fem/sparse_assembler.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace kerf {

SparseAssembler::SparseAssembler(const TetMatrix& elements, const DofMap& dofs)
    : elements_(elements), free_index_(dofs.free_index), prescribed_(dofs.prescribed) {
  const auto num_nodes = static_cast<Eigen::Index>(free_index_.size() / 3);
  const auto node_is_free = [&](Eigen::Index v) { return free_index_[static_cast<std::size_t>(3 * v)] >= 0; };
  for (Eigen::Index v = 0; v < num_nodes; ++v)
    for (int p = 1; p < 3; ++p)
      if ((free_index_[static_cast<std::size_t>(3 * v + p)] >= 0) != node_is_free(v))
        throw std::invalid_argument("SparseAssembler: node " + std::to_string(v) + " has some DOFs free and some prescribed");

  // 0. The slots each element uses: up to its last non-empty one.
  const int n = static_cast<int>(elements.cols());
  slots_used_.assign(static_cast<std::size_t>(elements.rows()), 0);
  block_offset_.assign(static_cast<std::size_t>(elements.rows()) + 1, 0);
  for (Eigen::Index t = 0; t < elements.rows(); ++t) {
    int used = 0;
    for (int a = 0; a < n; ++a)
      if (elements(t, a) >= 0) used = a + 1;
    slots_used_[static_cast<std::size_t>(t)] = used;
    block_offset_[static_cast<std::size_t>(t) + 1] = block_offset_[static_cast<std::size_t>(t)] + static_cast<std::size_t>(used * used);
  }

  // 1. Node adjacency: node j's neighbours are the free nodes it shares an element with (itself
  //    included), sorted.
  std::vector<std::vector<int>> neighbours(static_cast<std::size_t>(num_nodes));
  for (Eigen::Index t = 0; t < elements.rows(); ++t)
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b)
        if (elements(t, a) >= 0 && elements(t, b) >= 0 && node_is_free(elements(t, a)))
          neighbours[static_cast<std::size_t>(elements(t, b))].push_back(elements(t, a));
  for (auto& list : neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }

  // 2. The column-major pattern of K_ff. Free indices increase with the global DOF, so walking
  //    the sorted neighbours and their three components yields each column's rows in order; the
  //    three columns of a node are alike, 3 #neighbours long.
  const int num_free = dofs.num_free;
  std::vector<int> outer(static_cast<std::size_t>(num_free) + 1, 0);
  std::vector<int> inner;
  column_length_.assign(static_cast<std::size_t>(num_nodes), -1);
  for (Eigen::Index j = 0; j < num_nodes; ++j) {
    if (!node_is_free(j)) continue;
    column_length_[static_cast<std::size_t>(j)] = static_cast<int>(3 * neighbours[static_cast<std::size_t>(j)].size());
    for (int q = 0; q < 3; ++q) {
      for (int i : neighbours[static_cast<std::size_t>(j)])
        for (int p = 0; p < 3; ++p) inner.push_back(free_index_[static_cast<std::size_t>(3 * i + p)]);
      outer[static_cast<std::size_t>(free_index_[static_cast<std::size_t>(3 * j + q)]) + 1] = static_cast<int>(inner.size());
    }
  }
  K_.resize(num_free, num_free);
  K_.resizeNonZeros(static_cast<Eigen::Index>(inner.size()));
  std::copy(outer.begin(), outer.end(), K_.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), K_.innerIndexPtr());
  set_zero();

  // 3. The scatter map: for each free-free pair of slots (a, b), the position of the block's
  //    entry (3 node_a, 3 node_b) in the value array, found once by binary search in the column.
  block_first_.assign(block_offset_.back(), -1);
  for (Eigen::Index t = 0; t < elements.rows(); ++t) {
    const int used = slots_used_[static_cast<std::size_t>(t)];
    int* first = block_first_.data() + block_offset_[static_cast<std::size_t>(t)];
    for (int b = 0; b < used; ++b) {
      const int node_b = elements(t, b);
      if (node_b < 0 || !node_is_free(node_b)) continue;
      const int col = free_index_[static_cast<std::size_t>(3 * node_b)];
      const int* begin = K_.innerIndexPtr() + K_.outerIndexPtr()[col];
      const int* end = K_.innerIndexPtr() + K_.outerIndexPtr()[col + 1];
      for (int a = 0; a < used; ++a) {
        const int node_a = elements(t, a);
        if (node_a < 0 || !node_is_free(node_a)) continue;
        const int row = free_index_[static_cast<std::size_t>(3 * node_a)];
        first[b * used + a] = static_cast<int>(std::lower_bound(begin, end, row) - K_.innerIndexPtr());
      }
    }
  }
}

void SparseAssembler::set_zero() { std::fill(K_.valuePtr(), K_.valuePtr() + K_.nonZeros(), 0.0); }

} // namespace kerf
