// The XFEM mass (Paper 000 eqs. 76-82): cutting adds no mass (lumped u-part), a rigid
// translation of the whole body carries rho V |t|^2, and one of the piece above alone carries
// rho V_above |t|^2, with V_above known in closed form for a plane through the beam.
#include "xfem_test_support.hpp"

#include "kerf/xfem/xfem_mass.hpp"
#include "kerf/xfem/xfem_model.hpp"

#include <doctest/doctest.h>

using namespace xfem_test;

namespace {

const kerf::LinearMaterial material{300e3, 0.35, 1070.0};
constexpr double beam_volume = 0.03 * 0.06 * 0.2;

} // namespace

TEST_CASE("xfem mass: lumped and consistent masses of a beam cut obliquely through") {
  const kerf::TetMesh mesh = beam({2, 3, 8});
  // The plane passes through the centroid (0.015, 0.03, 0.1) of the mid cross-section and
  // crosses only the long sides of the beam (|dz| <= 0.011 over the section), so the part above
  // is a prism of the cross-section's area times the mean height 0.1: V_above = V / 2 exactly.
  const kerf::Enrichment e = kerf::make_enrichment(mesh, plane_cut({0.015, 0.03, 0.1}, {0.3, 0.2, 1.0}));
  REQUIRE(e.snapped_nodes == 0);
  REQUIRE(e.cut_tets > 0);
  const kerf::XfemModel model(mesh, material, e);
  const double rho = material.density;
  const auto n = static_cast<Eigen::Index>(3 * mesh.num_nodes());

  // Sums of a few hundred positive terms of similar size: round-off ~1e-15 relative; 1e-12.
  const Eigen::VectorXd lumped = kerf::xfem_lumped_mass(model, rho);
  for (int d = 0; d < 3; ++d) {
    double total = 0.0;
    for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) total += lumped[3 * v + d];
    CHECK(std::abs(total - rho * beam_volume) <= 1e-12 * rho * beam_volume);
  }
  CHECK(lumped.tail(lumped.size() - n).minCoeff() > 0.0); // every enriched DOF has mass (eq. 82)

  const Eigen::SparseMatrix<double> M = kerf::assemble_xfem_mass(model, rho);
  REQUIRE(M.rows() == 3 * model.num_dof_nodes());
  const Eigen::Vector3d t(0.3, -1.2, 0.7);

  // The whole body translated: u_i = t, a_i = 0.
  Eigen::VectorXd whole = Eigen::VectorXd::Zero(M.rows());
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) whole.segment<3>(3 * v) = t;
  const double whole_energy = whole.dot(M * whole);
  CHECK(std::abs(whole_energy - rho * beam_volume * t.squaredNorm()) <= 1e-12 * rho * beam_volume * t.squaredNorm());

  // The piece above translated, the piece below at rest: u_i = t above, 0 below; a_i = t for an
  // enriched node below (Psi_a = +1: t above, 0 on its own side) and a_i = t for one above
  // (Psi_b = -1: t - t = 0 below).
  Eigen::VectorXd above = Eigen::VectorXd::Zero(M.rows());
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) {
    if (e.node_sign[static_cast<std::size_t>(v)] > 0) above.segment<3>(3 * v) = t;
    if (const int a_node = enriched_dof_node(model, static_cast<int>(v)); a_node >= 0) above.segment<3>(3 * a_node) = t;
  }
  for (Eigen::Index v = 0; v < mesh.num_nodes(); ++v) { // every side value a node has is right
    const bool enriched = e.enriched_index[static_cast<std::size_t>(v)] >= 0;
    const int sign = e.node_sign[static_cast<std::size_t>(v)];
    if (sign > 0 || enriched) CHECK((node_side_value(model, above, static_cast<int>(v), +1) - t).norm() == 0.0);
    if (sign < 0 || enriched) CHECK(node_side_value(model, above, static_cast<int>(v), -1).norm() == 0.0);
  }
  double V_above = 0.0; // from the tets: the ones above, plus V_a of the cut ones
  for (Eigen::Index k = 0; k < mesh.num_tets(); ++k) V_above += e.fraction_above[static_cast<std::size_t>(k)] * model.element_volume(k);
  CHECK(std::abs(V_above - 0.5 * beam_volume) <= 1e-12 * beam_volume);
  const double above_energy = above.dot(M * above);
  MESSAGE("v^T M v: whole body " << whole_energy << " (rho V |t|^2 = " << rho * beam_volume * t.squaredNorm() << "), piece above "
                                 << above_energy << " (rho V/2 |t|^2 = " << 0.5 * rho * beam_volume * t.squaredNorm() << ")");
  CHECK(std::abs(above_energy - rho * 0.5 * beam_volume * t.squaredNorm()) <= 1e-12 * rho * beam_volume * t.squaredNorm());
  // The consistent mass is symmetric (both triangles are assembled).
  CHECK((Eigen::SparseMatrix<double>(M.transpose()) - M).norm() <= 1e-15 * M.norm());
}
