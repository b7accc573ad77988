// A bar of liver tissue held at one end and cut from above, as chapters 7 and 8 step it: its
// cut model, lumped mass, gravity and held nodes, and the two integrators on it, chapter 7's
// Newton step (the tight reference) and chapter 8's quasi-Newton step.
#pragma once

#include "dynamics/cut_body.hpp"
#include "kerf/corotation/corotated_pieces.hpp"
#include "kerf/dynamics/lumped_mass.hpp"
#include "kerf/dynamics/nonlinear_newmark.hpp"
#include "kerf/dynamics/quasi_newton_newmark.hpp"
#include "kerf/mesh/box_mesh.hpp"

#include <memory>
#include <vector>

namespace cantilever {

// The demo's tissue and step (examples/07_liver_cut.json).
inline const kerf::LinearMaterial tissue{4000.0, 0.45, 1060.0};
constexpr double dt = 0.01, g = 9.81;

// 10 x 4 x 4 cm, cut at x = 5.2 cm by a plane from the top down to z = `cut_bottom` (below 0:
// through), held at x = 0.
struct Bar {
  kerf::LinearMaterial material;
  cut_body::CutBody body;
  kerf::DofMap dofs;
  Eigen::SparseMatrix<double> M;
  Eigen::VectorXd weight;
  std::shared_ptr<kerf::SparseAssembler> assembler;

  explicit Bar(double cut_bottom, Eigen::Vector3i cells = {10, 4, 4}, const kerf::LinearMaterial& bar_material = tissue)
      : material(bar_material),
        body(kerf::make_box_mesh({0, 0, 0}, {0.1, 0.04, 0.04}, cells),
             {cut_body::plane_surface({1, 0, 0}, 0.052, {0.052, 0.02, 0.5 * (0.06 + cut_bottom)},
                                      0.5 * (0.06 - cut_bottom))},
             bar_material) {
    std::vector<int> held;
    for (Eigen::Index v = 0; v < body.mesh.num_nodes(); ++v)
      if (body.mesh.nodes(v, 0) < 1e-9) held.push_back(static_cast<int>(v));
    dofs = kerf::make_dof_map(body.model.num_dof_nodes(), {{held, {0, 0, 0}}});
    M = kerf::lump_cut_xfem_mass(body.model, material.density, kerf::LumpingScheme::bernstein, cut_body::subtets);
    Eigen::VectorXd down = Eigen::VectorXd::Zero(M.rows());
    for (Eigen::Index v = 0; v < body.mesh.num_nodes(); ++v) down[3 * v + 2] = -g;
    weight = M * down;
    assembler = std::make_shared<kerf::SparseAssembler>(body.model.assembly_slots(),
                                                        kerf::make_dof_map(body.model.num_dof_nodes(), {}));
  }

  // Chapter 7's step on the bar (Rayleigh alpha, beta), Newton to a relative residual of 1e-10.
  kerf::NonlinearDynamicSystem newton_system(double alpha, double beta) const {
    kerf::NonlinearDynamicSystem system;
    system.M = M;
    system.rayleigh_alpha = alpha;
    system.rayleigh_beta = beta;
    system.dofs = dofs;
    const Eigen::VectorXd f = weight, zero = Eigen::VectorXd::Zero(M.rows());
    system.load = [f](double) { return f; };
    system.motion = [zero](double) { return kerf::PrescribedMotion{zero, zero, zero}; };
    system.internal_force = cut_body::corotated_force(body.model, assembler);
    const kerf::CutXfemModel& model = body.model;
    system.elastic_energy = [&model](const Eigen::VectorXd& u) { return model.energy(u, true); };
    return system;
  }

  // Chapter 8's body: the same mass, load and holds on the model's pieces.
  kerf::QuasiNewtonBody quasi_newton_body(const kerf::CorotatedPieces& pieces, double alpha, double beta) const {
    return {&pieces, M, dofs, weight, body.mesh.num_nodes(), alpha, beta};
  }
};

// The displacements at rest and after each of `steps` steps of either integrator.
template <class Integrator>
std::vector<Eigen::VectorXd> from_rest(Integrator& newmark, Eigen::Index size, int steps) {
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(size);
  kerf::DynamicState state = newmark.initial_state(zero, zero, 0.0);
  std::vector<Eigen::VectorXd> u{state.u};
  for (int n = 0; n < steps; ++n) {
    newmark.step(state);
    u.push_back(state.u);
  }
  return u;
}

// The displacements after `steps` steps of `step` s from rest: chapter 7's Newton step.
inline std::vector<Eigen::VectorXd> newton_run(const Bar& bar, double alpha, double beta, int steps, double step = dt) {
  const kerf::NonlinearDynamicSystem system = bar.newton_system(alpha, beta);
  kerf::NonlinearNewmarkSettings settings;
  settings.update = kerf::RotationUpdate::newton;
  settings.tolerance = 1e-10;
  kerf::NonlinearNewmarkIntegrator newmark(system, step, settings);
  return from_rest(newmark, bar.M.rows(), steps);
}

// The same with chapter 8's step.
inline std::vector<Eigen::VectorXd> quasi_newton_run(const Bar& bar, double alpha, double beta, int steps,
                                                     kerf::QuasiNewtonNewmarkSettings settings, double step = dt) {
  const kerf::CorotatedPieces pieces(bar.body.model, bar.material, kerf::RotationMethod::automatic);
  kerf::QuasiNewtonNewmark newmark(step, bar.material, settings);
  newmark.set_body(bar.quasi_newton_body(pieces, alpha, beta));
  return from_rest(newmark, bar.M.rows(), steps);
}

// The largest node displacement of a run, and the largest difference between two runs' nodes
// (the mesh's nodes: the DOFs a picture and a probe read).
inline double largest_displacement(const std::vector<Eigen::VectorXd>& run, Eigen::Index nodes) {
  double largest = 0.0;
  for (const Eigen::VectorXd& u : run)
    for (Eigen::Index v = 0; v < nodes; ++v) largest = std::max(largest, u.segment<3>(3 * v).norm());
  return largest;
}
inline double largest_difference(const std::vector<Eigen::VectorXd>& a, const std::vector<Eigen::VectorXd>& b, Eigen::Index nodes) {
  double largest = 0.0;
  for (std::size_t n = 0; n < a.size(); ++n)
    for (Eigen::Index v = 0; v < nodes; ++v) largest = std::max(largest, (a[n].segment<3>(3 * v) - b[n].segment<3>(3 * v)).norm());
  return largest;
}

} // namespace cantilever
