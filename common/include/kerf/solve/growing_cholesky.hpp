/// @file growing_cholesky.hpp
/// @brief The solve of a symmetric positive definite matrix that grows by rows and columns
///        while its leading block stays: the leading block factorised once, the trailing rows
///        through their Schur complement, whose products are kept for the rows that did not
///        change.
#pragma once
#include "kerf/solve/cholmod_solver.hpp"

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <memory>

namespace kerf {

/// A = [A_ss A_se; A_es A_ee], A_ss fixed (n_s x n_s, sparse), the trailing block (k rows)
/// replaced at will. By block elimination,
///
///   S = A_ee - A_es A_ss^{-1} A_se = L_S L_S^T,                                   (8.7)
///   y = A_ss^{-1} b_s,   x_e = S^{-1} (b_e - A_es y),   x_s = y - A_ss^{-1} A_se x_e,   (8.8)
///
/// two solves with A_ss's factor (CHOLMOD's supernodal Cholesky, nested dissection) and one with
/// the dense k x k L_S. S's entries are the products a_i^T A_ss^{-1} a_j of the trailing columns
/// a_i of A_se plus A_ee's: when the trailing rows change, the products of two columns that are
/// the same as before are kept, and only the new or changed columns cost a solve each (all at
/// once: one pass over the factor). In chapter 8 A_ss is the block of the mesh's nodes, which a
/// cut does not change (the volumes of a cut tet's pieces sum to the tet's), and the trailing rows
/// are the enrichments': a cut that grows adds a few, and changes the few whose support it grew.
class GrowingCholesky {
public:
  /// Factorises A_ss (both triangles stored).
  /// @throws NotPositiveDefinite if A_ss is not positive definite
  explicit GrowingCholesky(const Eigen::SparseMatrix<double>& A_ss);

  /// Sets the trailing block: A_se (n_s x k) and A_ee (k x k, both triangles), k >= 0.
  /// @throws std::runtime_error if the Schur complement S is not positive definite
  void set_trailing(const Eigen::SparseMatrix<double>& A_se, const Eigen::SparseMatrix<double>& A_ee);

  Eigen::Index leading_size() const { return leading_.rows(); }
  Eigen::Index trailing_size() const { return A_se_.cols(); }
  /// The leading block as factorised.
  const Eigen::SparseMatrix<double>& leading_block() const { return leading_; }
  /// How many of the last set_trailing's columns were found among the ones before (their
  /// products with each other kept, no solve).
  Eigen::Index kept_columns() const { return kept_columns_; }

  /// Solves A X = B for three right-hand sides (x, y and z), in place (rows: the leading
  /// unknowns, then the trailing ones).
  void solve(Eigen::MatrixXd& B);

private:
  Eigen::SparseMatrix<double> leading_;
  std::unique_ptr<CholmodSolver> factor_; // of A_ss
  Eigen::SparseMatrix<double> A_se_;      // the trailing columns as last set
  Eigen::MatrixXd products_;              // a_i^T A_ss^{-1} a_j of those columns
  Eigen::LLT<Eigen::MatrixXd> schur_;     // S = L_S L_S^T
  Eigen::Index kept_columns_ = 0;
};

} // namespace kerf
