#include "kerf/xfem/cut_xfem_field_error.hpp"

#include "kerf/cut/tet_pieces.hpp"
#include "kerf/quadrature/gauss_piece_rules.hpp"

#include <cmath>

namespace kerf {

FieldError cut_xfem_field_error(const CutXfemModel& model, const LinearMaterial& material, const Eigen::VectorXd& u,
                                const CrackFronts& fronts, const ExactDisplacement& exact,
                                const ExactGradient& exact_gradient) {
  const TetMesh& mesh = model.mesh();
  const MeshPieces& pieces = model.pieces();
  const double mu = material.mu(), lambda = material.lambda();
  const auto energy_density = [&](const Eigen::Matrix3d& H) {
    const Eigen::Matrix3d eps = 0.5 * (H + H.transpose());
    return lambda * eps.trace() * eps.trace() + 2.0 * mu * eps.squaredNorm();
  };
  FieldError e;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const Eigen::Matrix<double, 4, 3> X = tet_corners(mesh, t);
    const int entry = pieces.entry[static_cast<std::size_t>(t)];
    const TetPieces whole = entry < 0 ? split_tet_by_triangles(X, {}) : TetPieces{};
    const TetPieces& tet = entry < 0 ? whole : pieces.tets[static_cast<std::size_t>(entry)];
    double longest_edge = 0.0;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) longest_edge = std::max(longest_edge, (X.row(i) - X.row(j)).norm());
    const bool front_tet = !fronts.empty() && !front_in_tet(fronts, X).empty();
    const int refinements =
        front_tet ? 2 : (fronts.distance(X.colwise().mean().transpose()) < 2.0 * longest_edge ? 1 : 0);
    for (int p = 0; p < tet.num_pieces(); ++p) {
      const PieceQuadratureRule rule = refined_subtet_rule(tet, p, 4, refinements);
      for (std::size_t q = 0; q < rule.points.size(); ++q) {
        const Eigen::Vector3d& x = rule.points[q];
        const double w = rule.weights[q];
        const Eigen::Vector3d u_exact = exact(x);
        const Eigen::Matrix3d H_exact = exact_gradient(x);
        e.L2 += w * (model.displacement_at(u, t, x) - u_exact).squaredNorm();
        e.L2_exact += w * u_exact.squaredNorm();
        e.energy += w * energy_density(model.displacement_gradient_at(u, t, x) - H_exact);
        e.energy_exact += w * energy_density(H_exact);
      }
    }
  }
  for (double* norm : {&e.L2, &e.L2_exact, &e.energy, &e.energy_exact}) *norm = std::sqrt(*norm);
  return e;
}

} // namespace kerf
