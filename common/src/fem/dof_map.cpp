#include "kerf/fem/dof_map.hpp"

#include <stdexcept>

namespace kerf {

Eigen::VectorXd DofMap::expand(const Eigen::VectorXd& u_free) const {
  Eigen::VectorXd u = prescribed;
  for (std::size_t d = 0; d < free_index.size(); ++d)
    if (free_index[d] >= 0) u[static_cast<Eigen::Index>(d)] = u_free[free_index[d]];
  return u;
}

Eigen::VectorXd DofMap::restrict_to_free(const Eigen::VectorXd& full) const {
  Eigen::VectorXd r(num_free);
  for (std::size_t d = 0; d < free_index.size(); ++d)
    if (free_index[d] >= 0) r[free_index[d]] = full[static_cast<Eigen::Index>(d)];
  return r;
}

DofMap make_dof_map(Eigen::Index num_nodes, const std::vector<DirichletNodes>& conditions) {
  DofMap map;
  const auto num_dofs = static_cast<std::size_t>(3 * num_nodes);
  std::vector<char> constrained(num_dofs, 0);
  map.prescribed = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(num_dofs));
  for (const auto& condition : conditions)
    for (int v : condition.nodes) {
      if (v < 0 || v >= num_nodes) throw std::out_of_range("make_dof_map: node index out of range");
      for (int p = 0; p < 3; ++p) {
        constrained[static_cast<std::size_t>(3 * v + p)] = 1;
        map.prescribed[3 * v + p] = condition.displacement[p];
      }
    }
  map.free_index.assign(num_dofs, -1);
  for (std::size_t d = 0; d < num_dofs; ++d)
    if (!constrained[d]) map.free_index[d] = map.num_free++;
  return map;
}

} // namespace kerf
