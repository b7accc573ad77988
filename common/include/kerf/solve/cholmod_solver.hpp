/// @file cholmod_solver.hpp
/// @brief CHOLMOD's supernodal Cholesky factorisation, with the fill-reducing ordering
/// computed on the mesh's nodes.
#pragma once

#include "kerf/solve/cholmod_ordering.hpp"
#include "kerf/solve/linear_solver.hpp"

#include <memory>
#include <string>

namespace kerf {

/// What the last analysis found and cost (CHOLMOD's own counts, before supernodal relaxation).
struct CholmodStatistics {
  double factor_entries = 0.0;     ///< nonzeros of the factor L
  double factorisation_flops = 0.0; ///< floating-point operations of one numeric factorisation
  int ordered_vertices = 0;        ///< vertices of the graph the ordering saw: blocks, or unknowns
};

/// A x = b by a supernodal Cholesky factorisation A = P^T L L^T P (SuiteSparse CHOLMOD).
///
/// The cost of the factorisation is set by the fill-reducing permutation P. Which one is the
/// `ordering` (SolverSettings::ordering):
/// - "nested-dissection" (the default): CHOLMOD's nested dissection (METIS bisections, the
///   pieces ordered by constrained minimum degree), computed on the graph of the blocks of
///   kerf::unknown_blocks, the mesh's nodes, and expanded to their unknowns;
/// - "metis", "amd": METIS's nested dissection or approximate minimum degree alone, on the
///   same node graph;
/// - "cholmod": CHOLMOD's own choice on the graph of the unknowns (it tries AMD, and METIS
///   when AMD's factor has many entries per entry of A), what Kerf did before.
/// On the chapter 1 beam the node graph is a third the size and the ordering a third the cost;
/// the benchmark (bench_linear_fem) compares the four.
class CholmodSolver final : public LinearSolver {
public:
  explicit CholmodSolver(const std::string& ordering = "nested-dissection");
  ~CholmodSolver() override;
  CholmodSolver(const CholmodSolver&) = delete;
  CholmodSolver& operator=(const CholmodSolver&) = delete;

  std::string name() const override { return "cholmod"; }
  void analyze_pattern(const Eigen::SparseMatrix<double>& A) override;
  void factorize(const Eigen::SparseMatrix<double>& A) override;
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override;
  /// A X = B for several right-hand sides at once (one pass over the factor for all of them).
  void solve_columns(const Eigen::MatrixXd& B, Eigen::MatrixXd& X);
  int factorisations() const override { return factorisations_; }
  /// The two halves of solve_columns, for a solver that puts rows of its own between them
  /// (growing_cholesky.hpp), with A = P^T L L^T P: Z = L^{-1} P B, the sweep down the factor, and
  /// X = P^T L^{-T} Z, the sweep up.
  void solve_down(const Eigen::MatrixXd& B, Eigen::MatrixXd& Z);
  void solve_up(const Eigen::MatrixXd& Z, Eigen::MatrixXd& X);

  /// The counts of the last analyze_pattern.
  const CholmodStatistics& statistics() const { return statistics_; }

private:
  struct Cholmod; ///< CHOLMOD's workspace and factor; cholmod.h stays out of this header
  // cholmod_solve2 of `system` (a CHOLMOD_ constant) for B, into Cholmod::solution or, for the
  // first of two systems in a row, Cholmod::halfway; checks B as solve_columns does.
  void solve_system(int system, const Eigen::MatrixXd& B, bool halfway);
  std::unique_ptr<Cholmod> cholmod_;
  std::string ordering_;
  CholmodStatistics statistics_;
  int factorisations_ = 0;
};

} // namespace kerf
