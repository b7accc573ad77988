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

void GrowingCholesky::solve(Eigen::MatrixXd& B) const {
  const Eigen::Index n_s = leading_.rows(), k = S_factor_.rows();
  if (B.rows() != n_s + k) throw std::invalid_argument("GrowingCholesky::solve: wrong number of rows");
  // Forward: z_s = L^{-1} P b_s, z_e = L_S^{-1} (b_e - W^T z_s).
  Eigen::MatrixXd z = factor_.permutationP() * B.topRows(n_s);
  factor_.matrixL().solveInPlace(z);
  if (k > 0) {
    Eigen::MatrixXd z_e = B.bottomRows(k) - W_.transpose() * z;
    S_factor_.triangularView<Eigen::Lower>().solveInPlace(z_e);
    // Backward: x_e = L_S^{-T} z_e, x_s = P^T L^{-T} (z_s - W x_e).
    S_factor_.triangularView<Eigen::Lower>().transpose().solveInPlace(z_e);
    z -= W_ * z_e;
    B.bottomRows(k) = z_e;
  }
  factor_.matrixU().solveInPlace(z);
  B.topRows(n_s) = factor_.permutationPinv() * z;
}

} // namespace kerf
