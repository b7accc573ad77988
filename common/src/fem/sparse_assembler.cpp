#include "kerf/fem/sparse_assembler.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace kerf {

namespace {

// Appends to a column the free rows of the three DOFs of each node in `nodes` (sorted).
void append_node_rows(const std::vector<int>& free_index, const std::vector<int>& nodes, std::vector<int>& inner) {
  for (int i : nodes)
    for (int p = 0; p < 3; ++p) inner.push_back(free_index[static_cast<std::size_t>(3 * i + p)]);
}

// Makes K the num_free-square matrix of the column-major pattern (outer, inner), zeros stored.
void adopt_pattern(Eigen::SparseMatrix<double>& K, int num_free, const std::vector<int>& outer, const std::vector<int>& inner) {
  K.resize(num_free, num_free);
  K.resizeNonZeros(static_cast<Eigen::Index>(inner.size()));
  std::copy(outer.begin(), outer.end(), K.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), K.innerIndexPtr());
  std::fill(K.valuePtr(), K.valuePtr() + K.nonZeros(), 0.0);
}

// The scatter map: for each element t (slots_used[t] slots, its blocks from block_offset[t] in
// block_first) and free-free pair of slots (a, b), the position in K's value array of the block's
// entry (3 node_a, 3 node_b): known(t, a, b, col) where it is known without a search (-1 where
// not), else found by binary search in the column.
template <class Known>
void fill_scatter_map(const TetMatrix& elements, const std::vector<int>& free_index, const std::vector<int>& slots_used,
                      const std::vector<std::size_t>& block_offset, const Eigen::SparseMatrix<double>& K, std::vector<int>& block_first,
                      const Known& known) {
  const auto node_is_free = [&](int v) { return free_index[static_cast<std::size_t>(3 * v)] >= 0; };
  const int* outer = K.outerIndexPtr();
  block_first.assign(block_offset.back(), -1);
  for (Eigen::Index t = 0; t < elements.rows(); ++t) {
    const int used = slots_used[static_cast<std::size_t>(t)];
    int* first = block_first.data() + block_offset[static_cast<std::size_t>(t)];
    for (int b = 0; b < used; ++b) {
      const int node_b = elements(t, b);
      if (node_b < 0 || !node_is_free(node_b)) continue;
      const int col = free_index[static_cast<std::size_t>(3 * node_b)];
      const int* begin = K.innerIndexPtr() + outer[col];
      const int* end = K.innerIndexPtr() + outer[col + 1];
      for (int a = 0; a < used; ++a) {
        const int node_a = elements(t, a);
        if (node_a < 0 || !node_is_free(node_a)) continue;
        const int position = known(t, a, b, col);
        const int row = free_index[static_cast<std::size_t>(3 * node_a)];
        first[b * used + a] = position >= 0 ? position : static_cast<int>(std::lower_bound(begin, end, row) - K.innerIndexPtr());
      }
    }
  }
}

} // namespace

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
      append_node_rows(free_index_, neighbours[static_cast<std::size_t>(j)], inner);
      outer[static_cast<std::size_t>(free_index_[static_cast<std::size_t>(3 * j + q)]) + 1] = static_cast<int>(inner.size());
    }
  }
  adopt_pattern(K_, num_free, outer, inner);

  // 3. The scatter map: for each free-free pair of slots (a, b), the position of the block's
  //    entry (3 node_a, 3 node_b) in the value array, found once by binary search in the column.
  fill_scatter_map(elements_, free_index_, slots_used_, block_offset_, K_, block_first_, [](Eigen::Index, int, int, int) { return -1; });
}

SparseAssembler::SparseAssembler(const SparseAssembler& before, const TetMatrix& elements, const DofMap& dofs, int mesh_slots)
    : elements_(elements), free_index_(dofs.free_index), prescribed_(dofs.prescribed) {
  const auto num_nodes = static_cast<Eigen::Index>(free_index_.size() / 3);
  const Eigen::Index T = elements.rows();
  const int n = static_cast<int>(elements.cols());
  const auto fail = [](const std::string& why) { throw std::invalid_argument("SparseAssembler (from an earlier one): " + why); };
  if (T != before.elements_.rows() || mesh_slots < 1 || mesh_slots > n || mesh_slots > before.elements_.cols())
    fail("the elements are not those of the earlier assembler");

  // 0. The mesh's nodes: those in the mesh slots, 0 .. mesh_nodes - 1, unchanged row by row, and
  //    numbered before every other DOF node; their DOFs freed and numbered as before.
  Eigen::Index mesh_nodes = 0;
  for (Eigen::Index t = 0; t < T; ++t)
    for (int a = 0; a < mesh_slots; ++a) {
      if (elements(t, a) != before.elements_(t, a) || elements(t, a) < 0)
        fail("row " + std::to_string(t) + " has other mesh nodes than before");
      mesh_nodes = std::max<Eigen::Index>(mesh_nodes, elements(t, a) + 1);
    }
  if (mesh_nodes > num_nodes || static_cast<std::size_t>(3 * mesh_nodes) > before.free_index_.size() ||
      !std::equal(free_index_.begin(), free_index_.begin() + 3 * mesh_nodes, before.free_index_.begin()))
    fail("the mesh's DOFs are numbered otherwise than before");
  int mesh_free = 0; // the free mesh DOFs, which have the free indices 0 .. mesh_free - 1
  for (Eigen::Index i = 0; i < 3 * mesh_nodes; ++i) mesh_free += free_index_[static_cast<std::size_t>(i)] >= 0 ? 1 : 0;
  for (Eigen::Index i = 3 * mesh_nodes; i < 3 * num_nodes; ++i)
    if (free_index_[static_cast<std::size_t>(i)] >= 0 && free_index_[static_cast<std::size_t>(i)] < mesh_free)
      fail("a DOF after the mesh's is numbered among them");
  const auto node_is_free = [&](Eigen::Index v) { return free_index_[static_cast<std::size_t>(3 * v)] >= 0; };
  for (Eigen::Index v = mesh_nodes; v < num_nodes; ++v)
    for (int p = 1; p < 3; ++p)
      if ((free_index_[static_cast<std::size_t>(3 * v + p)] >= 0) != node_is_free(v))
        throw std::invalid_argument("SparseAssembler: node " + std::to_string(v) + " has some DOFs free and some prescribed");

  // 1. The slots each element uses, and the enriched rows: those with a slot past the mesh's.
  slots_used_.assign(static_cast<std::size_t>(T), 0);
  block_offset_.assign(static_cast<std::size_t>(T) + 1, 0);
  std::vector<Eigen::Index> enriched;
  for (Eigen::Index t = 0; t < T; ++t) {
    int used = 0;
    for (int a = 0; a < n; ++a)
      if (elements(t, a) >= 0) {
        used = a + 1;
        if (a >= mesh_slots && elements(t, a) < mesh_nodes) fail("row " + std::to_string(t) + " has a mesh node past its mesh slots");
      }
    if (used > mesh_slots) enriched.push_back(t);
    slots_used_[static_cast<std::size_t>(t)] = used;
    block_offset_[static_cast<std::size_t>(t) + 1] = block_offset_[static_cast<std::size_t>(t)] + static_cast<std::size_t>(used * used);
  }

  // 2. What the enriched rows add: to a mesh node's columns the enrichment rows it shares a row
  //    with, to an enrichment's columns every free DOF node it shares a row with.
  std::vector<std::vector<int>> added(static_cast<std::size_t>(num_nodes));
  for (const Eigen::Index t : enriched) {
    const int used = slots_used_[static_cast<std::size_t>(t)];
    for (int b = 0; b < used; ++b)
      for (int a = 0; a < used; ++a) {
        const int node_a = elements(t, a), node_b = elements(t, b);
        if (node_a < 0 || node_b < 0 || !node_is_free(node_a)) continue;
        if (node_a >= mesh_nodes || node_b >= mesh_nodes) added[static_cast<std::size_t>(node_b)].push_back(node_a);
      }
  }
  for (auto& list : added) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }

  // 3. The pattern, column by column in the order of the free indices: a mesh node's columns
  //    are its mesh rows as before (the leading rows of its earlier column) and then its added
  //    enrichment rows; an enrichment's columns are its added rows.
  const int num_free = dofs.num_free;
  const int* before_outer = before.K_.outerIndexPtr();
  const int* before_inner = before.K_.innerIndexPtr();
  std::vector<int> outer(static_cast<std::size_t>(num_free) + 1, 0);
  std::vector<int> inner;
  inner.reserve(static_cast<std::size_t>(before.K_.nonZeros()));
  column_length_.assign(static_cast<std::size_t>(num_nodes), -1);
  for (Eigen::Index j = 0; j < num_nodes; ++j) {
    if (!node_is_free(j)) continue;
    const std::vector<int>& rows = added[static_cast<std::size_t>(j)];
    int kept = 0;
    const int* kept_begin = nullptr;
    if (j < mesh_nodes) {
      const int col = free_index_[static_cast<std::size_t>(3 * j)];
      kept_begin = before_inner + before_outer[col];
      kept = static_cast<int>(std::lower_bound(kept_begin, before_inner + before_outer[col + 1], mesh_free) - kept_begin);
    }
    column_length_[static_cast<std::size_t>(j)] = kept + static_cast<int>(3 * rows.size());
    for (int q = 0; q < 3; ++q) {
      inner.insert(inner.end(), kept_begin, kept_begin + kept);
      append_node_rows(free_index_, rows, inner);
      outer[static_cast<std::size_t>(free_index_[static_cast<std::size_t>(3 * j + q)]) + 1] = static_cast<int>(inner.size());
    }
  }
  adopt_pattern(K_, num_free, outer, inner);

  // 4. The scatter map: a mesh-mesh block sits as far into its column as before, the others
  //    (enriched rows only) are found by binary search.
  const int* outer_now = K_.outerIndexPtr();
  fill_scatter_map(elements_, free_index_, slots_used_, block_offset_, K_, block_first_, [&](Eigen::Index t, int a, int b, int col) {
    if (a >= mesh_slots || b >= mesh_slots) return -1;
    const int used_before = before.slots_used_[static_cast<std::size_t>(t)];
    const int* first_before = before.block_first_.data() + before.block_offset_[static_cast<std::size_t>(t)];
    return first_before[b * used_before + a] - before_outer[col] + outer_now[col];
  });
}

void SparseAssembler::set_zero() { std::fill(K_.valuePtr(), K_.valuePtr() + K_.nonZeros(), 0.0); }

} // namespace kerf
