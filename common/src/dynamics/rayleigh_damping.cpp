#include "kerf/dynamics/rayleigh_damping.hpp"

#include <stdexcept>

namespace kerf {

Eigen::SparseMatrix<double> rayleigh_damping(const Eigen::SparseMatrix<double>& M, const Eigen::SparseMatrix<double>& K,
                                             double alpha, double beta) {
  if (M.rows() != K.rows() || M.cols() != K.cols())
    throw std::invalid_argument("rayleigh_damping: M and K differ in size");
  Eigen::SparseMatrix<double> C = alpha * M + beta * K;
  C.makeCompressed();
  return C;
}

} // namespace kerf
