#include "kerf/xfem/node_block_preconditioner.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <stdexcept>
#include <string>

namespace kerf {

Eigen::SparseMatrix<double> node_block_preconditioner(const Eigen::SparseMatrix<double>& A, const std::vector<int>& group) {
  const Eigen::Index n = A.rows();
  if (A.cols() != n || static_cast<Eigen::Index>(group.size()) != n)
    throw std::invalid_argument("node_block_preconditioner: A must be square with one group per row");
  if (n > 0 && *std::min_element(group.begin(), group.end()) < 0)
    throw std::invalid_argument("node_block_preconditioner: a group index is negative");
  const int groups = n > 0 ? *std::max_element(group.begin(), group.end()) + 1 : 0;
  std::vector<std::vector<Eigen::Index>> rows(static_cast<std::size_t>(groups));
  for (Eigen::Index i = 0; i < n; ++i) rows[static_cast<std::size_t>(group[static_cast<std::size_t>(i)])].push_back(i);
  std::vector<Eigen::Triplet<double>> entries;
  for (int g = 0; g < groups; ++g) {
    const std::vector<Eigen::Index>& r = rows[static_cast<std::size_t>(g)];
    if (r.empty()) continue;
    const auto m = static_cast<Eigen::Index>(r.size());
    Eigen::MatrixXd block(m, m);
    for (Eigen::Index a = 0; a < m; ++a)
      for (Eigen::Index b = 0; b < m; ++b) block(a, b) = A.coeff(r[static_cast<std::size_t>(a)], r[static_cast<std::size_t>(b)]);
    const Eigen::LLT<Eigen::MatrixXd> llt(block);
    if (llt.info() != Eigen::Success)
      throw std::invalid_argument("node_block_preconditioner: the diagonal block of node " + std::to_string(g) + " is not positive definite");
    // S_gg = L^-T: then S_gg^T A_gg S_gg = L^-1 L L^T L^-T = I.
    const Eigen::MatrixXd S = llt.matrixU().solve(Eigen::MatrixXd::Identity(m, m));
    for (Eigen::Index a = 0; a < m; ++a)
      for (Eigen::Index b = 0; b < m; ++b)
        if (S(a, b) != 0.0) entries.emplace_back(r[static_cast<std::size_t>(a)], r[static_cast<std::size_t>(b)], S(a, b));
  }
  Eigen::SparseMatrix<double> S(n, n);
  S.setFromTriplets(entries.begin(), entries.end());
  return S;
}

} // namespace kerf
