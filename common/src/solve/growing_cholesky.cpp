#include "kerf/solve/growing_cholesky.hpp"

#include <cstring>
#include <functional>
#include <stdexcept>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace kerf {

namespace {

// A column's rows and values as bytes: two columns are the same exactly when these are.
std::string column_key(const Eigen::SparseMatrix<double>& A, Eigen::Index j) {
  const Eigen::Index begin = A.outerIndexPtr()[j], end = A.outerIndexPtr()[j + 1];
  std::string key(static_cast<std::size_t>(end - begin) * (sizeof(int) + sizeof(double)), '\0');
  std::memcpy(key.data(), A.innerIndexPtr() + begin, static_cast<std::size_t>(end - begin) * sizeof(int));
  std::memcpy(key.data() + static_cast<std::size_t>(end - begin) * sizeof(int), A.valuePtr() + begin,
              static_cast<std::size_t>(end - begin) * sizeof(double));
  return key;
}

// a_i^T y for column i of A and a dense y.
double column_dot(const Eigen::SparseMatrix<double>& A, Eigen::Index i, const Eigen::VectorXd& y) {
  double sum = 0.0;
  for (Eigen::SparseMatrix<double>::InnerIterator it(A, i); it; ++it) sum += it.value() * y[it.index()];
  return sum;
}

} // namespace

GrowingCholesky::GrowingCholesky(const Eigen::SparseMatrix<double>& A_ss)
    : leading_(A_ss), factor_(std::make_unique<CholmodSolver>("nested-dissection")), A_se_(A_ss.rows(), 0) {
  factor_->analyze_pattern(leading_);
  factor_->factorize(leading_);
}

void GrowingCholesky::set_trailing(const Eigen::SparseMatrix<double>& A_se, const Eigen::SparseMatrix<double>& A_ee) {
  if (A_se.rows() != leading_.rows() || A_se.cols() != A_ee.rows() || A_ee.rows() != A_ee.cols())
    throw std::invalid_argument("GrowingCholesky::set_trailing: block sizes do not match");
  Eigen::SparseMatrix<double> columns = A_se;
  columns.makeCompressed();
  const Eigen::Index k = columns.cols();
  // Which new columns were there before: their products with each other are kept.
  std::unordered_map<std::string, Eigen::Index> before;
  for (Eigen::Index j = 0; j < A_se_.cols(); ++j) before.emplace(column_key(A_se_, j), j);
  std::vector<Eigen::Index> old_index(static_cast<std::size_t>(k), -1), changed;
  for (Eigen::Index j = 0; j < k; ++j) {
    const auto found = before.find(column_key(columns, j));
    if (found != before.end()) old_index[static_cast<std::size_t>(j)] = found->second;
    else changed.push_back(j);
  }
  kept_columns_ = k - static_cast<Eigen::Index>(changed.size());
  // One solve for all the new columns: Y = A_ss^{-1} [a_j, j changed].
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(leading_.rows(), static_cast<Eigen::Index>(changed.size()));
  for (std::size_t c = 0; c < changed.size(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(columns, changed[c]); it; ++it) B(it.index(), static_cast<Eigen::Index>(c)) = it.value();
  Eigen::MatrixXd Y;
  if (!changed.empty()) factor_->solve_columns(B, Y);
  // (8.7): the products, kept or new, then S and its factor.
  Eigen::MatrixXd products(k, k);
  for (Eigen::Index j = 0; j < k; ++j)
    for (Eigen::Index i = 0; i < k; ++i) {
      const Eigen::Index old_i = old_index[static_cast<std::size_t>(i)], old_j = old_index[static_cast<std::size_t>(j)];
      if (old_i >= 0 && old_j >= 0) products(i, j) = products_(old_i, old_j);
    }
  for (std::size_t c = 0; c < changed.size(); ++c) {
    const Eigen::Index j = changed[c];
    const Eigen::VectorXd y = Y.col(static_cast<Eigen::Index>(c));
    for (Eigen::Index i = 0; i < k; ++i) products(i, j) = products(j, i) = column_dot(columns, i, y);
  }
  schur_.compute(Eigen::MatrixXd(A_ee) - products);
  if (k > 0 && schur_.info() != Eigen::Success)
    throw std::runtime_error("GrowingCholesky: the trailing rows' Schur complement is not positive definite");
  A_se_ = std::move(columns);
  products_ = std::move(products);
}

void GrowingCholesky::solve(Eigen::MatrixXd& B) {
  const Eigen::Index n_s = leading_.rows(), k = A_se_.cols();
  if (B.rows() != n_s + k || B.cols() != 3) throw std::invalid_argument("GrowingCholesky::solve: expected rows x 3 right-hand sides");
  // (8.8).
  Eigen::MatrixXd y;
  factor_->solve_columns(B.topRows(n_s), y);
  if (k > 0) {
    const Eigen::MatrixXd x_e = schur_.solve(B.bottomRows(k) - A_se_.transpose() * y);
    Eigen::MatrixXd correction;
    factor_->solve_columns(A_se_ * x_e, correction);
    y -= correction;
    B.bottomRows(k) = x_e;
  }
  B.topRows(n_s) = y;
}

} // namespace kerf
