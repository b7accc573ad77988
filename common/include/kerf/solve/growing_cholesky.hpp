/// @file growing_cholesky.hpp
/// @brief The Cholesky factor of a symmetric positive definite matrix that grows by rows and
///        columns while its leading block stays: the leading block factorised once, the
///        trailing rows appended to its factor, and a solve that passes over the whole factor
///        once down and once up.
#pragma once

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <memory>

namespace kerf {

class CholmodSolver;

/// A = [A_ss A_se; A_es A_ee], A_ss fixed (n_s x n_s, sparse), the trailing block (k rows)
/// replaced at will. With A_ss = P^T L_ss L_ss^T P (CHOLMOD's supernodal factorisation, nested
/// dissection), A's Cholesky factor is A_ss's with k rows appended:
///
///   A = P_A^T [L_ss 0; L_es L_S] [L_ss 0; L_es L_S]^T P_A,   L_es^T = L_ss^{-1} P A_se,
///   S = A_ee - A_es A_ss^{-1} A_se = A_ee - L_es L_es^T = L_S L_S^T,                 (8.7)
///
/// P_A = diag(P, I). A solve is the two triangular sweeps over it,
///
///   L_ss z_s = P b_s,   L_S z_e = b_e - L_es z_s,   L_S^T x_e = z_e,
///   L_ss^T w = z_s - L_es^T x_e,   x_s = P^T w,                                     (8.8)
///
/// one pass down and one up CHOLMOD's L_ss (half of what a solve with A_ss costs), with the k
/// sparse rows of L_es and the dense k x k L_S between them. Row j of L_es is the sweep down of
/// column j of A_se alone: it is nonzero only on the rows of L_ss its entries reach (their paths to
/// the elimination tree's root), and stored sparse. When the trailing rows change, the rows of L_es
/// of columns that are the same as before are kept, with their products with each other in S; only
/// new or changed columns cost a sweep.
/// In chapter 8 A_ss is the block of the mesh's nodes, which a cut does not change (the volumes of
/// a cut tet's pieces sum to the tet's), and the trailing rows are the enrichments': a cut that
/// grows adds a few, and changes the few whose support it grew.
class GrowingCholesky {
public:
  /// Factorises A_ss (both triangles stored).
  /// @throws NotPositiveDefinite if A_ss is not positive definite
  explicit GrowingCholesky(const Eigen::SparseMatrix<double>& A_ss);
  ~GrowingCholesky();

  /// Sets the trailing block: A_se (n_s x k) and A_ee (k x k, both triangles), k >= 0.
  /// @throws std::runtime_error if the Schur complement S is not positive definite
  void set_trailing(const Eigen::SparseMatrix<double>& A_se, const Eigen::SparseMatrix<double>& A_ee);

  Eigen::Index leading_size() const { return leading_.rows(); }
  Eigen::Index trailing_size() const { return A_se_.cols(); }
  /// The leading block as factorised.
  const Eigen::SparseMatrix<double>& leading_block() const { return leading_; }
  /// How many of the last set_trailing's columns were found among the ones before (their rows of
  /// L_es and their products with each other kept, no sweep).
  Eigen::Index kept_columns() const { return kept_columns_; }

  /// Solves A X = B for three right-hand sides (x, y and z), in place (rows: the leading
  /// unknowns, then the trailing ones).
  void solve(Eigen::MatrixXd& B);

private:
  Eigen::SparseMatrix<double> leading_;
  std::unique_ptr<CholmodSolver> factor_;        // of A_ss
  Eigen::SparseMatrix<double> A_se_;             // the trailing columns as last set
  Eigen::SparseMatrix<double, Eigen::RowMajor> L_es_; // k x n_s
  Eigen::MatrixXd products_;                     // L_es L_es^T: a_i^T A_ss^{-1} a_j
  Eigen::LLT<Eigen::MatrixXd> schur_;            // S = L_S L_S^T
  Eigen::Index kept_columns_ = 0;
};

} // namespace kerf
