#include "kerf/xfem/pull_back.hpp"

#include <Eigen/LU>
#include <limits>

namespace kerf {

PullBack pull_back_to_reference(const CutXfemModel& model, const PointLocator& locator, const Eigen::VectorXd& u,
                                const Eigen::Vector3d& x, const Eigen::Vector3d& guess, double tolerance, int max_iterations) {
  PullBack result;
  result.reference = guess;
  for (;;) {
    const PointLocation where = locator.locate(result.reference);
    result.tet = where.tet;
    if (where.tet < 0) {
      // The iterate left the reference mesh: no material point there to move.
      result.residual = std::numeric_limits<double>::infinity();
      return result;
    }
    const Eigen::Vector3d g = result.reference + model.displacement_at(u, where.tet, result.reference) - x;
    result.residual = g.norm();
    if (result.residual <= tolerance) {
      result.converged = true;
      return result;
    }
    if (result.iterations >= max_iterations) return result;
    const Eigen::Matrix3d J = Eigen::Matrix3d::Identity() + model.displacement_gradient_at(u, where.tet, result.reference);
    const Eigen::FullPivLU<Eigen::Matrix3d> lu(J);
    if (!lu.isInvertible()) return result; // a collapsed element: no direction to go
    result.reference -= lu.solve(g);
    ++result.iterations;
  }
}

} // namespace kerf
