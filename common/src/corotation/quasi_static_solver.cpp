#include "kerf/corotation/quasi_static_solver.hpp"

#include "kerf/fem/sparse_assembler.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

namespace kerf {

namespace {

/// The linearised system of one Newton iteration, K_ff du_f = r_f - K_fc du_c, and the forces
/// it was built from.
struct LinearisedSystem {
  Eigen::VectorXd f_int;     ///< internal forces at the current state (all DOFs)
  Eigen::VectorXd lifted;    ///< -K_fc du_c (free DOFs)
  CorotationStatistics statistics;
};

/// Assembles the tangent (into `assembler`) and the internal forces at u, lifting du_c.
LinearisedSystem linearise(const QuasiStaticModel& model, const Eigen::VectorXd& u, const Eigen::VectorXd& du_c,
                           const QuasiStaticSettings& settings, CorotationalTangent tangent, int num_free,
                           SparseAssembler& assembler) {
  LinearisedSystem system;
  system.lifted = Eigen::VectorXd::Zero(num_free);
  assembler.set_zero();
  assembler.set_prescribed(du_c);
  system.statistics = model.assemble(u, settings.rotation, tangent, system.f_int, &assembler, &system.lifted);
  return system;
}

} // namespace

QuasiStaticResult solve_quasi_static(const QuasiStaticModel& model, const DofMap& dofs, const Eigen::VectorXd& f_ext,
                                     const QuasiStaticSettings& settings, const PrescribedPath& path) {
  const auto prescribed_at = [&](double lambda) -> Eigen::VectorXd { return path ? path(lambda) : Eigen::VectorXd(lambda * dofs.prescribed); };
  const double roundoff_floor = 10.0 * std::numeric_limits<double>::epsilon() * model.position_force_norm();
  SparseAssembler assembler(model.assembly_slots(), dofs);
  const std::unique_ptr<LinearSolver> solver = make_linear_solver(settings.solver);
  solver->analyze_pattern(assembler.matrix()); // the pattern never changes: analyse it once

  QuasiStaticResult result;
  result.u = Eigen::VectorXd::Zero(3 * model.num_dof_nodes());
  Eigen::VectorXd previous_equilibrium = result.u;
  const Eigen::VectorXd no_increment = Eigen::VectorXd::Zero(result.u.size());
  for (int step = 1; step <= settings.load_steps; ++step) {
    // The step's targets: the load lambda f_ext and the prescribed u_c(lambda). The prescribed
    // DOFs move by du_c = u_c(lambda) - u_c(previous lambda), all of it in the first iteration.
    const double lambda = double(step) / settings.load_steps;
    const Eigen::VectorXd load = dofs.restrict_to_free(lambda * f_ext);
    Eigen::VectorXd du_c = prescribed_at(lambda) - prescribed_at(double(step - 1) / settings.load_steps);
    for (std::size_t d = 0; d < dofs.free_index.size(); ++d)
      if (dofs.free_index[d] >= 0) du_c[static_cast<Eigen::Index>(d)] = 0.0;
    double scale = (lambda * f_ext).norm();
    bool step_converged = false;
    // The secant predictor moves the free DOFs on by the last step's change and the prescribed
    // ones onto their path at once (so that no element is strained by free nodes that have
    // moved on beside a support that has not); nothing is then left to lift.
    const Eigen::VectorXd last_change = result.u - previous_equilibrium;
    previous_equilibrium = result.u;
    if (settings.predictor == LoadStepPredictor::secant && step > 1) {
      for (std::size_t d = 0; d < dofs.free_index.size(); ++d) {
        const auto i = static_cast<Eigen::Index>(d);
        result.u[i] += dofs.free_index[d] >= 0 ? last_change[i] : du_c[i];
      }
      du_c.setZero();
    }

    for (int iteration = 0; iteration <= settings.max_iterations; ++iteration) {
      const bool first = iteration == 0;
      const Eigen::VectorXd& lifted_increment = first ? du_c : no_increment;
      // The residual r_f = lambda f_ext - f_int(u) and the tangent, in one pass over the elements.
      LinearisedSystem system = linearise(model, result.u, lifted_increment, settings, settings.tangent, dofs.num_free, assembler);
      result.last_statistics = system.statistics;
      const Eigen::VectorXd residual = load - dofs.restrict_to_free(system.f_int);
      scale = std::max({scale, system.f_int.norm(), system.lifted.norm()});

      // The history records the residual of the system this iteration solves, r_f - K_fc du_c:
      // at iteration 0 it holds the step's prescribed increment still to be applied, so a step
      // driven by a moving support does not look converged before it starts.
      const double solved_residual = (residual + system.lifted).norm();
      NewtonIteration record{step, iteration, scale > 0.0 ? solved_residual / scale : solved_residual, false};
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

      // K_ff du_f = r_f - K_fc du_c.
      Eigen::VectorXd du_free = Eigen::VectorXd::Zero(dofs.num_free);
      try {
        solver->factorize(assembler.matrix());
        solver->solve(residual + system.lifted, du_free);
      } catch (const std::runtime_error&) {
        // The consistent tangent is not positive definite (strong compression), or CG could not
        // solve with it: whichever solver found out (a pivot, a curvature, no convergence), take
        // this iteration with the warped stiffness R K R^T, which is positive definite whenever
        // the body is held. A failure there is the caller's to see.
        if (settings.tangent != CorotationalTangent::consistent) throw;
        system = linearise(model, result.u, lifted_increment, settings, CorotationalTangent::warped, dofs.num_free, assembler);
        solver->factorize(assembler.matrix());
        du_free = Eigen::VectorXd::Zero(dofs.num_free);
        solver->solve(residual + system.lifted, du_free);
        record.warped_fallback = true;
      }
      result.history.push_back(record);
      ++result.total_iterations;
      result.linear_iterations += solver->iterations();

      // Free DOFs move by du_f; prescribed ones by du_c (first iteration) or not at all.
      for (std::size_t d = 0; d < dofs.free_index.size(); ++d) {
        const int free = dofs.free_index[d];
        result.u[static_cast<Eigen::Index>(d)] += free >= 0 ? du_free[free] : lifted_increment[static_cast<Eigen::Index>(d)];
      }
      if (!result.u.allFinite()) throw std::runtime_error("the Newton iteration produced a non-finite displacement");
    }
    result.converged = result.converged && step_converged;
  }
  result.factorisations = solver->factorisations();
  return result;
}

} // namespace kerf
