/// @file unknown_blocks.hpp
/// @brief The unknowns that share a node: runs of columns with the same sparsity pattern.
#pragma once

#include <Eigen/SparseCore>
#include <vector>

namespace kerf {

/// Splits the columns of a sparse matrix with both triangles stored into blocks of consecutive
/// columns that have exactly the same rows.
///
/// In a stiffness matrix numbered node by node, the free displacement components of one node
/// couple to the same unknowns, so their columns are identical in pattern: a block is a node
/// (two nodes with the same neighbourhood may share one). A fill-reducing ordering of the
/// block graph, three times smaller than the graph of the unknowns, is as good and cheaper to
/// compute (kerf::CholmodSolver). Returns the first column of every block and, last, the number
/// of columns: block k is the columns [starts[k], starts[k+1]).
std::vector<int> unknown_blocks(const Eigen::SparseMatrix<double>& A);

} // namespace kerf
