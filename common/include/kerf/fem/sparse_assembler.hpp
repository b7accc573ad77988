/// @file sparse_assembler.hpp
/// @brief Assembly into a sparsity pattern and scatter map built once and reused (eq. 23).
#pragma once

#include "kerf/fem/dof_map.hpp"
#include "kerf/mesh/tet_mesh.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cassert>
#include <vector>

namespace kerf {

/// Assembles element matrices into the reduced matrix K_ff (both triangles stored, column
/// major) and lifts the prescribed DOFs into the right-hand side: f_f -= K_fc u_c.
///
/// The pattern follows the mesh connectivity (a 3x3 block for every pair of nodes that share a
/// tet, Schoch et al. section 3.6). We compute it once, and with it, for every pair of nodes of
/// every element, where their 3x3 block sits in the matrix's value array: the scatter map.
/// Re-assembling is then a loop of additions into a fixed array, with no search, no sort and no
/// allocation; chapter 2 re-assembles every step and relies on it.
///
/// One position per block is enough because a node's three DOFs are free or prescribed
/// together (DirichletNodes prescribes all three), so the three free rows of node i are
/// consecutive in every column, and the three columns of node j have the same rows: entry
/// (3i + p, 3j + q) sits at first + q L_j + p, with L_j the length of node j's columns. That
/// is 16 ints per Tet4 and 100 per Tet10 (9 times fewer than one per entry).
class SparseAssembler {
public:
  /// Builds the pattern of K_ff and the scatter map for the elements of `elements` (#T by n).
  ///
  /// Each row lists the "DOF nodes" of one element, three DOFs each: for plain FEM the tet's
  /// nodes. A row may leave slots empty (-1; chapter 3's corners without enriched DOFs do); an
  /// element uses its leading slots up to its last non-empty one.
  ///
  /// The assembler keeps its own copies of what it needs, so temporaries are fine. The lifting
  /// uses dofs.prescribed until set_prescribed() says otherwise.
  /// @throws std::invalid_argument if a node has some DOFs free and others prescribed
  SparseAssembler(const TetMatrix& elements, const DofMap& dofs);

  /// The assembler of a cut that has grown, built from the one before it where the mesh did
  /// not change (chapter 7 makes one at every change of topology).
  ///
  /// Every row of `elements` starts with `mesh_slots` slots that hold the mesh's nodes, the same
  /// as the same row of `before`'s elements, and `dofs` frees and numbers their DOFs as
  /// `before`'s DofMap did; the DOF nodes in the other slots (enrichments) are numbered after
  /// every mesh node and may differ in every way. Free indices grow with the DOF, so in every
  /// column the mesh's rows come first, at the same offsets as before: the mesh's part of the
  /// pattern is copied from `before`, its part of the scatter map shifted by the columns' new
  /// starts, and only the rows that have other slots are walked. The result is the other
  /// constructor's (tests/chapter_07/test_incremental_rebuild.cpp), at a cost set by the enriched rows
  /// and a copy of the pattern's index arrays.
  /// @throws std::invalid_argument if a row's mesh slots or the mesh DOFs' numbering differ from
  ///         `before`'s, or another slot holds a DOF node numbered before a mesh node
  SparseAssembler(const SparseAssembler& before, const TetMatrix& elements, const DofMap& dofs, int mesh_slots);

  /// The prescribed values u_c (3 #DOF nodes; entries at free DOFs are ignored) that later
  /// add_element calls lift into the right-hand side. A quasi-static step lifts its prescribed
  /// increment in its first Newton iteration and nothing afterwards, and says so here.
  void set_prescribed(const Eigen::VectorXd& u_c) { prescribed_ = u_c; }

  /// The reduced matrix K_ff (num_free x num_free); its values are what was added since the
  /// last set_zero().
  const Eigen::SparseMatrix<double>& matrix() const { return K_; }

  /// Sets every stored value of K_ff to zero, keeping the pattern.
  void set_zero();

  /// The number of leading slots element t uses; its element matrix is 3 slots by 3 slots.
  int slots_used(Eigen::Index t) const { return slots_used_[static_cast<std::size_t>(t)]; }

  /// Adds the element matrix Ke (3 slots_used(t) square, node-major) of element t: its
  /// free-free blocks to K_ff, and -Ke(free, prescribed) u_c to rhs_free (the lifted
  /// right-hand side). Rows and columns of empty slots are ignored.
  template <int m>
  void add_element(Eigen::Index t, const Eigen::Matrix<double, m, m>& Ke, Eigen::VectorXd& rhs_free) {
    add_element_matrix(t, Ke, rhs_free);
  }

  /// The same for any matrix expression, e.g. the leading block of a fixed-size element matrix
  /// whose last slots are empty.
  template <class Derived>
  void add_element_matrix(Eigen::Index t, const Eigen::MatrixBase<Derived>& Ke, Eigen::VectorXd& rhs_free) {
    const int n = slots_used(t);
    assert(Ke.rows() == 3 * n && Ke.cols() == 3 * n);
    const int* first = block_first_.data() + block_offset_[static_cast<std::size_t>(t)];
    double* values = K_.valuePtr();
    for (int b = 0; b < n; ++b) {
      const int node_b = elements_(t, b);
      if (node_b < 0) continue; // an empty slot
      const int column_length = column_length_[static_cast<std::size_t>(node_b)];
      if (column_length < 0) {
        lift_prescribed_column(t, n, b, Ke, rhs_free);
        continue;
      }
      for (int a = 0; a < n; ++a) {
        const int position = first[b * n + a];
        if (position < 0) continue; // an empty or prescribed row
        for (int q = 0; q < 3; ++q)
          for (int p = 0; p < 3; ++p) values[position + q * column_length + p] += Ke(3 * a + p, 3 * b + q);
      }
    }
  }

  /// Number of stored entries (both triangles) of K_ff.
  Eigen::Index num_stored_entries() const { return K_.nonZeros(); }

private:
  /// A prescribed node b's columns move to the right-hand side: f_f -= K_fc u_c.
  template <class Derived>
  void lift_prescribed_column(Eigen::Index t, int n, int b, const Eigen::MatrixBase<Derived>& Ke, Eigen::VectorXd& rhs_free) const {
    const Eigen::Vector3d u_c = prescribed_.segment<3>(3 * elements_(t, b));
    if (u_c.isZero(0.0)) return;
    for (int a = 0; a < n; ++a) {
      const int node_a = elements_(t, a);
      if (node_a < 0 || column_length_[static_cast<std::size_t>(node_a)] < 0) continue;
      const int row = free_index_[static_cast<std::size_t>(3 * node_a)];
      rhs_free.segment<3>(row) -= Ke.template block<3, 3>(3 * a, 3 * b) * u_c;
    }
  }

  TetMatrix elements_;                    ///< the element rows (DOF nodes per slot, -1 for an empty slot)
  std::vector<int> free_index_;           ///< DofMap::free_index
  Eigen::VectorXd prescribed_;            ///< the u_c the lifting uses
  Eigen::SparseMatrix<double> K_;
  std::vector<int> column_length_;        ///< per DOF node, the length of its columns in K_ff, -1 if prescribed
  std::vector<int> slots_used_;           ///< per element, the leading slots it uses
  std::vector<std::size_t> block_offset_; ///< per element, where its blocks start in block_first_
  std::vector<int> block_first_;          ///< per element, slots^2 positions of the blocks' (0, 0) entries (column-major), -1 if not free-free
};

} // namespace kerf
