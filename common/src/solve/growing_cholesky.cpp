#include "kerf/solve/growing_cholesky.hpp"

#include "kerf/solve/cholmod_solver.hpp"

#include <cstring>
#include <stdexcept>
#include <string>
#include <unordered_map>

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

} // namespace

GrowingCholesky::GrowingCholesky(const Eigen::SparseMatrix<double>& A_ss)
    : leading_(A_ss), factor_(std::make_unique<CholmodSolver>("nested-dissection")), A_se_(A_ss.rows(), 0), L_es_(0, A_ss.rows()) {
  factor_->analyze_pattern(leading_);
  factor_->factorize(leading_);
}

GrowingCholesky::~GrowingCholesky() = default;

void GrowingCholesky::set_trailing(const Eigen::SparseMatrix<double>& A_se, const Eigen::SparseMatrix<double>& A_ee) {
  if (A_se.rows() != leading_.rows() || A_se.cols() != A_ee.rows() || A_ee.rows() != A_ee.cols())
    throw std::invalid_argument("GrowingCholesky::set_trailing: block sizes do not match");
  Eigen::SparseMatrix<double> columns = A_se;
  columns.makeCompressed();
  const Eigen::Index k = columns.cols(), n_s = leading_.rows();
  // Which new columns were there before: their rows of L_es, and their products with each
  // other, are kept.
  std::unordered_map<std::string, Eigen::Index> before;
  for (Eigen::Index j = 0; j < A_se_.cols(); ++j) before.emplace(column_key(A_se_, j), j);
  std::vector<Eigen::Index> old_index(static_cast<std::size_t>(k), -1);
  std::vector<Eigen::Index> changed;
  for (Eigen::Index j = 0; j < k; ++j) {
    const auto found = before.find(column_key(columns, j));
    if (found != before.end()) old_index[static_cast<std::size_t>(j)] = found->second;
    else changed.push_back(j);
  }
  // The rows of L_es: kept, or the sweep down of the new columns, all in one pass. A row is zero
  // exactly where its column's entries do not reach; only its nonzeros are stored.
  Eigen::MatrixXd new_columns = Eigen::MatrixXd::Zero(n_s, static_cast<Eigen::Index>(changed.size())), swept;
  for (std::size_t c = 0; c < changed.size(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(columns, changed[c]); it; ++it) new_columns(it.index(), static_cast<Eigen::Index>(c)) = it.value();
  if (!changed.empty()) factor_->solve_down(new_columns, swept);
  std::vector<Eigen::Triplet<double>> entries;
  for (Eigen::Index j = 0, c = 0; j < k; ++j) {
    const Eigen::Index old_j = old_index[static_cast<std::size_t>(j)];
    if (old_j >= 0) {
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(L_es_, old_j); it; ++it) entries.emplace_back(j, it.index(), it.value());
    } else {
      for (Eigen::Index r = 0; r < n_s; ++r)
        if (swept(r, c) != 0.0) entries.emplace_back(j, r, swept(r, c));
      ++c;
    }
  }
  kept_columns_ = k - static_cast<Eigen::Index>(changed.size());
  Eigen::SparseMatrix<double, Eigen::RowMajor> L_es(k, n_s);
  L_es.setFromTriplets(entries.begin(), entries.end());
  // (8.7): the products L_es L_es^T, kept or new, then S and its factor.
  Eigen::MatrixXd products(k, k);
  for (Eigen::Index j = 0; j < k; ++j)
    for (Eigen::Index i = 0; i < k; ++i) {
      const Eigen::Index old_i = old_index[static_cast<std::size_t>(i)], old_j = old_index[static_cast<std::size_t>(j)];
      if (old_i >= 0 && old_j >= 0) products(i, j) = products_(old_i, old_j);
    }
  // A new row's products with every row: L_es times its sweep, which is that row densely.
  const Eigen::MatrixXd with_new = changed.empty() ? Eigen::MatrixXd(k, 0) : Eigen::MatrixXd(L_es * swept);
  for (std::size_t c = 0; c < changed.size(); ++c)
    for (Eigen::Index i = 0; i < k; ++i)
      products(i, changed[c]) = products(changed[c], i) = with_new(i, static_cast<Eigen::Index>(c));
  schur_.compute(Eigen::MatrixXd(A_ee) - products);
  if (k > 0 && schur_.info() != Eigen::Success)
    throw std::runtime_error("GrowingCholesky: the trailing rows' Schur complement is not positive definite");
  A_se_ = std::move(columns);
  L_es_ = std::move(L_es);
  products_ = std::move(products);
}

void GrowingCholesky::solve(Eigen::MatrixXd& B) {
  const Eigen::Index n_s = leading_.rows(), k = A_se_.cols();
  if (B.rows() != n_s + k || B.cols() != 3) throw std::invalid_argument("GrowingCholesky::solve: expected rows x 3 right-hand sides");
  // (8.8): down L_ss, across L_es and L_S, up L_ss.
  Eigen::MatrixXd z;
  factor_->solve_down(B.topRows(n_s), z);
  if (k > 0) {
    // b_e - L_es z_s and z_s - L_es^T x_e row by row of L_es, the three right-hand sides of an
    // entry together (Eigen's products take them one at a time).
    const int* start = L_es_.outerIndexPtr();
    const int* column = L_es_.innerIndexPtr();
    const double* value = L_es_.valuePtr();
    double* z_x = z.col(0).data();
    double* z_y = z.col(1).data();
    double* z_z = z.col(2).data();
    Eigen::MatrixXd x_e = B.bottomRows(k);
    for (Eigen::Index j = 0; j < k; ++j) {
      double sum_x = 0.0, sum_y = 0.0, sum_z = 0.0;
      for (int q = start[j]; q < start[j + 1]; ++q) {
        const int i = column[q];
        sum_x += value[q] * z_x[i], sum_y += value[q] * z_y[i], sum_z += value[q] * z_z[i];
      }
      x_e(j, 0) -= sum_x, x_e(j, 1) -= sum_y, x_e(j, 2) -= sum_z;
    }
    schur_.matrixL().solveInPlace(x_e);
    schur_.matrixU().solveInPlace(x_e);
    for (Eigen::Index j = 0; j < k; ++j) {
      const double x = x_e(j, 0), y = x_e(j, 1), w = x_e(j, 2);
      for (int q = start[j]; q < start[j + 1]; ++q) {
        const int i = column[q];
        z_x[i] -= value[q] * x, z_y[i] -= value[q] * y, z_z[i] -= value[q] * w;
      }
    }
    B.bottomRows(k) = x_e;
  }
  Eigen::MatrixXd x_s;
  factor_->solve_up(z, x_s);
  B.topRows(n_s) = x_s;
}

} // namespace kerf
