#include "kerf/corotation/corotated_pieces.hpp"

#include "kerf/fem/tet_shape_functions.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace kerf {

namespace {

// The rotation of F, started from R0: Newton's method on the condition that R^T F be symmetric.
// With R = R0 exp([theta]) and A = R0^T F, skew((I - [theta]) A) = 0 to first order gives
//
//   (tr(A) I - sym(A)) theta = (A_32 - A_23, A_13 - A_31, A_21 - A_12),
//
// a 3x3 solve per iteration (by cofactors), converging quadratically; R turns by the Cayley
// transform of theta, which is exp([theta]) to second order and exactly a rotation. Started from
// the rotation the piece had at the last evaluation (a step moves it little) it takes one or two
// iterations, where Higham's iteration from F needs four to six inverses however close the last
// rotation was (its speed depends on the stretch, not on the turn). It stops after a correction
// smaller than `tolerance` (rad): the rotation is then within about its square of the polar one
// (1e-7: to round-off). An inverted F (det F <= 0), a matrix that is
// not positive definite (a turn of over 90 degrees from R0) or no convergence take `method`'s.
Eigen::Matrix3d warm_rotation(const Eigen::Matrix3d& F, const Eigen::Matrix3d& R0, RotationMethod method, double tolerance) {
  if (F.determinant() <= 0.0) return element_rotation(F, method).R;
  Eigen::Matrix3d R = R0;
  for (int iteration = 0; iteration < 8; ++iteration) {
    const Eigen::Matrix3d A = R.transpose() * F;
    const Eigen::Vector3d skew(A(2, 1) - A(1, 2), A(0, 2) - A(2, 0), A(1, 0) - A(0, 1));
    const Eigen::Matrix3d H = A.trace() * Eigen::Matrix3d::Identity() - 0.5 * (A + A.transpose());
    // The adjugate of the symmetric H (its cofactors), and det H.
    Eigen::Matrix3d H_adjugate;
    H_adjugate(0, 0) = H(1, 1) * H(2, 2) - H(1, 2) * H(1, 2);
    H_adjugate(1, 1) = H(0, 0) * H(2, 2) - H(0, 2) * H(0, 2);
    H_adjugate(2, 2) = H(0, 0) * H(1, 1) - H(0, 1) * H(0, 1);
    H_adjugate(0, 1) = H_adjugate(1, 0) = H(0, 2) * H(1, 2) - H(0, 1) * H(2, 2);
    H_adjugate(0, 2) = H_adjugate(2, 0) = H(0, 1) * H(1, 2) - H(0, 2) * H(1, 1);
    H_adjugate(1, 2) = H_adjugate(2, 1) = H(0, 1) * H(0, 2) - H(0, 0) * H(1, 2);
    const double det_H = H.row(0).dot(H_adjugate.col(0));
    if (!(det_H > 0.0 && H(0, 0) > 0.0)) break;
    const Eigen::Vector3d w = (0.5 / det_H) * (H_adjugate * skew); // theta / 2
    // Cayley: (I - [w])^{-1} (I + [w]) = I + 2 ([w] + [w]^2) / (1 + |w|^2), [w]^2 = w w^T - |w|^2 I.
    const double w2 = w.squaredNorm();
    Eigen::Matrix3d turn = w * w.transpose() - w2 * Eigen::Matrix3d::Identity();
    turn(0, 1) -= w.z(), turn(1, 0) += w.z(), turn(0, 2) += w.y(), turn(2, 0) -= w.y(), turn(1, 2) -= w.x(), turn(2, 1) += w.x();
    R = R * (Eigen::Matrix3d::Identity() + (2.0 / (1.0 + w2)) * turn);
    if (4.0 * w2 < tolerance * tolerance) return R;
  }
  return element_rotation(F, method).R;
}

// The tolerance of energy() and warped_product()'s rotations: the polar one to round-off.
constexpr double exact_turn = 1e-7;

} // namespace

CorotatedPieces::CorotatedPieces(const CutXfemModel& model, const LinearMaterial& material, RotationMethod rotation)
    : num_dof_nodes_(model.num_dof_nodes()), num_mesh_nodes_(model.mesh().num_nodes()), mu_(material.mu()), lambda_(material.lambda()), rotation_(rotation) {
  const TetMesh& mesh = model.mesh();
  if (mesh.order() != 1) throw std::invalid_argument("CorotatedPieces: the pieces are Tet4's (a Tet10's gradient varies)");
  if (model.num_branch_nodes() > 0)
    throw std::invalid_argument("CorotatedPieces: branch functions are not linear on a piece");
  first_slot_.push_back(0);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    double det_J = 0.0;
    const Eigen::Matrix<double, 4, 3> G = physical_shape_gradients<4>(tet_corners(mesh, t), tet4_shape_gradients(), det_J);
    double pieces_volume = 0.0;
    for (int p = 0; p < model.num_integrated_pieces(t); ++p) {
      volume_.push_back(model.integrated_volume(t, p));
      pieces_volume += volume_.back();
      for (int a = 0; a < 4; ++a) {
        const int node = mesh.tets(t, a);
        slot_node_.push_back(node);
        slot_gradient_.push_back(G.row(a).transpose());
        // The phantom node's enrichment, if one is active on this piece: u_a + a_k.
        const int phantom = model.phantom_node(t, p, a);
        if (phantom != node) {
          slot_node_.push_back(phantom);
          slot_gradient_.push_back(G.row(a).transpose());
        }
      }
      first_slot_.push_back(static_cast<int>(slot_node_.size()));
      if (first_slot_.back() - first_slot_[first_slot_.size() - 2] > 4) enriched_pieces_.push_back(volume_.size() - 1);
    }
    const double tet_volume = std::abs(det_J) / 6.0;
    largest_volume_mismatch_ = std::max(largest_volume_mismatch_, std::abs(pieces_volume - tet_volume) / tet_volume);
  }
  // The blocks: the four-slot pieces in order, four at a time.
  std::vector<std::size_t> simple;
  for (std::size_t p = 0; p < volume_.size(); ++p) (first_slot_[p + 1] - first_slot_[p] == 4 ? simple : unblocked_).push_back(p);
  const std::size_t full = simple.size() / 4 * 4;
  unblocked_.insert(unblocked_.end(), simple.begin() + static_cast<std::ptrdiff_t>(full), simple.end());
  for (std::size_t k = 0; k < full; k += 4) {
    PieceBlock block;
    for (int lane = 0; lane < 4; ++lane) {
      const std::size_t p = simple[k + static_cast<std::size_t>(lane)];
      block.piece[lane] = p;
      block.volume[lane] = volume_[p];
      for (int a = 0; a < 4; ++a) {
        const int s = first_slot_[p] + a;
        block.dof[a][lane] = 3 * slot_node_[s];
        for (int i = 0; i < 3; ++i) block.gradient[a][i][lane] = slot_gradient_[s][i];
      }
    }
    blocks_.push_back(block);
  }
}

Eigen::Matrix3d CorotatedPieces::gradient_sum(const Eigen::VectorXd& q, std::size_t p) const {
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  for (int s = first_slot_[p]; s < first_slot_[p + 1]; ++s) sum.noalias() += q.segment<3>(3 * slot_node_[s]) * slot_gradient_[s].transpose();
  return sum;
}

Eigen::Matrix3d CorotatedPieces::stress(const Eigen::Matrix3d& strain) const {
  return 2.0 * mu_ * strain + lambda_ * strain.trace() * Eigen::Matrix3d::Identity();
}

double CorotatedPieces::energy_density(const Eigen::Matrix3d& strain) const {
  const double trace = strain.trace();
  return mu_ * strain.squaredNorm() + 0.5 * lambda_ * trace * trace;
}

void CorotatedPieces::add_piece_force(std::size_t p, const Eigen::Matrix3d& VP, Eigen::VectorXd& force) const {
  for (int s = first_slot_[p]; s < first_slot_[p + 1]; ++s) force.segment<3>(3 * slot_node_[s]).noalias() += VP * slot_gradient_[s];
}

// The symmetric part of a 3x3 matrix.
static Eigen::Matrix3d symmetric_part(const Eigen::Matrix3d& A) { return 0.5 * (A + A.transpose()); }

double CorotatedPieces::energy(const Eigen::VectorXd& u, Eigen::VectorXd& f_int, std::vector<Eigen::Matrix3d>& rotations) const {
  f_int.setZero(u.size());
  if (rotations.size() != volume_.size()) rotations.assign(volume_.size(), Eigen::Matrix3d::Identity());
  double W = 0.0;
  for (std::size_t p = 0; p < volume_.size(); ++p) {
    const Eigen::Matrix3d F = Eigen::Matrix3d::Identity() + gradient_sum(u, p); // (8.1)
    const Eigen::Matrix3d& R = rotations[p] = warm_rotation(F, rotations[p], rotation_, exact_turn);
    // (8.2), (8.3): the strain R^T F - I, symmetrised against round-off in R; P = R sigma.
    const Eigen::Matrix3d strain = symmetric_part(R.transpose() * F) - Eigen::Matrix3d::Identity();
    W += volume_[p] * energy_density(strain);
    add_piece_force(p, volume_[p] * R * stress(strain), f_int);
  }
  return W;
}

double CorotatedPieces::warped_product(const std::vector<Eigen::Matrix3d>& rotations, const Eigen::VectorXd& d,
                                       Eigen::VectorXd& K_d) const {
  if (rotations.size() != volume_.size())
    throw std::invalid_argument("CorotatedPieces::warped_product: expected one rotation per piece");
  K_d.setZero(d.size());
  double half_dKd = 0.0;
  for (std::size_t p = 0; p < volume_.size(); ++p) {
    // The linear strain sym(R^T D) of the displacement d seen in the piece's turned frame.
    const Eigen::Matrix3d strain = symmetric_part(rotations[p].transpose() * gradient_sum(d, p));
    half_dKd += volume_[p] * energy_density(strain);
    add_piece_force(p, volume_[p] * rotations[p] * stress(strain), K_d);
  }
  return half_dKd;
}

std::vector<Eigen::Matrix3d> CorotatedPieces::gradient_sums(const Eigen::VectorXd& q) const {
  std::vector<Eigen::Matrix3d> sums(volume_.size());
  for (std::size_t p = 0; p < volume_.size(); ++p) sums[p] = gradient_sum(q, p);
  return sums;
}

CorotatedPieces::StepTerms CorotatedPieces::step_terms(const Eigen::VectorXd& u, const std::vector<Eigen::Matrix3d>& reference_sums,
                                                       double c, const std::vector<Eigen::Matrix3d>& turned, Eigen::VectorXd& force,
                                                       std::vector<Eigen::Matrix3d>& rotations, double turn_tolerance) const {
  if (reference_sums.size() != volume_.size() || turned.size() != volume_.size())
    throw std::invalid_argument("CorotatedPieces::step_terms: expected one reference sum and one rotation per piece");
  force.setZero(u.size());
  if (rotations.size() != volume_.size()) rotations.assign(volume_.size(), Eigen::Matrix3d::Identity());
  StepTerms terms = block_step_terms(u, reference_sums, c, turned, force, rotations, turn_tolerance);
  for (std::size_t p : unblocked_) {
    const StepTerms piece = piece_step_terms(p, u, reference_sums[p], c, turned[p], force, rotations[p], turn_tolerance);
    terms.W += piece.W;
    terms.half_dKd += piece.half_dKd;
  }
  return terms;
}

CorotatedPieces::StepTerms CorotatedPieces::piece_step_terms(std::size_t p, const Eigen::VectorXd& u, const Eigen::Matrix3d& reference_sum,
                                                             double c, const Eigen::Matrix3d& turned, Eigen::VectorXd& force,
                                                             Eigen::Matrix3d& rotation, double turn_tolerance) const {
  // One gather serves both terms: F - I for the elastic one, F - I - (sum of u_ref) = D for K_R d.
  const Eigen::Matrix3d grad_u = gradient_sum(u, p);
  const Eigen::Matrix3d F = Eigen::Matrix3d::Identity() + grad_u;
  const Eigen::Matrix3d& R = rotation = warm_rotation(F, rotation, rotation_, turn_tolerance);
  const Eigen::Matrix3d strain = symmetric_part(R.transpose() * F) - Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d& Q = turned;
  const Eigen::Matrix3d rate_strain = symmetric_part(Q.transpose() * (grad_u - reference_sum));
  // One scatter: V (R sigma(strain) + c Q sigma(rate_strain)) g_s.
  add_piece_force(p, volume_[p] * (R * stress(strain) + c * (Q * stress(rate_strain))), force);
  return {volume_[p] * energy_density(strain), volume_[p] * energy_density(rate_strain)};
}

Eigen::SparseMatrix<double> CorotatedPieces::laplacian_of(const std::vector<std::size_t>& pieces, bool enrichment_rows_only) const {
  std::vector<Eigen::Triplet<double>> entries;
  for (std::size_t p : pieces)
    for (int s = first_slot_[p]; s < first_slot_[p + 1]; ++s)
      for (int r = first_slot_[p]; r < first_slot_[p + 1]; ++r)
        if (!enrichment_rows_only || slot_node_[s] >= num_mesh_nodes_ || slot_node_[r] >= num_mesh_nodes_)
          entries.emplace_back(slot_node_[s], slot_node_[r], volume_[p] * slot_gradient_[s].dot(slot_gradient_[r]));
  Eigen::SparseMatrix<double> L(num_dof_nodes_, num_dof_nodes_);
  L.setFromTriplets(entries.begin(), entries.end());
  return L;
}

Eigen::SparseMatrix<double> CorotatedPieces::laplacian() const {
  std::vector<std::size_t> all(volume_.size());
  for (std::size_t p = 0; p < all.size(); ++p) all[p] = p;
  return laplacian_of(all, false);
}

Eigen::SparseMatrix<double> CorotatedPieces::enrichment_laplacian() const { return laplacian_of(enriched_pieces_, true); }

} // namespace kerf
