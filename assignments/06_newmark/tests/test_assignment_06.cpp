// Assignment 06's own test cases (assignments/06_newmark/README.md), for what the dynamics
// suite leaves out: each graded function checked on its own, against values computed here from
// the formulas' inputs, on every element type it serves (Tet4 and Tet10) and for more than one
// (beta, gamma). Each test case calls one graded function only; grade.sh links it with the
// library's version of the others.
#include "dynamics/cut_body.hpp"
#include "kerf/dynamics/lumped_mass.hpp"
#include "kerf/dynamics/newmark.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"
#include "kerf/mesh/tet_mesh.hpp"
#include "kerf/xfem/cut_xfem_mass.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace {

const kerf::LinearMaterial material{1000.0, 0.3, 1100.0};
const double rho = material.density;

// ---------------------------------------------------------------------------------------------
// Newmark

// Two DOF nodes coupled by symmetric positive definite M and K (6 x 6), node 0 held at u_c.
kerf::LinearDynamicSystem coupled_system(double alpha_rayleigh, double beta_rayleigh) {
  Eigen::MatrixXd A(6, 6), B(6, 6);
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) {
      A(r, c) = std::sin(1.0 + r + 2.0 * c); // fixed, not random: the same system every run
      B(r, c) = std::cos(2.0 + 3.0 * r + c);
    }
  const Eigen::MatrixXd M = A * A.transpose() + 6.0 * Eigen::MatrixXd::Identity(6, 6);
  const Eigen::MatrixXd K = 400.0 * (B * B.transpose() + Eigen::MatrixXd::Identity(6, 6));
  kerf::LinearDynamicSystem system;
  system.M = M.sparseView();
  system.K = K.sparseView();
  system.C = (alpha_rayleigh * M + beta_rayleigh * K).sparseView(); // Rayleigh: C = alpha_R M + beta_R K
  system.dofs = kerf::make_dof_map(2, {{{0}, Eigen::Vector3d(0.01, -0.02, 0.03)}});
  system.load = [](double t) {
    Eigen::VectorXd f(6);
    f << 1.0, -2.0, 0.5, 3.0 * std::sin(7.0 * t), -1.0 + t, 2.0 * std::cos(5.0 * t);
    return f;
  };
  return system;
}

Eigen::VectorXd sample(int n, double phase) {
  Eigen::VectorXd x(n);
  for (int i = 0; i < n; ++i) x[i] = std::sin(phase + 1.7 * i) + 0.3;
  return x;
}

const std::array<kerf::NewmarkParameters, 4> parameter_sets{
    kerf::NewmarkParameters{0.25, 0.5},       // the average acceleration rule
    kerf::NewmarkParameters{0.3025, 0.6},     // (gamma + 1/2)^2 / 4: damps the high frequencies
    kerf::NewmarkParameters{0.0, 0.5},        // the central difference
    kerf::NewmarkParameters{0.35, 0.7}};      // beta and gamma far apart: a swap shows

double energy(const Eigen::SparseMatrix<double>& M, const Eigen::SparseMatrix<double>& K, const Eigen::VectorXd& u,
              const Eigen::VectorXd& v) {
  return 0.5 * v.dot(M * v) + 0.5 * u.dot(K * u);
}

} // namespace

TEST_CASE("newmark_predict: u~ and v~ for four (beta, gamma), against the predictor's formula") {
  const double dt = 0.013;
  const Eigen::VectorXd u = sample(7, 0.1), v = sample(7, 1.3), a = sample(7, 2.9);
  for (const kerf::NewmarkParameters& p : parameter_sets) {
    CAPTURE(p.beta);
    CAPTURE(p.gamma);
    const kerf::NewmarkPrediction predicted = kerf::newmark_predict(u, v, a, dt, p);
    const Eigen::VectorXd u_expected = u + dt * v + dt * dt * (0.5 - p.beta) * a;
    const Eigen::VectorXd v_expected = v + dt * (1.0 - p.gamma) * a;
    REQUIRE(predicted.u.size() == 7);
    REQUIRE(predicted.v.size() == 7);
    // Sums of three terms of order 1: round-off is a few 1e-16.
    CHECK((predicted.u - u_expected).lpNorm<Eigen::Infinity>() <= 1e-14);
    CHECK((predicted.v - v_expected).lpNorm<Eigen::Infinity>() <= 1e-14);
  }
}

TEST_CASE("newmark_correct: the state at t_next on every DOF, the held node at u_c with v = a = 0") {
  const kerf::LinearDynamicSystem system = coupled_system(0.0, 0.0);
  const kerf::ReducedDynamicSystem reduced(system);
  const double dt = 0.013, t_next = 0.5;
  const kerf::NewmarkPrediction predicted{sample(3, 0.4), sample(3, 1.1)};
  const Eigen::VectorXd a_next = sample(3, 2.2);
  for (const kerf::NewmarkParameters& p : parameter_sets) {
    CAPTURE(p.beta);
    CAPTURE(p.gamma);
    const kerf::DynamicState state = kerf::newmark_correct(reduced, t_next, predicted, a_next, dt, p);
    CHECK(state.t == t_next);
    REQUIRE(state.u.size() == 6);
    REQUIRE(state.v.size() == 6);
    REQUIRE(state.a.size() == 6);
    // Node 0 is held: DOFs 0..2 prescribed, DOFs 3..5 free (free index 0..2).
    for (int i = 0; i < 3; ++i) {
      CAPTURE(i);
      CHECK(state.u[i] == system.dofs.prescribed[i]);
      CHECK(state.v[i] == 0.0);
      CHECK(state.a[i] == 0.0);
      CHECK(state.u[3 + i] == kerf_test::relative(predicted.u[i] + p.beta * dt * dt * a_next[i], 1e-14));
      CHECK(state.v[3 + i] == kerf_test::relative(predicted.v[i] + p.gamma * dt * a_next[i], 1e-14));
      CHECK(state.a[3 + i] == a_next[i]);
    }
  }
}

TEST_CASE("NewmarkIntegrator::step: the equations of motion at t_{n+1}, Newmark's updates and every energy term") {
  // Rayleigh damping C = alpha_R M + beta_R K (alpha_R, beta_R are not Newmark's beta, gamma).
  const kerf::LinearDynamicSystem system = coupled_system(0.8, 0.002);
  const kerf::ReducedDynamicSystem reduced(system);
  const double dt = 0.01;
  for (const kerf::NewmarkParameters& p : parameter_sets) {
    CAPTURE(p.beta);
    CAPTURE(p.gamma);
    kerf::NewmarkIntegrator newmark(system, dt, p);
    const Eigen::VectorXd u0 = system.dofs.expand(0.01 * sample(3, 0.7));
    const Eigen::VectorXd v0 = (Eigen::VectorXd(6) << 0, 0, 0, 0.3, -0.2, 0.1).finished();
    kerf::DynamicState state = kerf::consistent_initial_state(reduced, u0, v0, 0.0, {});
    double numerical_total = 0.0;
    for (int n = 0; n < 20; ++n) {
      CAPTURE(n);
      const kerf::DynamicState old = state;
      const kerf::StepEnergy e = newmark.step(state);
      REQUIRE(state.u.size() == 6);
      CHECK(state.t == kerf_test::relative(old.t + dt, 1e-15));
      // The equations of motion on the free DOFs at t_{n+1} (the held node has v = a = 0, so only
      // its K u_c acts): the residual, against the forces' size (order 10), is round-off.
      const Eigen::VectorXd residual = system.M * state.a + system.C * state.v + system.K * state.u - system.load(state.t);
      CHECK(system.dofs.restrict_to_free(residual).lpNorm<Eigen::Infinity>() <= 1e-10);
      // Newmark's updates between the two states.
      const Eigen::VectorXd u_update = old.u + dt * old.v + dt * dt * ((0.5 - p.beta) * old.a + p.beta * state.a);
      const Eigen::VectorXd v_update = old.v + dt * ((1.0 - p.gamma) * old.a + p.gamma * state.a);
      CHECK((state.u - u_update).lpNorm<Eigen::Infinity>() <= 1e-14);
      CHECK((state.v - v_update).lpNorm<Eigen::Infinity>() <= 1e-12);
      CHECK(state.u.head(3) == system.dofs.prescribed.head(3));
      // Every energy term from its definition, on full vectors.
      const Eigen::VectorXd du = state.u - old.u, jump = state.a - old.a;
      const Eigen::VectorXd a_bar = 0.5 * (state.a + old.a), v_bar = 0.5 * (state.v + old.v);
      const double work = du.dot(0.5 * (system.load(old.t) + system.load(state.t)));
      const double damping = du.dot(system.C * v_bar);
      const double numerical = dt * dt * (p.beta - 0.5 * p.gamma) * jump.dot(system.M * a_bar) -
                               dt * (p.gamma - 0.5) * v_bar.dot(system.M * jump);
      const double scale = std::abs(work) + std::abs(damping) + 1e-12;
      CHECK(e.external_work == doctest::Approx(work).epsilon(1e-10).scale(scale));
      CHECK(e.damping == doctest::Approx(damping).epsilon(1e-10).scale(scale));
      CHECK(e.numerical == doctest::Approx(numerical).epsilon(1e-10).scale(scale));
      // The balance the formula is derived for: what the energy did is what the terms say.
      const double delta_energy = energy(system.M, system.K, state.u, state.v) - energy(system.M, system.K, old.u, old.v);
      CHECK(delta_energy == doctest::Approx(e.external_work - e.damping - e.numerical).epsilon(1e-9).scale(scale));
      numerical_total += e.numerical;
      if (p.beta == 0.25 && p.gamma == 0.5) CHECK(std::abs(e.numerical) <= 1e-13 * scale);
    }
    // gamma > 1/2 removes energy (the dissipation is positive over the run).
    if (p.gamma > 0.5) CHECK(numerical_total > 0.0);
  }
}

// ---------------------------------------------------------------------------------------------
// The lumped mass and its load

namespace {

// A plane cutting the unit tet, with the closed-form volume of its minus side n . x < offset.
struct TetCut {
  std::string name;
  Eigen::Vector3d normal;
  double offset;
  double volume_minus;
};

std::vector<TetCut> tet_cuts() {
  const double s = 0.4, w = 0.6;
  return {{"corner 0 cut off (1:3)", {1, 1, 1}, s, s * s * s / 6.0},
          {"two corners against two (2:2)", {1, 1, 0}, w, w * w / 2.0 - w * w * w / 3.0}};
}

const std::array<kerf::LumpingScheme, 5> all_schemes{kerf::LumpingScheme::bernstein, kerf::LumpingScheme::row_sum,
                                                     kerf::LumpingScheme::hrz, kerf::LumpingScheme::virtual_tet,
                                                     kerf::LumpingScheme::schoch_eq_81_82};

const char* name_of(kerf::LumpingScheme scheme) {
  switch (scheme) {
  case kerf::LumpingScheme::bernstein: return "bernstein";
  case kerf::LumpingScheme::row_sum: return "row_sum";
  case kerf::LumpingScheme::hrz: return "hrz";
  case kerf::LumpingScheme::virtual_tet: return "virtual_tet";
  case kerf::LumpingScheme::schoch_eq_81_82: return "schoch_eq_81_82";
  }
  return "?";
}

// The lumped diagonal D_p (n entries) of a piece from its unit-density consistent mass m_p.
Eigen::VectorXd piece_diagonal(const Eigen::MatrixXd& m, kerf::LumpingScheme scheme) {
  const Eigen::Index n = m.rows();
  const double volume = m.sum();
  const Eigen::VectorXd rows = rho * m.rowwise().sum();
  switch (scheme) {
  case kerf::LumpingScheme::row_sum: return rows;
  case kerf::LumpingScheme::hrz: return rho * volume * m.diagonal() / m.trace();
  case kerf::LumpingScheme::virtual_tet: return Eigen::VectorXd::Constant(n, rho * volume / static_cast<double>(n));
  case kerf::LumpingScheme::bernstein: {
    if (n == 4) return rows;
    Eigen::VectorXd D = Eigen::VectorXd::Zero(n);
    for (int e = 0; e < 6; ++e) {
      D[4 + e] += rows[4 + e] / 2.0;
      for (const int a : kerf::tet_edge_corners[e]) D[a] += rows[4 + e] / 4.0;
    }
    for (int a = 0; a < 4; ++a) D[a] += rows[a];
    return D;
  }
  case kerf::LumpingScheme::schoch_eq_81_82: break;
  }
  return {};
}

// The expected lumped mass (dense, 3 per DOF node) and gravity load of a body of one tet,
// scattered here from the piece masses the library integrates (cut_xfem_piece_masses, not part of
// the assignment): M = sum_p T_p^T (D_p kron I_3) T_p and f = sum_p T_p^T (D_p 1 kron g), or,
// for eqs. 81-82 (Schoch et al. 2013), M^uu_ii = m / n, M^aa_kk = sum_p (V_p / V) m / n.
struct Expected {
  Eigen::MatrixXd M;
  Eigen::VectorXd f;
};

Expected expected_lumping(const kerf::CutXfemModel& model, kerf::LumpingScheme scheme, const Eigen::Vector3d& g) {
  const Eigen::Index dofs = 3 * model.num_dof_nodes();
  Expected x{Eigen::MatrixXd::Zero(dofs, dofs), Eigen::VectorXd::Zero(dofs)};
  const std::vector<Eigen::MatrixXd> pieces = kerf::cut_xfem_piece_masses(model, 0, 1.0, cut_body::subtets);
  const int n = static_cast<int>(model.mesh().tets.cols());
  double volume = 0.0;
  for (const Eigen::MatrixXd& m : pieces) volume += m.sum();
  const auto add = [&](int r, int c, double value) {
    for (int d = 0; d < 3; ++d) x.M(3 * r + d, 3 * c + d) += value;
  };
  for (int p = 0; p < static_cast<int>(pieces.size()); ++p) {
    const Eigen::VectorXd D = scheme == kerf::LumpingScheme::schoch_eq_81_82
                                  ? Eigen::VectorXd::Constant(n, rho * pieces[p].sum() / n)
                                  : piece_diagonal(pieces[p], scheme);
    for (int a = 0; a < n; ++a) {
      const int i = model.mesh().tets(0, a), k = model.phantom_node(0, p, a);
      if (scheme == kerf::LumpingScheme::schoch_eq_81_82) {
        if (k != i) add(k, k, D[a]); // eq. 82
        continue;
      }
      add(i, i, D[a]);
      x.f.segment<3>(3 * i) += D[a] * g;
      if (k != i) {
        add(i, k, D[a]);
        add(k, i, D[a]);
        add(k, k, D[a]);
        x.f.segment<3>(3 * k) += D[a] * g;
      }
    }
  }
  if (scheme == kerf::LumpingScheme::schoch_eq_81_82) {
    for (int a = 0; a < n; ++a) add(model.mesh().tets(0, a), model.mesh().tets(0, a), rho * volume / n); // eq. 81
    x.f = model.gravity_load(rho, g);
  }
  return x;
}

// The bodies both test cases run on: the unit Tet4 and Tet10, whole and cut by each plane.
template <typename Check> void for_each_body(const Check& check) {
  for (const bool quadratic : {false, true}) {
    const kerf::TetMesh mesh = quadratic ? kerf::tet10_from_tet4(cut_body::unit_tet()) : cut_body::unit_tet();
    CAPTURE(std::string(quadratic ? "Tet10" : "Tet4"));
    {
      CAPTURE(std::string("whole"));
      const cut_body::CutBody body(mesh, {}, material);
      check(body, 1.0 / 6.0, 0.0);
    }
    for (const TetCut& cut : tet_cuts()) {
      CAPTURE(cut.name);
      const cut_body::CutBody body(mesh, {cut_body::plane_surface(cut.normal, cut.offset, {0.25, 0.25, 0.25}, 3.0)}, material);
      REQUIRE(body.pieces.num_pieces(0) == 2);
      check(body, 1.0 / 6.0, cut.volume_minus);
    }
  }
}

} // namespace

TEST_CASE("lump_cut_xfem_mass: every scheme entry by entry on a whole and a cut Tet4 and Tet10") {
  for_each_body([](const cut_body::CutBody& body, double V, double volume_minus) {
    // The piece masses the expected values are built from weigh the closed-form volumes.
    const std::vector<Eigen::MatrixXd> pieces = kerf::cut_xfem_piece_masses(body.model, 0, 1.0, cut_body::subtets);
    if (volume_minus > 0.0) {
      const double smaller = std::min(pieces[0].sum(), pieces[1].sum());
      REQUIRE(smaller == kerf_test::relative(std::min(volume_minus, V - volume_minus), 1e-12));
    }
    for (const kerf::LumpingScheme scheme : all_schemes) {
      CAPTURE(std::string(name_of(scheme)));
      const Eigen::MatrixXd M = Eigen::MatrixXd(kerf::lump_cut_xfem_mass(body.model, rho, scheme, cut_body::subtets));
      const Expected x = expected_lumping(body.model, scheme, Eigen::Vector3d(0, 0, -9.81));
      REQUIRE(M.rows() == x.M.rows());
      REQUIRE(M.cols() == x.M.cols());
      // Entries of order rho V / 10 = 18: round-off is below 1e-13 of rho V.
      CHECK((M - x.M).lpNorm<Eigen::Infinity>() <= 1e-13 * rho * V);
    }
  });
}

TEST_CASE("lumped_gravity_load: every scheme's load on a whole and a cut Tet4 and Tet10") {
  const Eigen::Vector3d g(0.5, -9.81, 1.5);
  for_each_body([&](const cut_body::CutBody& body, double V, double) {
    for (const kerf::LumpingScheme scheme : all_schemes) {
      CAPTURE(std::string(name_of(scheme)));
      const Eigen::VectorXd f = kerf::lumped_gravity_load(body.model, rho, g, scheme, cut_body::subtets);
      const Expected x = expected_lumping(body.model, scheme, g);
      REQUIRE(f.size() == x.f.size());
      CHECK((f - x.f).lpNorm<Eigen::Infinity>() <= 1e-13 * rho * V * g.norm());
    }
  });
}
