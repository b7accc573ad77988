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
/// tet, Schoch et al. section 3.6). We compute it once, and with it, for every element entry,
/// the position of that entry in the matrix's value array: the scatter map. Re-assembling is
/// then a loop of additions into a fixed array, with no search, no sort and no allocation;
/// chapter 2 re-assembles every step and relies on it.
class SparseAssembler {
public:
  /// Builds the pattern of K_ff and the scatter map for the elements of `tets` (#T by n).
  ///
  /// Each row lists the "DOF nodes" of one element, three DOFs each. For plain FEM these are
  /// the tet's nodes. Chapter 3's XFEM elements list their 4 nodes and then the 4 enriched DOF
  /// nodes (Paper 000 eq. 74), and a node that is not enriched leaves its slot empty: -1. An
  /// element uses the leading slots up to its last non-empty one; a row whose enriched slots
  /// are all empty is assembled as a plain 12x12 element.
  SparseAssembler(const TetMatrix& tets, const DofMap& dofs);

  /// The reduced matrix K_ff (num_free x num_free); its values are what was added since the
  /// last set_zero().
  const Eigen::SparseMatrix<double>& matrix() const { return K_; }

  /// Sets every stored value of K_ff to zero, keeping the pattern.
  void set_zero();

  /// The number of leading slots element t uses; its element matrix is 3 slots by 3 slots.
  int slots_used(Eigen::Index t) const { return slots_used_[static_cast<std::size_t>(t)]; }

  /// Adds the element matrix Ke (3 slots_used(t) square, node-major) of element t: its
  /// free-free entries to K_ff, and -Ke(free, prescribed) u_prescribed to rhs_free (the lifted
  /// right-hand side). Rows and columns of empty slots are ignored.
  template <int m>
  void add_element(Eigen::Index t, const Eigen::Matrix<double, m, m>& Ke, Eigen::VectorXd& rhs_free) {
    add_element_matrix(t, Ke, rhs_free);
  }

  /// The same for any matrix expression, e.g. the leading block of a fixed-size XFEM element
  /// matrix whose last slots are empty.
  template <class Derived>
  void add_element_matrix(Eigen::Index t, const Eigen::MatrixBase<Derived>& Ke, Eigen::VectorXd& rhs_free) {
    const int m = static_cast<int>(Ke.rows());
    assert(m == 3 * slots_used(t) && Ke.cols() == m);
    const int* scatter = scatter_.data() + scatter_offset_[static_cast<std::size_t>(t)];
    double* values = K_.valuePtr();
    for (int c = 0; c < m; ++c) {
      if (tets_(t, c / 3) < 0) continue; // an empty slot
      const int global_col = 3 * tets_(t, c / 3) + c % 3;
      if (dofs_.free_index[static_cast<std::size_t>(global_col)] < 0) {
        // A prescribed column moves to the right-hand side: f_f -= K_fc u_c.
        const double u_c = dofs_.prescribed[global_col];
        if (u_c != 0.0)
          for (int r = 0; r < m; ++r) {
            if (tets_(t, r / 3) < 0) continue;
            const int free_row = dofs_.free_index[static_cast<std::size_t>(3 * tets_(t, r / 3) + r % 3)];
            if (free_row >= 0) rhs_free[free_row] -= Ke(r, c) * u_c;
          }
        continue;
      }
      for (int r = 0; r < m; ++r)
        if (scatter[c * m + r] >= 0) values[scatter[c * m + r]] += Ke(r, c);
    }
  }

  /// Number of stored entries (both triangles) of K_ff.
  Eigen::Index num_stored_entries() const { return K_.nonZeros(); }

private:
  const TetMatrix& tets_;
  const DofMap& dofs_;
  Eigen::SparseMatrix<double> K_;
  std::vector<int> slots_used_;          ///< per element, the leading slots it uses
  std::vector<std::size_t> scatter_offset_; ///< per element, where its block of scatter_ starts
  std::vector<int> scatter_; ///< per element, (3 slots)^2 positions in K_.valuePtr() (column-major), -1 if not free-free
};

} // namespace kerf
