#include "kerf/solve/growing_cholesky.hpp"

#include <stdexcept>

namespace kerf {

GrowingCholesky::GrowingCholesky(const Eigen::SparseMatrix<double>& A_ss) : leading_(A_ss) {
  factor_.compute(leading_);
  if (factor_.info() != Eigen::Success)
    throw std::runtime_error("GrowingCholesky: the leading block is not positive definite");
  W_.resize(leading_.rows(), 0);
  S_factor_.resize(0, 0);
}

void GrowingCholesky::set_trailing(const Eigen::SparseMatrix<double>& A_se, const Eigen::SparseMatrix<double>& A_ee) {
  if (A_se.rows() != leading_.rows() || A_se.cols() != A_ee.rows() || A_ee.rows() != A_ee.cols())
    throw std::invalid_argument("GrowingCholesky::set_trailing: block sizes do not match");
  // (8.8): W = L^{-1} P A_se, a sparse triangular solve with a sparse right-hand side.
  W_ = factor_.permutationP() * A_se;
  factor_.matrixL().solveInPlace(W_);
  W_.prune(0.0);
  const Eigen::MatrixXd S = Eigen::MatrixXd(A_ee) - Eigen::MatrixXd(W_.transpose() * W_);
  Eigen::LLT<Eigen::MatrixXd> schur(S);
  if (schur.info() != Eigen::Success)
    throw std::runtime_error("GrowingCholesky: the trailing rows' Schur complement is not positive definite");
  S_factor_ = schur.matrixL();
}

namespace {

// Three right-hand sides side by side, so that each entry of a sparse factor, read once, serves
// all three: the solves read the factor once instead of once per column.
using Rows3 = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

// L z = b in place, L lower triangular in compressed columns, its diagonal first in each column.
void forward_substitute(const Eigen::SparseMatrix<double>& L, Rows3& z) {
  for (Eigen::Index j = 0; j < L.outerSize(); ++j) {
    Eigen::SparseMatrix<double>::InnerIterator it(L, j);
    z.row(j) /= it.value();
    const Eigen::RowVector3d z_j = z.row(j);
    for (++it; it; ++it) z.row(it.index()) -= it.value() * z_j;
  }
}

// L^T x = z in place.
void backward_substitute(const Eigen::SparseMatrix<double>& L, Rows3& x) {
  for (Eigen::Index j = L.outerSize(); j-- > 0;) {
    Eigen::SparseMatrix<double>::InnerIterator it(L, j);
    const double diagonal = it.value();
    Eigen::RowVector3d sum = x.row(j);
    for (++it; it; ++it) sum -= it.value() * x.row(it.index());
    x.row(j) = sum / diagonal;
  }
}

} // namespace

void GrowingCholesky::solve(Eigen::MatrixXd& B) const {
  const Eigen::Index n_s = leading_.rows(), k = S_factor_.rows();
  if (B.rows() != n_s + k || B.cols() != 3) throw std::invalid_argument("GrowingCholesky::solve: expected rows x 3 right-hand sides");
  const Eigen::SparseMatrix<double>& L = factor_.matrixL().nestedExpression();
  // Forward: z_s = L^{-1} P b_s, z_e = L_S^{-1} (b_e - W^T z_s).
  Rows3 z = factor_.permutationP() * B.topRows(n_s);
  forward_substitute(L, z);
  if (k > 0) {
    Eigen::MatrixXd z_e = B.bottomRows(k);
    for (Eigen::Index j = 0; j < k; ++j)
      for (Eigen::SparseMatrix<double>::InnerIterator it(W_, j); it; ++it) z_e.row(j) -= it.value() * z.row(it.index());
    S_factor_.triangularView<Eigen::Lower>().solveInPlace(z_e);
    // Backward: x_e = L_S^{-T} z_e, x_s = P^T L^{-T} (z_s - W x_e).
    S_factor_.triangularView<Eigen::Lower>().transpose().solveInPlace(z_e);
    for (Eigen::Index j = 0; j < k; ++j)
      for (Eigen::SparseMatrix<double>::InnerIterator it(W_, j); it; ++it) z.row(it.index()) -= it.value() * z_e.row(j);
    B.bottomRows(k) = z_e;
  }
  backward_substitute(L, z);
  B.topRows(n_s) = factor_.permutationPinv() * Eigen::MatrixXd(z);
}

} // namespace kerf
