#include "kerf/dynamics/bilateral_preconditioner.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace kerf {

Eigen::VectorXd koschier_preconditioner(const EnrichmentVolumes& volumes, Eigen::Index num_nodes) {
  const auto num_enrichments = static_cast<Eigen::Index>(volumes.enriched.size());
  Eigen::VectorXd t = Eigen::VectorXd::Ones(3 * (num_nodes + num_enrichments));
  for (Eigen::Index k = 0; k < num_enrichments; ++k) {
    const double v = volumes.fraction(k); // eq. 27
    if (!(v > 0.0))
      throw std::invalid_argument("koschier_preconditioner: enrichment " + std::to_string(k) +
                                  " acts on no volume (V_enr / V_supp = " + std::to_string(v) + "); constrain it by eq. 22 first");
    t.segment<3>(3 * (num_nodes + k)).setConstant(1.0 / std::sqrt(v)); // eq. 26 with v for V
  }
  return t;
}

Eigen::VectorXd jacobi_preconditioner(const Eigen::SparseMatrix<double>& A) {
  const Eigen::VectorXd diagonal = A.diagonal();
  for (Eigen::Index k = 0; k < diagonal.size(); ++k)
    if (!(diagonal[k] > 0.0))
      throw std::invalid_argument("jacobi_preconditioner: diagonal entry " + std::to_string(k) + " is not positive");
  return diagonal.cwiseSqrt().cwiseInverse();
}

Eigen::SparseMatrix<double> scale_bilaterally(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& t) {
  if (A.rows() != t.size() || A.cols() != t.size())
    throw std::invalid_argument("scale_bilaterally: T must have one entry per row and column of A");
  return (t.asDiagonal() * A * t.asDiagonal()).eval();
}

Eigen::VectorXd solve_bilaterally_preconditioned(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& c,
                                                 const Eigen::VectorXd& t, const SolverSettings& settings) {
  const Eigen::VectorXd y = solve_once(scale_bilaterally(A, t), t.cwiseProduct(c), settings); // eq. 24 (T^T = T)
  return t.cwiseProduct(y);                                                                  // eq. 25
}

} // namespace kerf
