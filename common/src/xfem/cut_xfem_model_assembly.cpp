// CutXfemModel: forces, tangents, energies and the gravity load (cut_xfem_model.hpp's file
// comment). Every tet is assembled on its slots, its row of assembly_slots(): piece by piece,
// each piece's phantom element scattered with its T_p (assemble_tet), or, in a tet with branch
// functions, by BranchTets with one rotation per piece (assemble_branch_tet).
#include "kerf/xfem/cut_xfem_model.hpp"

#include "kerf/corotation/corotated_element.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/fem/tet_stiffness.hpp"

#include <Eigen/Dense>

namespace kerf {

template <int n>
void CutXfemModel::assemble_tet(Eigen::Index t, const Eigen::VectorXd& u, RotationMethod rotation,
                                CorotationalTangent tangent, bool corotated, Eigen::VectorXd& f_int,
                                SparseAssembler* assembler, Eigen::VectorXd* rhs_free, CorotationStatistics& stats,
                                ElementBuffers& buffers, double* energy) const {
  constexpr int m3 = 3 * n;
  const std::span<const PhantomPiece> pieces = integrated_pieces(t);

  const int slots = num_slots(t);
  // The element's force and matrix on its slots, in the caller's buffers: no allocation per tet.
  auto f_e = buffers.f.head(3 * slots);
  auto K_e = buffers.K.topLeftCorner(3 * slots, 3 * slots);
  // A tet of one piece without enrichments (most of them) is its own phantom element: its force
  // and matrix go straight to the global ones, without the element buffers.
  const bool plain = slots == n && pieces.size() == 1;
  if (!plain) {
    f_e.setZero();
    if (assembler) K_e.setZero();
  }

  Eigen::Matrix<double, n, 3> X;
  for (int a = 0; a < n; ++a) X.row(a) = mesh_.nodes.row(mesh_.tets(t, a));
  const double mu = material_.mu(), lambda = material_.lambda();
  for (const PhantomPiece& piece : pieces) {
    // The phantom element's nodal displacements u_p = T_p u_e.
    Eigen::Matrix<double, n, 3> u_p;
    for (int a = 0; a < n; ++a) {
      Eigen::Vector3d value = u.segment<3>(3 * mesh_.tets(t, a));
      const int s = piece.enrichment_slot[static_cast<std::size_t>(a)];
      if (s >= 0) value += u.segment<3>(3 * slots_(t, s));
      u_p.row(a) = value.transpose();
    }
    Eigen::Matrix<double, m3, 1> f_p = Eigen::Matrix<double, m3, 1>::Zero();
    Eigen::Matrix<double, m3, m3> K_p = Eigen::Matrix<double, m3, m3>::Zero();
    const auto add_point = [&](const Eigen::Matrix<double, m3, m3>& K_q, const Eigen::Matrix<double, n, 3>& G,
                               double weight) {
      if (corotated) {
        const PolarDecomposition polar = add_corotated_point<n>(K_q, G, X, u_p, weight, mu, lambda, rotation, tangent,
                                                                f_p, assembler ? &K_p : nullptr, &stats);
        if (energy) { // 1/2 d^T K_q d with the point's own rotation (energy()'s sum)
          const Eigen::Matrix<double, m3, 1> d = corotated_displacement<n>(polar.R, X, u_p);
          if constexpr (n == 4) {
            // A Tet4 piece is one point, and f_p was zero before it: f_p = R (K_q d) node by node
            // (Schoch et al. 2013, eq. 39), so K_q d = R^T f_p without a second 12 x 12 product.
            double d_K_d = 0.0;
            for (int a = 0; a < n; ++a)
              d_K_d += d.template segment<3>(3 * a).dot(polar.R.transpose() * f_p.template segment<3>(3 * a));
            *energy += 0.5 * d_K_d;
          } else {
            *energy += 0.5 * d.dot(K_q * d);
          }
        }
      } else {
        Eigen::Matrix<double, m3, 1> u_vector;
        for (int a = 0; a < n; ++a) u_vector.template segment<3>(3 * a) = u_p.row(a).transpose();
        f_p += K_q * u_vector;
        K_p += K_q;
      }
    };
    if constexpr (n == 4) {
      // A Tet4's gradients are constant: the piece is one point with the rule's total weight,
      // whose stiffness the piece keeps (tet4_piece_stiffness).
      double weight = 0.0;
      for (const PiecePoint& point : piece.points) weight += point.weight;
      if (!piece.points.empty())
        add_point(*piece.tet4_stiffness, piece.points.front().G.template topRows<4>(), weight);
    } else {
      for (const PiecePoint& point : piece.points) {
        Eigen::Matrix<double, m3, m3> K_q = Eigen::Matrix<double, m3, m3>::Zero();
        add_stiffness_integrand<n>(point.G, point.weight, mu, lambda, K_q);
        add_point(K_q, point.G, point.weight);
      }
    }
    if (plain) {
      for (int a = 0; a < n; ++a) f_int.segment<3>(3 * mesh_.tets(t, a)) += f_p.template segment<3>(3 * a);
      if (assembler) assembler->add_element_matrix(t, K_p, *rhs_free);
      return;
    }
    // Scatter with T_p: node a's row goes to u_a and, if enriched here, to its enrichment.
    for (int a = 0; a < n; ++a) {
      const int sa = piece.enrichment_slot[static_cast<std::size_t>(a)];
      f_e.segment<3>(3 * a) += f_p.template segment<3>(3 * a);
      if (sa >= 0) f_e.segment<3>(3 * sa) += f_p.template segment<3>(3 * a);
      if (!assembler) continue;
      for (int b = 0; b < n; ++b) {
        const int sb = piece.enrichment_slot[static_cast<std::size_t>(b)];
        const Eigen::Matrix3d block = K_p.template block<3, 3>(3 * a, 3 * b);
        K_e.block<3, 3>(3 * a, 3 * b) += block;
        if (sa >= 0) K_e.block<3, 3>(3 * sa, 3 * b) += block;
        if (sb >= 0) K_e.block<3, 3>(3 * a, 3 * sb) += block;
        if (sa >= 0 && sb >= 0) K_e.block<3, 3>(3 * sa, 3 * sb) += block;
      }
    }
  }
  for (int s = 0; s < slots; ++s) f_int.segment<3>(3 * slots_(t, s)) += f_e.segment<3>(3 * s);
  if (assembler) assembler->add_element_matrix(t, K_e, *rhs_free);
}

void CutXfemModel::slot_state(Eigen::Index t, const Eigen::VectorXd& u, Eigen::MatrixX3d& X,
                              Eigen::MatrixX3d& q) const {
  const int n = mesh_.nodes_per_tet();
  const int slots = num_slots(t);
  X = Eigen::MatrixX3d::Zero(slots, 3);
  q.resize(slots, 3);
  for (int a = 0; a < n; ++a) X.row(a) = mesh_.nodes.row(mesh_.tets(t, a));
  for (int s = 0; s < slots; ++s) q.row(s) = u.segment<3>(3 * slots_(t, s)).transpose();
}

void CutXfemModel::assemble_branch_tet(Eigen::Index t, const Eigen::VectorXd& u, RotationMethod rotation,
                                       CorotationalTangent tangent, bool corotated, Eigen::VectorXd& f_int,
                                       SparseAssembler* assembler, Eigen::VectorXd* rhs_free,
                                       CorotationStatistics& stats) const {
  const int slots = num_slots(t);
  Eigen::MatrixX3d X, q;
  slot_state(t, u, X, q);
  Eigen::VectorXd f_e = Eigen::VectorXd::Zero(3 * slots);
  Eigen::MatrixXd K_e;
  if (assembler) K_e = Eigen::MatrixXd::Zero(3 * slots, 3 * slots);
  branch_.add_forces(t, X, q, rotation, tangent, corotated, f_e, assembler ? &K_e : nullptr, stats);
  for (int s = 0; s < slots; ++s) f_int.segment<3>(3 * slots_(t, s)) += f_e.segment<3>(3 * s);
  if (assembler) assembler->add_element_matrix(t, K_e, *rhs_free);
}

double CutXfemModel::branch_tet_energy(Eigen::Index t, const Eigen::VectorXd& u, bool corotated,
                                       RotationMethod rotation) const {
  Eigen::MatrixX3d X, q;
  slot_state(t, u, X, q);
  return branch_.energy(t, X, q, corotated, rotation);
}

CorotationStatistics CutXfemModel::assemble_all(const Eigen::VectorXd& u, RotationMethod rotation,
                                                CorotationalTangent tangent, Eigen::VectorXd& f_int,
                                                SparseAssembler* assembler, Eigen::VectorXd* rhs_free,
                                                double* energy) const {
  CorotationStatistics stats;
  f_int = Eigen::VectorXd::Zero(3 * num_dof_nodes());
  ElementBuffers buffers(slots_.cols());
  for (Eigen::Index t = 0; t < mesh_.num_tets(); ++t) {
    if (branch_.contains(t)) {
      assemble_branch_tet(t, u, rotation, tangent, true, f_int, assembler, rhs_free, stats);
      if (energy) *energy += branch_tet_energy(t, u, true, rotation); // a few tets: their pieces' rotations again
    } else if (mesh_.order() == 1) {
      assemble_tet<4>(t, u, rotation, tangent, true, f_int, assembler, rhs_free, stats, buffers, energy);
    } else {
      assemble_tet<10>(t, u, rotation, tangent, true, f_int, assembler, rhs_free, stats, buffers, energy);
    }
  }
  return stats;
}

CorotationStatistics CutXfemModel::assemble(const Eigen::VectorXd& u, RotationMethod rotation,
                                            CorotationalTangent tangent, Eigen::VectorXd& f_int,
                                            SparseAssembler* assembler, Eigen::VectorXd* rhs_free) const {
  return assemble_all(u, rotation, tangent, f_int, assembler, rhs_free, nullptr);
}

double CutXfemModel::assemble_with_energy(const Eigen::VectorXd& u, RotationMethod rotation,
                                          CorotationalTangent tangent, Eigen::VectorXd& f_int,
                                          SparseAssembler* assembler, Eigen::VectorXd* rhs_free,
                                          CorotationStatistics* stats) const {
  double energy = 0.0;
  const CorotationStatistics statistics = assemble_all(u, rotation, tangent, f_int, assembler, rhs_free, &energy);
  if (stats) *stats = statistics;
  return energy;
}

template <int n>
double CutXfemModel::tet_energy(Eigen::Index t, const Eigen::VectorXd& u, bool corotated,
                                RotationMethod rotation) const {
  // The phantom element alone misses the branch functions' strain: those tets have their own.
  if (branch_.contains(t)) return branch_tet_energy(t, u, corotated, rotation);
  double energy = 0.0;
  for (const PhantomPiece& piece : integrated_pieces(t)) {
    Eigen::Matrix<double, n, 3> u_p; // the phantom element's nodal displacements, as in assemble_tet
    for (int a = 0; a < n; ++a) {
      Eigen::Vector3d value = u.segment<3>(3 * mesh_.tets(t, a));
      const int s = piece.enrichment_slot[static_cast<std::size_t>(a)];
      if (s >= 0) value += u.segment<3>(3 * slots_(t, s));
      u_p.row(a) = value.transpose();
    }
    // 1/2 d^T K_q d without forming K_q (it is a time step's second assembly in chapter 6): the
    // gradient of d is H = R^T F - I (the gradients satisfy sum_a X_a G_a^T = I), and for the
    // isotropic K_q of add_stiffness_integrand, 1/2 d^T K_q d = weight (mu eps:eps + lambda/2
    // tr(eps)^2) with eps = sym(H), the small-strain energy density of the corotated displacement.
    const auto point_energy = [&](const Eigen::Matrix<double, n, 3>& G, double weight) {
      const Eigen::Matrix3d F = Eigen::Matrix3d::Identity() + u_p.transpose() * G;
      Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
      if (corotated) R = element_rotation(F, rotation).R;
      const Eigen::Matrix3d H = R.transpose() * F - Eigen::Matrix3d::Identity();
      const Eigen::Matrix3d eps = 0.5 * (H + H.transpose());
      return weight * (material_.mu() * eps.squaredNorm() + 0.5 * material_.lambda() * eps.trace() * eps.trace());
    };
    if constexpr (n == 4) {
      double weight = 0.0;
      for (const PiecePoint& point : piece.points) weight += point.weight;
      if (!piece.points.empty()) energy += point_energy(piece.points.front().G.template topRows<4>(), weight);
    } else {
      for (const PiecePoint& point : piece.points) energy += point_energy(point.G, point.weight);
    }
  }
  return energy;
}

double CutXfemModel::energy(const Eigen::VectorXd& u, bool corotated, RotationMethod rotation) const {
  double energy = 0.0;
  for (Eigen::Index t = 0; t < mesh_.num_tets(); ++t)
    energy += mesh_.order() == 1 ? tet_energy<4>(t, u, corotated, rotation) : tet_energy<10>(t, u, corotated, rotation);
  return energy;
}

void CutXfemModel::assemble_linear_stiffness(SparseAssembler& assembler, Eigen::VectorXd& rhs_free) const {
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(3 * num_dof_nodes());
  Eigen::VectorXd f_int = zero;
  CorotationStatistics unused;
  ElementBuffers buffers(slots_.cols());
  const RotationMethod rotation = RotationMethod::automatic;   // not used: linear
  const CorotationalTangent tangent = CorotationalTangent::warped;
  for (Eigen::Index t = 0; t < mesh_.num_tets(); ++t) {
    if (branch_.contains(t))
      assemble_branch_tet(t, zero, rotation, tangent, false, f_int, &assembler, &rhs_free, unused);
    else if (mesh_.order() == 1)
      assemble_tet<4>(t, zero, rotation, tangent, false, f_int, &assembler, &rhs_free, unused, buffers);
    else
      assemble_tet<10>(t, zero, rotation, tangent, false, f_int, &assembler, &rhs_free, unused, buffers);
  }
}

Eigen::VectorXd CutXfemModel::gravity_load(double density, const Eigen::Vector3d& g) const {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * num_dof_nodes());
  const int n = mesh_.nodes_per_tet();
  for (Eigen::Index t = 0; t < mesh_.num_tets(); ++t) {
    const std::span<const PhantomPiece> pieces = integrated_pieces(t);
    for (std::size_t p = 0; p < pieces.size(); ++p)
      for (std::size_t q = 0; q < pieces[p].points.size(); ++q) {
        const PiecePoint& point = pieces[p].points[q];
        for (int a = 0; a < n; ++a) {
          const Eigen::Vector3d load = point.weight * density * point.N[a] * g;
          f.segment<3>(3 * mesh_.tets(t, a)) += load;
          const int s = pieces[p].enrichment_slot[static_cast<std::size_t>(a)];
          if (s >= 0) f.segment<3>(3 * slots_(t, s)) += load;
        }
        if (!branch_.contains(t)) continue;
        // The branch rows too: Paulus et al. (section 4.2) drop the body force on every enriched
        // DOF, which is an approximation (int N_a F_l b is not zero in a cut tet), wrong for gravity.
        const Eigen::MatrixXd& value = branch_.piece(t, static_cast<int>(p)).value;
        for (Eigen::Index j = 0; j < value.cols(); ++j)
          f.segment<3>(3 * slots_(t, branch_.first_slot(t) + static_cast<int>(j))) +=
              point.weight * density * value(static_cast<Eigen::Index>(q), j) * g;
      }
  }
  return f;
}

} // namespace kerf
