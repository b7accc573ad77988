#include "kerf/solve/cholmod_solver.hpp"

#include "kerf/solve/unknown_blocks.hpp"
#include "solve/solver_checks.hpp"

#include <cholmod.h>
#include <omp.h>

#include <stdexcept>
#include <vector>

namespace kerf {

namespace {

using solver_checks::not_positive_definite;

// CHOLMOD's supernodal factorisation (SuiteSparse 5, as Debian 12 ships it) runs some loops in
// OpenMP regions that ask for a fixed number of threads, 4, chosen when CHOLMOD was compiled,
// whatever OMP_NUM_THREADS says. On a machine with fewer cores those threads take turns on
// them, and each turn costs a context switch: on 2 cores we measured factorisations 1.5 to 4
// times slower than with one thread. With dynamic adjustment on, OpenMP gives a region no
// more threads than there are idle cores, nor more than OMP_NUM_THREADS. This guard turns it
// on for one call and restores the caller's setting afterwards.
class OpenMpThreadsAtMostCores {
public:
  OpenMpThreadsAtMostCores() : was_dynamic_(omp_get_dynamic()) { omp_set_dynamic(1); }
  ~OpenMpThreadsAtMostCores() { omp_set_dynamic(was_dynamic_); }
  OpenMpThreadsAtMostCores(const OpenMpThreadsAtMostCores&) = delete;
  OpenMpThreadsAtMostCores& operator=(const OpenMpThreadsAtMostCores&) = delete;

private:
  int was_dynamic_;
};

// CHOLMOD's view of a matrix in compressed columns (n x n, column j's rows at
// rows[column_start[j] .. column_start[j+1])), without a copy: CHOLMOD reads, never writes,
// a matrix it orders or factorises. `values` null means a pattern. stype -1 has CHOLMOD read
// the lower triangle only and take the matrix as symmetric, stype 1 the upper.
cholmod_sparse compressed_column_view(std::size_t n, std::size_t entries, const int* column_start, const int* rows,
                                      const double* values, int stype) {
  cholmod_sparse view{};
  view.nrow = view.ncol = n;
  view.nzmax = entries;
  view.p = const_cast<int*>(column_start);
  view.i = const_cast<int*>(rows);
  view.x = const_cast<double*>(values);
  view.stype = stype;
  view.itype = CHOLMOD_INT;
  view.xtype = values ? CHOLMOD_REAL : CHOLMOD_PATTERN;
  view.dtype = CHOLMOD_DOUBLE;
  view.sorted = 1;
  view.packed = 1;
  return view;
}

// An Eigen matrix with both triangles stored, compressed: its lower triangle is read.
cholmod_sparse view_lower_triangle(const Eigen::SparseMatrix<double>& A) {
  return compressed_column_view(static_cast<std::size_t>(A.rows()), static_cast<std::size_t>(A.nonZeros()),
                                A.outerIndexPtr(), A.innerIndexPtr(), A.valuePtr(), -1);
}

// The graph of the blocks of unknown_blocks: vertex k is block k, adjacent to the blocks of the
// rows of its first column (all its columns have the same rows). Stored as a full symmetric
// pattern in compressed columns.
struct BlockGraph {
  std::vector<int> column_start{0}, rows;

  // CHOLMOD's view of it, its upper triangle read.
  cholmod_sparse view() const {
    return compressed_column_view(column_start.size() - 1, rows.size(), column_start.data(), rows.data(), nullptr, 1);
  }
};

BlockGraph make_block_graph(const Eigen::SparseMatrix<double>& A, const std::vector<int>& starts) {
  const int blocks = static_cast<int>(starts.size()) - 1;
  std::vector<int> block_of(static_cast<std::size_t>(A.rows()));
  for (int k = 0; k < blocks; ++k)
    for (int j = starts[k]; j < starts[k + 1]; ++j) block_of[j] = k;
  BlockGraph graph;
  for (int k = 0; k < blocks; ++k) {
    // The rows of a column are sorted and the blocks are runs of consecutive indices, so the
    // rows' blocks come in order too: a block is new when it differs from the last one kept.
    const int j = starts[k];
    for (int q = A.outerIndexPtr()[j]; q < A.outerIndexPtr()[j + 1]; ++q) {
      const int block = block_of[A.innerIndexPtr()[q]];
      const bool first_in_column = graph.rows.size() == static_cast<std::size_t>(graph.column_start.back());
      if (first_in_column || graph.rows.back() != block) graph.rows.push_back(block);
    }
    graph.column_start.push_back(static_cast<int>(graph.rows.size()));
  }
  return graph;
}

// The fill-reducing order of the block graph, with the named method: block_order[i] is the
// block eliminated i-th.
std::vector<int> order_block_graph(const BlockGraph& graph, const std::string& ordering, cholmod_common& c) {
  cholmod_sparse view = graph.view();
  const std::size_t blocks = view.ncol;
  std::vector<int> block_order(blocks);
  bool ordered = false;
  if (ordering == "nested-dissection") {
    std::vector<int> component_parent(blocks), component_of(blocks);
    ordered = cholmod_nested_dissection(&view, nullptr, 0, block_order.data(), component_parent.data(), component_of.data(), &c) >= 0;
  } else if (ordering == "metis") {
    ordered = cholmod_metis(&view, nullptr, 0, 1, block_order.data(), &c) != 0;
  } else {
    ordered = cholmod_amd(&view, nullptr, 0, block_order.data(), &c) != 0;
  }
  if (!ordered) throw std::runtime_error("CHOLMOD could not order the matrix (status " + std::to_string(c.status) + ")");
  return block_order;
}

} // namespace

struct CholmodSolver::Cholmod {
  cholmod_common common{};
  cholmod_factor* factor = nullptr;
  cholmod_dense* solution = nullptr; // cholmod_solve2's output and workspace, reused by every solve
  cholmod_dense* halfway = nullptr;   // solve_down's and solve_up's result between their two systems
  cholmod_dense* workspace_y = nullptr;
  cholmod_dense* workspace_e = nullptr;
  bool factorised = false; // whether `factor` holds the numeric factor of the last factorize

  Cholmod() {
    cholmod_start(&common);
    common.print = 0; // a failed factorisation is reported by an exception, not on stderr
    common.supernodal = CHOLMOD_SUPERNODAL;
  }
  ~Cholmod() {
    free_factor();
    cholmod_free_dense(&solution, &common);
    cholmod_free_dense(&halfway, &common);
    cholmod_free_dense(&workspace_y, &common);
    cholmod_free_dense(&workspace_e, &common);
    cholmod_finish(&common);
  }
  Cholmod(const Cholmod&) = delete;
  Cholmod& operator=(const Cholmod&) = delete;
  void free_factor() {
    if (factor) cholmod_free_factor(&factor, &common);
    factorised = false;
  }
};

CholmodSolver::CholmodSolver(const std::string& ordering) : cholmod_(std::make_unique<Cholmod>()), ordering_(ordering) {
  if (!is_cholmod_ordering(ordering))
    throw std::invalid_argument("unknown ordering '" + ordering + "' (expected nested-dissection, metis, amd or cholmod)");
}

CholmodSolver::~CholmodSolver() = default;

void CholmodSolver::analyze_pattern(const Eigen::SparseMatrix<double>& A_in) {
  if (A_in.rows() != A_in.cols()) throw std::invalid_argument("CholmodSolver: the matrix is not square");
  Eigen::SparseMatrix<double> compressed;
  const Eigen::SparseMatrix<double>& A = A_in.isCompressed() ? A_in : (compressed = A_in);
  cholmod_common& c = cholmod_->common;
  cholmod_->free_factor();
  cholmod_sparse A_view = view_lower_triangle(A);
  const int n = static_cast<int>(A.rows());

  if (ordering_ == "cholmod") {
    c.nmethods = 0; // CHOLMOD's default strategy
    cholmod_->factor = cholmod_analyze(&A_view, &c);
    statistics_.ordered_vertices = n;
  } else {
    const std::vector<int> starts = unknown_blocks(A);
    const BlockGraph graph = make_block_graph(A, starts);
    const std::vector<int> block_order = order_block_graph(graph, ordering_, c);
    // Each block's unknowns, in their order, where the block falls in the block order.
    std::vector<int> permutation;
    permutation.reserve(static_cast<std::size_t>(n));
    for (int k : block_order)
      for (int j = starts[k]; j < starts[k + 1]; ++j) permutation.push_back(j);
    c.nmethods = 1;
    c.method[0].ordering = CHOLMOD_GIVEN;
    c.postorder = 1; // CHOLMOD reorders the elimination tree for bigger supernodes; the fill stays
    cholmod_->factor = cholmod_analyze_p(&A_view, permutation.data(), nullptr, 0, &c);
    statistics_.ordered_vertices = static_cast<int>(block_order.size());
  }
  if (!cholmod_->factor) throw std::runtime_error("CHOLMOD's analysis failed (status " + std::to_string(c.status) + ")");
  statistics_.factor_entries = c.lnz;
  statistics_.factorisation_flops = c.fl;
}

void CholmodSolver::factorize(const Eigen::SparseMatrix<double>& A_in) {
  if (!cholmod_->factor) throw std::logic_error("CholmodSolver::factorize before analyze_pattern");
  if (static_cast<std::size_t>(A_in.rows()) != cholmod_->factor->n || A_in.rows() != A_in.cols())
    throw std::invalid_argument("CholmodSolver::factorize: the matrix does not have the analysed size");
  Eigen::SparseMatrix<double> compressed;
  const Eigen::SparseMatrix<double>& A = A_in.isCompressed() ? A_in : (compressed = A_in);
  cholmod_sparse A_view = view_lower_triangle(A);
  cholmod_common& c = cholmod_->common;
  cholmod_->factorised = false;
  {
    const OpenMpThreadsAtMostCores threads;
    cholmod_factorize(&A_view, cholmod_->factor, &c);
  }
  // A non-positive pivot stops the factorisation at column `minor`: the matrix is not positive
  // definite. Any other failure (out of memory) is an ordinary error.
  if (c.status == CHOLMOD_NOT_POSDEF || cholmod_->factor->minor < cholmod_->factor->n)
    throw NotPositiveDefinite(not_positive_definite);
  if (c.status < CHOLMOD_OK) throw std::runtime_error("CHOLMOD's factorisation failed (status " + std::to_string(c.status) + ")");
  cholmod_->factorised = true;
  ++factorisations_;
}

void CholmodSolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  Eigen::MatrixXd X;
  solve_columns(b, X);
  x = X.col(0);
}

namespace {

// CHOLMOD's view of a dense matrix, without a copy (CHOLMOD reads it, never writes it).
cholmod_dense dense_view(const Eigen::MatrixXd& B) {
  cholmod_dense view{};
  view.nrow = view.d = static_cast<std::size_t>(B.rows());
  view.ncol = static_cast<std::size_t>(B.cols());
  view.nzmax = view.nrow * view.ncol;
  view.x = const_cast<double*>(B.data());
  view.xtype = CHOLMOD_REAL;
  view.dtype = CHOLMOD_DOUBLE;
  return view;
}

} // namespace

void CholmodSolver::solve_system(int system, const Eigen::MatrixXd& B, bool halfway) {
  if (!cholmod_->factorised)
    throw std::logic_error("CholmodSolver::solve before factorize");
  if (static_cast<std::size_t>(B.rows()) != cholmod_->factor->n)
    throw std::invalid_argument("CholmodSolver::solve: the right-hand side does not have the matrix's size");
  solver_checks::require_finite_right_hand_side(B);
  cholmod_dense b_view = dense_view(B);
  if (!cholmod_solve2(system, cholmod_->factor, &b_view, nullptr, halfway ? &cholmod_->halfway : &cholmod_->solution, nullptr,
                      &cholmod_->workspace_y, &cholmod_->workspace_e, &cholmod_->common))
    throw std::runtime_error("CHOLMOD's solve failed (status " + std::to_string(cholmod_->common.status) + ")");
}

namespace {

// X from CHOLMOD's result; a factor that is not positive definite shows as a non-finite entry.
void copy_out(const cholmod_dense* X_cholmod, Eigen::Index rows, Eigen::Index cols, Eigen::MatrixXd& X) {
  X = Eigen::Map<const Eigen::MatrixXd>(static_cast<const double*>(X_cholmod->x), rows, cols);
  if (!X.allFinite()) throw NotPositiveDefinite(not_positive_definite);
}

} // namespace

void CholmodSolver::solve_columns(const Eigen::MatrixXd& B, Eigen::MatrixXd& X) {
  solve_system(CHOLMOD_A, B, false);
  copy_out(cholmod_->solution, B.rows(), B.cols(), X);
}

void CholmodSolver::solve_down(const Eigen::MatrixXd& B, Eigen::MatrixXd& Z) {
  solve_system(CHOLMOD_P, B, true);
  const Eigen::Map<const Eigen::MatrixXd> PB(static_cast<const double*>(cholmod_->halfway->x), B.rows(), B.cols());
  solve_system(CHOLMOD_L, PB, false);
  copy_out(cholmod_->solution, B.rows(), B.cols(), Z);
}

void CholmodSolver::solve_up(const Eigen::MatrixXd& Z, Eigen::MatrixXd& X) {
  solve_system(CHOLMOD_Lt, Z, true);
  const Eigen::Map<const Eigen::MatrixXd> LtZ(static_cast<const double*>(cholmod_->halfway->x), Z.rows(), Z.cols());
  solve_system(CHOLMOD_Pt, LtZ, false);
  copy_out(cholmod_->solution, Z.rows(), Z.cols(), X);
}

} // namespace kerf
