/// @file symmetric_block_matrix.hpp
/// @brief A symmetric matrix stored as the upper triangle of its 3x3 blocks, for fast products.
#pragma once

#include <Eigen/SparseCore>
#include <vector>

namespace kerf {

/// A symmetric sparse matrix A as the 3x3 blocks of its upper block triangle, stored block row by
/// block row (block compressed rows), to multiply vectors by: conjugate gradients spends nearly all
/// its time in y = A x, some 30 times a time step in chapters 6 and 7.
///
/// Why blocks: the unknowns come three to a node (x, y and z of one displacement), and every
/// node couples to another through a full 3x3 block (SparseAssembler). Eigen's compressed columns
/// read one row index per value; a block reads one index per 9 values, and its 3x3 product is
/// straight-line code the compiler keeps in registers. Why the upper triangle: A is symmetric, so
/// each block B_IJ above the diagonal gives both y_I += B_IJ x_J and y_J += B_IJ^T x_I, and the
/// matrix is read half as much. On the 10k-tet liver's step matrix (4818 unknowns, 195 678 stored
/// entries) a product takes a third to a half of the time of Eigen's selfadjointView<Upper>.
///
/// A is read as Eigen's `selfadjointView<Eigen::Upper>()` reads it: its entries with row <= column
/// define it, the others are ignored. A size that is not a multiple of 3 is padded with zero rows
/// and columns to one (the vectors multiplied have the padded size, padded_size()).
class SymmetricBlockMatrix {
public:
  /// The block pattern of A's upper triangle, and where each of its stored entries goes. Every
  /// diagonal block is stored, even where A has no entry in it.
  void analyze_pattern(const Eigen::SparseMatrix<double>& A);

  /// Whether A has the pattern analyze_pattern() last saw (same size, same stored positions).
  bool has_pattern_of(const Eigen::SparseMatrix<double>& A) const;

  /// Copies A's values into the blocks; A must have the analysed pattern (has_pattern_of).
  void set_values(const Eigen::SparseMatrix<double>& A);

  /// A's size n, and n rounded up to a multiple of 3.
  Eigen::Index size() const { return size_; }
  Eigen::Index padded_size() const { return 3 * num_block_rows(); }

  /// y = A x, for x of the padded size. Its padding meets only zero entries, so any finite values
  /// there leave y unchanged (a NaN or an infinity would not: 0 times it is NaN); y's padding is 0.
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;

  /// The diagonal of A, of the padded size (0 in the padding).
  Eigen::VectorXd diagonal() const;

private:
  Eigen::Index num_block_rows() const { return static_cast<Eigen::Index>(row_start_.size()) - 1; }

  Eigen::Index size_ = 0;
  std::vector<int> row_start_;       ///< per block row I, where its blocks start; the diagonal block first
  std::vector<int> block_column_;    ///< per block, its block column J >= I
  std::vector<double> values_;       ///< per block, 9 values, row-major
  std::vector<int> target_;          ///< per stored entry of A, its place in values_ (-1: below the diagonal)
  std::vector<int> pattern_outer_;   ///< A's column starts, to recognise its pattern
  std::vector<int> pattern_inner_;   ///< A's row indices, the same
};

} // namespace kerf
