#include "kerf/solve/symmetric_block_matrix.hpp"

#include <algorithm>
#include <stdexcept>

namespace kerf {

void SymmetricBlockMatrix::analyze_pattern(const Eigen::SparseMatrix<double>& A) {
  if (A.rows() != A.cols()) throw std::invalid_argument("SymmetricBlockMatrix: the matrix is not square");
  if (!A.isCompressed()) throw std::invalid_argument("SymmetricBlockMatrix: the matrix is not compressed");
  size_ = A.rows();
  const Eigen::Index blocks = (size_ + 2) / 3;
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();

  // Two passes over A's upper entries (i, j), i <= j, each in block (I, J) = (i / 3, j / 3).
  // Columns come in increasing order, so a block row I meets its block columns J in increasing
  // order too: a block is new to row I when J differs from the last J the row met. Every row
  // starts with its diagonal block, so the row's J starts at I.
  std::vector<int> last_column(static_cast<std::size_t>(blocks));
  for (Eigen::Index I = 0; I < blocks; ++I) last_column[static_cast<std::size_t>(I)] = static_cast<int>(I);
  // First pass: how many blocks each row has.
  row_start_.assign(static_cast<std::size_t>(blocks) + 1, 0);
  for (Eigen::Index I = 0; I < blocks; ++I) row_start_[static_cast<std::size_t>(I) + 1] = 1;
  for (Eigen::Index j = 0; j < size_; ++j) {
    const int J = static_cast<int>(j / 3);
    for (int k = outer[j]; k < outer[j + 1]; ++k) {
      if (inner[k] > j) continue;
      int& last = last_column[static_cast<std::size_t>(inner[k] / 3)];
      if (last != J) {
        last = J;
        ++row_start_[static_cast<std::size_t>(inner[k] / 3) + 1];
      }
    }
  }
  for (Eigen::Index I = 0; I < blocks; ++I) row_start_[static_cast<std::size_t>(I) + 1] += row_start_[static_cast<std::size_t>(I)];
  block_column_.assign(static_cast<std::size_t>(row_start_.back()), 0);
  values_.assign(9 * block_column_.size(), 0.0);

  // Second pass: the blocks' columns, and where each stored entry goes: entry (p, q) of block b
  // at 9 b + 3 p + q. `current` is the block row I is filling (its diagonal block first).
  std::vector<int> current(static_cast<std::size_t>(blocks));
  for (Eigen::Index I = 0; I < blocks; ++I) {
    const auto row = static_cast<std::size_t>(I);
    current[row] = row_start_[row];
    block_column_[static_cast<std::size_t>(row_start_[row])] = static_cast<int>(I);
  }
  target_.assign(static_cast<std::size_t>(A.nonZeros()), -1);
  for (Eigen::Index j = 0; j < size_; ++j) {
    const int J = static_cast<int>(j / 3);
    for (int k = outer[j]; k < outer[j + 1]; ++k) {
      const int i = inner[k];
      if (i > j) continue;
      const auto row = static_cast<std::size_t>(i / 3);
      int& block = current[row];
      if (block_column_[static_cast<std::size_t>(block)] != J) block_column_[static_cast<std::size_t>(++block)] = J;
      target_[static_cast<std::size_t>(k)] = 9 * block + 3 * (i % 3) + static_cast<int>(j % 3);
    }
  }
  pattern_outer_.assign(outer, outer + size_ + 1);
  pattern_inner_.assign(inner, inner + A.nonZeros());
}

bool SymmetricBlockMatrix::has_pattern_of(const Eigen::SparseMatrix<double>& A) const {
  if (A.rows() != size_ || A.cols() != size_ || !A.isCompressed()) return false;
  if (static_cast<std::size_t>(A.nonZeros()) != pattern_inner_.size()) return false;
  return std::equal(pattern_outer_.begin(), pattern_outer_.end(), A.outerIndexPtr()) &&
         std::equal(pattern_inner_.begin(), pattern_inner_.end(), A.innerIndexPtr());
}

void SymmetricBlockMatrix::set_values(const Eigen::SparseMatrix<double>& A) {
  if (static_cast<std::size_t>(A.nonZeros()) != target_.size())
    throw std::invalid_argument("SymmetricBlockMatrix: the matrix does not have the analysed pattern");
  std::fill(values_.begin(), values_.end(), 0.0);
  const double* value = A.valuePtr();
  for (std::size_t k = 0; k < target_.size(); ++k)
    if (target_[k] >= 0) values_[static_cast<std::size_t>(target_[k])] = value[k];
  // A diagonal block holds only its upper entries so far: its lower ones are their mirror.
  for (std::size_t I = 0; I + 1 < row_start_.size(); ++I) {
    double* D = &values_[9 * static_cast<std::size_t>(row_start_[I])];
    D[3] = D[1];
    D[6] = D[2];
    D[7] = D[5];
  }
}

void SymmetricBlockMatrix::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  if (x.size() != padded_size()) throw std::invalid_argument("SymmetricBlockMatrix: the vector does not have the padded size");
  y.setZero(padded_size());
  const double* X = x.data();
  double* Y = y.data();
  const Eigen::Index blocks = num_block_rows();
  for (Eigen::Index I = 0; I < blocks; ++I) {
    const double x0 = X[3 * I], x1 = X[3 * I + 1], x2 = X[3 * I + 2];
    int b = row_start_[static_cast<std::size_t>(I)];
    // The diagonal block: y_I += D x_I.
    const double* D = &values_[9 * static_cast<std::size_t>(b)];
    double y0 = D[0] * x0 + D[1] * x1 + D[2] * x2;
    double y1 = D[3] * x0 + D[4] * x1 + D[5] * x2;
    double y2 = D[6] * x0 + D[7] * x1 + D[8] * x2;
    // A block above the diagonal: y_I += B x_J, and by symmetry y_J += B^T x_I.
    for (++b; b < row_start_[static_cast<std::size_t>(I) + 1]; ++b) {
      const double* B = &values_[9 * static_cast<std::size_t>(b)];
      const Eigen::Index J = block_column_[static_cast<std::size_t>(b)];
      const double* xJ = X + 3 * J;
      double* yJ = Y + 3 * J;
      y0 += B[0] * xJ[0] + B[1] * xJ[1] + B[2] * xJ[2];
      y1 += B[3] * xJ[0] + B[4] * xJ[1] + B[5] * xJ[2];
      y2 += B[6] * xJ[0] + B[7] * xJ[1] + B[8] * xJ[2];
      yJ[0] += B[0] * x0 + B[3] * x1 + B[6] * x2;
      yJ[1] += B[1] * x0 + B[4] * x1 + B[7] * x2;
      yJ[2] += B[2] * x0 + B[5] * x1 + B[8] * x2;
    }
    Y[3 * I] += y0;
    Y[3 * I + 1] += y1;
    Y[3 * I + 2] += y2;
  }
  // The padding's rows and columns are zero: whatever x holds there, y is 0 there.
  for (Eigen::Index i = size_; i < padded_size(); ++i) y[i] = 0.0;
}

Eigen::VectorXd SymmetricBlockMatrix::diagonal() const {
  Eigen::VectorXd d = Eigen::VectorXd::Zero(padded_size());
  for (Eigen::Index I = 0; I < num_block_rows(); ++I) {
    const double* D = &values_[9 * static_cast<std::size_t>(row_start_[static_cast<std::size_t>(I)])];
    for (int p = 0; p < 3; ++p) d[3 * I + p] = D[4 * p];
  }
  for (Eigen::Index i = size_; i < padded_size(); ++i) d[i] = 0.0;
  return d;
}

} // namespace kerf
