/// @file dof_map.hpp
/// @brief Which displacement DOFs are unknown and which are prescribed (Dirichlet by elimination).
#pragma once

#include <Eigen/Core>
#include <vector>

namespace kerf {

/// Prescribed displacement of a set of nodes: u(node) = displacement for every listed node.
struct DirichletNodes {
  std::vector<int> nodes;            ///< 0-based node indices
  Eigen::Vector3d displacement{0, 0, 0}; ///< prescribed displacement in m
};

/// The map from the 3#V displacement DOFs (node-major: DOF 3 v + p is component p of node v)
/// to the unknowns of the reduced system K_ff u_f = f_f - K_fc u_c.
///
/// Eliminating the prescribed DOFs (instead of a penalty or a row replacement) keeps K_ff
/// symmetric positive definite and of the right size, which is what CHOLMOD and CG need, and
/// keeps its condition number free of an arbitrary penalty factor.
struct DofMap {
  std::vector<int> free_index; ///< size 3#V: the unknown's index, or -1 for a prescribed DOF
  Eigen::VectorXd prescribed;  ///< size 3#V: the prescribed values (0 on free DOFs)
  int num_free = 0;            ///< number of unknowns

  /// The full displacement vector (3#V) from the unknowns u_f: prescribed values elsewhere.
  Eigen::VectorXd expand(const Eigen::VectorXd& u_free) const;
  /// The entries of a full vector (3#V) on the free DOFs.
  Eigen::VectorXd restrict_to_free(const Eigen::VectorXd& full) const;
};

/// Builds the map for `num_nodes` nodes; a node listed in several conditions takes the
/// displacement of the last one, as a scene file reads from top to bottom.
DofMap make_dof_map(Eigen::Index num_nodes, const std::vector<DirichletNodes>& conditions);

} // namespace kerf
