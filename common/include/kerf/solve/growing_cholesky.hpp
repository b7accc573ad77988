/// @file growing_cholesky.hpp
/// @brief The Cholesky factor of a symmetric positive definite matrix that grows by rows and
///        columns while its leading block stays: factorise the leading block once, and each
///        time the trailing rows change, only their Schur complement.
#pragma once
#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

namespace kerf {

/// A = [A_ss A_se; A_es A_ee], A_ss fixed (n_s x n_s, sparse), the trailing block (k rows)
/// replaced at will. With P A_ss P^T = L L^T (a fill-reducing P), the factor of A is
///
///   [P 0; 0 I] A [P 0; 0 I]^T = [L 0; W^T L_S] [L^T W; 0 L_S^T],
///   W = L^{-1} P A_se,   L_S L_S^T = S = A_ee - W^T W                              (8.8)
///
/// so a change of the trailing rows costs k sparse triangular solves (W, whose columns are
/// sparse: a column of L^{-1} b is non-zero only on the paths of the elimination tree from b's
/// entries to the root) and a dense k x k Cholesky factorisation of S, not a new factorisation
/// of A_ss. In chapter 8 A_ss is the block of the mesh's nodes, which a cut does not change (the
/// volumes of a cut tet's pieces sum to the tet's), and the trailing rows are the enrichments'.
class GrowingCholesky {
public:
  /// Factorises A_ss (lower triangle read).
  /// @throws std::runtime_error if A_ss is not positive definite
  explicit GrowingCholesky(const Eigen::SparseMatrix<double>& A_ss);

  /// Sets the trailing block: A_se (n_s x k) and A_ee (k x k, both triangles), k >= 0.
  /// @throws std::runtime_error if the Schur complement S is not positive definite
  void set_trailing(const Eigen::SparseMatrix<double>& A_se, const Eigen::SparseMatrix<double>& A_ee);

  Eigen::Index leading_size() const { return leading_.rows(); }
  Eigen::Index trailing_size() const { return S_factor_.rows(); }
  /// The leading block as factorised.
  const Eigen::SparseMatrix<double>& leading_block() const { return leading_; }

  /// Solves A X = B for three right-hand sides (x, y and z), in place (rows: the leading
  /// unknowns, then the trailing ones).
  void solve(Eigen::MatrixXd& B) const;

private:
  Eigen::SparseMatrix<double> leading_;
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> factor_; // P A_ss P^T = L L^T
  Eigen::SparseMatrix<double> W_;                            // L^{-1} P A_se, n_s x k
  Eigen::MatrixXd S_factor_;                                 // L_S, lower triangular, k x k
};

} // namespace kerf
