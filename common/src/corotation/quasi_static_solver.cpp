#include "kerf/corotation/quasi_static_solver.hpp"

#include "kerf/fem/sparse_assembler.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace kerf {

QuasiStaticResult solve_quasi_static(const QuasiStaticModel& model, const DofMap& dofs, const Eigen::VectorXd& f_ext,
                                     const QuasiStaticSettings& settings, const PrescribedPath& path) {
  const auto prescribed_at = [&](double lambda) -> Eigen::VectorXd { return path ? path(lambda) : Eigen::VectorXd(lambda * dofs.prescribed); };
  const double roundoff_floor = 10.0 * std::numeric_limits<double>::epsilon() * model.position_force_norm();
  // `increment` maps the free DOFs' correction du_f and the prescribed DOFs' increment du_c of
  // an iteration to the whole vector: du_c is the step's increment of u_c in the first iteration
  // of a step, zero afterwards. The assembler lifts with whatever we last set_prescribed().
  DofMap increment = dofs;
  SparseAssembler assembler(model.assembly_slots(), dofs);
  auto solver = make_linear_solver(settings.solver);
  solver->analyze_pattern(assembler.matrix());

  QuasiStaticResult result;
  result.u = Eigen::VectorXd::Zero(3 * model.num_dof_nodes());
  Eigen::VectorXd f_int, rhs, du_free;
  for (int step = 1; step <= settings.load_steps; ++step) {
    const double lambda = double(step) / settings.load_steps;
    const double previous = double(step - 1) / settings.load_steps;
    increment.prescribed = prescribed_at(lambda) - prescribed_at(previous);
    for (std::size_t d = 0; d < increment.free_index.size(); ++d)
      if (increment.free_index[d] >= 0) increment.prescribed[static_cast<Eigen::Index>(d)] = 0.0;
    const Eigen::VectorXd load = dofs.restrict_to_free(lambda * f_ext);
    double scale = (lambda * f_ext).norm();
    bool step_converged = false;
    for (int iteration = 0; iteration <= settings.max_iterations; ++iteration) {
      // Residual at the current state, and the tangent, in one pass over the elements.
      assembler.set_zero();
      rhs = Eigen::VectorXd::Zero(dofs.num_free);
      const bool first = iteration == 0;
      if (!first) increment.prescribed.setZero();
      assembler.set_prescribed(increment.prescribed); // lift K_fc du_c in the first iteration only
      result.last_statistics = model.assemble(result.u, settings.rotation, settings.tangent, f_int, &assembler, &rhs);
      const Eigen::VectorXd residual = load - dofs.restrict_to_free(f_int);
      scale = std::max({scale, f_int.norm(), rhs.norm()}); // rhs holds -K_fc du_c so far
      // The history records the residual of the system this iteration solves, r_f - K_fc du_c:
      // at iteration 0 it holds the step's prescribed increment still to be applied (rhs is
      // -K_fc du_c then, zero afterwards), so a step driven by a moving support does not look
      // converged before it starts.
      const double step_residual = (residual + rhs).norm();
      NewtonIteration record{step, iteration, scale > 0.0 ? step_residual / scale : step_residual, false};
      const double relative = scale > 0.0 ? residual.norm() / scale : residual.norm();
      if (!first && (relative <= settings.tolerance || residual.norm() <= roundoff_floor)) {
        result.history.push_back(record);
        step_converged = true;
        break;
      }
      if (iteration == settings.max_iterations) {
        result.history.push_back(record);
        break;
      }
      rhs += residual;
      du_free = Eigen::VectorXd::Zero(dofs.num_free);
      try {
        solver->factorize(assembler.matrix());
        solver->solve(rhs, du_free);
      } catch (const std::runtime_error&) {
        // The consistent tangent is not positive definite (strong compression), or CG could not
        // solve with it: whichever solver found out (a pivot, a curvature, no convergence), take
        // this iteration with the warped stiffness R K R^T, which is positive definite whenever
        // the body is held. A failure there is the caller's to see.
        if (settings.tangent != CorotationalTangent::consistent) throw;
        assembler.set_zero();
        rhs = Eigen::VectorXd::Zero(dofs.num_free);
        model.assemble(result.u, settings.rotation, CorotationalTangent::warped, f_int, &assembler, &rhs);
        rhs += residual;
        solver->factorize(assembler.matrix());
        du_free = Eigen::VectorXd::Zero(dofs.num_free);
        solver->solve(rhs, du_free);
        record.warped_fallback = true;
      }
      result.history.push_back(record);
      ++result.total_iterations;
      result.u += increment.expand(du_free); // free DOFs move by du_f, prescribed ones by du_c
      if (!result.u.allFinite()) throw std::runtime_error("the Newton iteration produced a non-finite displacement");
    }
    result.converged = result.converged && step_converged;
  }
  return result;
}

} // namespace kerf
