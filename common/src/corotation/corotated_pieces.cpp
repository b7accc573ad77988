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

CorotatedPieces::CorotatedPieces(const CutXfemModel& model, const LinearMaterial& material, RotationMethod rotation,
                                 const CorotatedPieces* before)
    : num_dof_nodes_(model.num_dof_nodes()), num_mesh_nodes_(model.mesh().num_nodes()), mu_(material.mu()), lambda_(material.lambda()),
      rotation_(rotation), num_tets_(static_cast<std::size_t>(model.mesh().num_tets())) {
  const TetMesh& mesh = model.mesh();
  if (mesh.order() != 1) throw std::invalid_argument("CorotatedPieces: the pieces are Tet4's (a Tet10's gradient varies)");
  if (model.num_branch_nodes() > 0)
    throw std::invalid_argument("CorotatedPieces: branch functions are not linear on a piece");
  if (before && (before->num_tets_ != num_tets_ || before->num_mesh_nodes_ != num_mesh_nodes_))
    throw std::invalid_argument("CorotatedPieces: the earlier pieces are of another mesh");
  whole_ = before ? before->whole_ : nullptr;
  if (!whole_) {
    auto whole = std::make_shared<WholeTets>();
    whole->node.resize(4 * num_tets_);
    whole->gradient.resize(4 * num_tets_);
    whole->volume.resize(num_tets_);
    for (std::size_t t = 0; t < num_tets_; ++t) {
      double det_J = 0.0;
      const auto T = static_cast<Eigen::Index>(t);
      const Eigen::Matrix<double, 4, 3> G = physical_shape_gradients<4>(tet_corners(mesh, T), tet4_shape_gradients(), det_J);
      whole->volume[t] = std::abs(det_J) / 6.0;
      for (int a = 0; a < 4; ++a) {
        whole->node[4 * t + static_cast<std::size_t>(a)] = mesh.tets(T, a);
        whole->gradient[4 * t + static_cast<std::size_t>(a)] = G.row(a).transpose();
      }
    }
    whole->blocks.resize(num_tets_ / 4);
    for (std::size_t k = 0; k < whole->blocks.size(); ++k) {
      PieceBlock& block = whole->blocks[k];
      for (int lane = 0; lane < 4; ++lane) {
        const std::size_t t = 4 * k + static_cast<std::size_t>(lane);
        block.piece[lane] = t;
        for (int a = 0; a < 4; ++a) {
          block.dof[a][lane] = 3 * whole->node[4 * t + static_cast<std::size_t>(a)];
          for (int i = 0; i < 3; ++i) block.gradient[a][i][lane] = whole->gradient[4 * t + static_cast<std::size_t>(a)][i];
        }
      }
    }
    whole_ = std::move(whole);
  }

  // The special tets: those the model integrates by pieces, and those on which a node's
  // enrichment acts (only a tet around an enriched node can be one): both found from the cut,
  // not from the mesh.
  std::vector<char> special(num_tets_, 0);
  for (const int t : model.pieces().entry_tet)
    if (model.integrated_by_pieces(t)) special[static_cast<std::size_t>(t)] = 1;
  for (const int node : model.enrichment().enrichment_node)
    for (const int t : model.pieces().neighbours->node_tets[static_cast<std::size_t>(node)]) {
      char& is_special = special[static_cast<std::size_t>(t)];
      for (int p = 0; p < model.num_integrated_pieces(t) && !is_special; ++p)
        for (int a = 0; a < 4; ++a) is_special = is_special || model.phantom_node(t, p, a) != mesh.tets(t, a);
    }
  whole_volume_ = whole_->volume;
  first_slot_.push_back(0);
  for (std::size_t t = 0; t < num_tets_; ++t) {
    if (!special[t]) continue;
    special_tets_.push_back(static_cast<int>(t));
    whole_volume_[t] = 0.0;
    const auto T = static_cast<Eigen::Index>(t);
    double pieces_volume = 0.0;
    for (int p = 0; p < model.num_integrated_pieces(T); ++p) {
      volume_.push_back(model.integrated_volume(T, p));
      piece_tet_.push_back(static_cast<int>(t));
      pieces_volume += volume_.back();
      for (int a = 0; a < 4; ++a) {
        const int node = mesh.tets(T, a);
        const Eigen::Vector3d& g = whole_->gradient[4 * t + static_cast<std::size_t>(a)];
        slot_node_.push_back(node);
        slot_gradient_.push_back(g);
        // The phantom node's enrichment, if one is active on this piece: u_a + a_k.
        const int phantom = model.phantom_node(T, p, a);
        if (phantom != node) {
          slot_node_.push_back(phantom);
          slot_gradient_.push_back(g);
        }
      }
      first_slot_.push_back(static_cast<int>(slot_node_.size()));
      if (first_slot_.back() - first_slot_[first_slot_.size() - 2] > 4) enriched_pieces_.push_back(num_tets_ + volume_.size() - 1);
    }
    largest_volume_mismatch_ = std::max(largest_volume_mismatch_, std::abs(pieces_volume - whole_->volume[t]) / whole_->volume[t]);
  }
  // The special pieces four to a block; the whole tets' blocks leave the last num_tets_ % 4.
  const std::size_t special_pieces = volume_.size();
  special_blocks_.resize((special_pieces + 3) / 4);
  special_block_volume_.assign(4 * special_blocks_.size(), 0.0);
  for (std::size_t k = 0; k < special_blocks_.size(); ++k) {
    SpecialBlock& block = special_blocks_[k];
    for (int lane = 0; lane < 4; ++lane) {
      const std::size_t index = 4 * k + static_cast<std::size_t>(lane);
      const bool present = index < special_pieces;
      const std::size_t q = present ? index : 4 * k; // a lane without a piece repeats lane 0's, with no volume
      if (present) special_block_volume_[index] = volume_[q];
      block.piece[lane] = num_tets_ + q;
      const Slots slot = slots(num_tets_ + q);
      if (slot.count > 8) throw std::logic_error("CorotatedPieces: a piece with more than eight slots");
      for (int s = 0; s < slot.count; ++s) {
        block.dof[s][lane] = 3 * slot.node[s];
        for (int i = 0; i < 3; ++i) block.gradient[s][i][lane] = slot.gradient[s][i];
      }
      for (int s = slot.count; s < 8; ++s) block.dof[s][lane] = 3 * slot.node[0]; // a zero gradient: adds nothing
    }
  }
  for (std::size_t t = 4 * whole_->blocks.size(); t < num_tets_; ++t)
    if (!special[t]) unblocked_.push_back(t);
}

CorotatedPieces::Slots CorotatedPieces::slots(std::size_t p) const {
  if (p < num_tets_) return {&whole_->node[4 * p], &whole_->gradient[4 * p], 4};
  const std::size_t q = p - num_tets_;
  const auto first = static_cast<std::size_t>(first_slot_[q]);
  return {&slot_node_[first], &slot_gradient_[first], first_slot_[q + 1] - first_slot_[q]};
}

Eigen::Matrix3d CorotatedPieces::gradient_sum(const Eigen::VectorXd& q, std::size_t p) const {
  const Slots slot = slots(p);
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  for (int s = 0; s < slot.count; ++s) sum.noalias() += q.segment<3>(3 * slot.node[s]) * slot.gradient[s].transpose();
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
  const Slots slot = slots(p);
  for (int s = 0; s < slot.count; ++s) force.segment<3>(3 * slot.node[s]).noalias() += VP * slot.gradient[s];
}

// The symmetric part of a 3x3 matrix.
static Eigen::Matrix3d symmetric_part(const Eigen::Matrix3d& A) { return 0.5 * (A + A.transpose()); }

double CorotatedPieces::energy(const Eigen::VectorXd& u, Eigen::VectorXd& f_int, std::vector<Eigen::Matrix3d>& rotations) const {
  f_int.setZero(u.size());
  const auto n = static_cast<std::size_t>(num_pieces());
  if (rotations.size() != n) rotations.assign(n, Eigen::Matrix3d::Identity());
  double W = 0.0;
  for (std::size_t p = 0; p < n; ++p) {
    if (volume(p) == 0.0) continue; // a special tet's whole piece
    const Eigen::Matrix3d F = Eigen::Matrix3d::Identity() + gradient_sum(u, p); // (8.1)
    const Eigen::Matrix3d& R = rotations[p] = warm_rotation(F, rotations[p], rotation_, exact_turn);
    // (8.2), (8.3): the strain R^T F - I, symmetrised against round-off in R; P = R sigma.
    const Eigen::Matrix3d strain = symmetric_part(R.transpose() * F) - Eigen::Matrix3d::Identity();
    W += volume(p) * energy_density(strain);
    add_piece_force(p, volume(p) * R * stress(strain), f_int);
  }
  return W;
}

void CorotatedPieces::warm_rotations(std::vector<Eigen::Matrix3d>& rotations) const {
  if (rotations.size() < num_tets_) throw std::invalid_argument("CorotatedPieces::warm_rotations: expected one rotation per tet at least");
  rotations.resize(num_tets_ + piece_tet_.size());
  for (std::size_t q = 0; q < piece_tet_.size(); ++q) rotations[num_tets_ + q] = rotations[static_cast<std::size_t>(piece_tet_[q])];
}

double CorotatedPieces::warped_product(const std::vector<Eigen::Matrix3d>& rotations, const Eigen::VectorXd& d,
                                       Eigen::VectorXd& K_d) const {
  const auto n = static_cast<std::size_t>(num_pieces());
  if (rotations.size() != n) throw std::invalid_argument("CorotatedPieces::warped_product: expected one rotation per piece");
  K_d.setZero(d.size());
  double half_dKd = block_warped_product(rotations, d, K_d);
  for (std::size_t p : unblocked_) {
    // The linear strain sym(R^T D) of the displacement d seen in the piece's turned frame.
    const Eigen::Matrix3d strain = symmetric_part(rotations[p].transpose() * gradient_sum(d, p));
    half_dKd += volume(p) * energy_density(strain);
    add_piece_force(p, volume(p) * rotations[p] * stress(strain), K_d);
  }
  return half_dKd;
}

std::vector<Eigen::Matrix3d> CorotatedPieces::gradient_sums(const Eigen::VectorXd& q) const {
  std::vector<Eigen::Matrix3d> sums;
  gradient_sums(q, sums);
  return sums;
}

void CorotatedPieces::gradient_sums(const Eigen::VectorXd& q, std::vector<Eigen::Matrix3d>& sums) const {
  sums.resize(static_cast<std::size_t>(num_pieces()));
  // Every special piece and the whole tets of the blocks four at a time, then the tets after
  // the last whole block (special or not) one by one.
  block_gradient_sums(q, sums);
  for (std::size_t t = 4 * whole_->blocks.size(); t < num_tets_; ++t) sums[t] = gradient_sum(q, t);
}

CorotatedPieces::StepTerms CorotatedPieces::step_terms(const Eigen::VectorXd& u, const std::vector<Eigen::Matrix3d>& reference_sums,
                                                       double c, const std::vector<Eigen::Matrix3d>& turned, Eigen::VectorXd& force,
                                                       std::vector<Eigen::Matrix3d>& rotations, double turn_tolerance) const {
  const auto n = static_cast<std::size_t>(num_pieces());
  if (reference_sums.size() != n || turned.size() != n)
    throw std::invalid_argument("CorotatedPieces::step_terms: expected one reference sum and one rotation per piece");
  force.setZero(u.size());
  if (rotations.size() != n) rotations.assign(n, Eigen::Matrix3d::Identity());
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
  const double V = volume(p);
  add_piece_force(p, V * (R * stress(strain) + c * (Q * stress(rate_strain))), force);
  return {V * energy_density(strain), V * energy_density(rate_strain)};
}

Eigen::SparseMatrix<double> CorotatedPieces::laplacian_of(const std::vector<std::size_t>& pieces, bool enrichment_rows_only) const {
  std::vector<Eigen::Triplet<double>> entries;
  for (std::size_t p : pieces) {
    const double V = volume(p);
    if (V == 0.0) continue; // a special tet's whole piece adds nothing
    const Slots slot = slots(p);
    for (int s = 0; s < slot.count; ++s)
      for (int r = 0; r < slot.count; ++r)
        if (!enrichment_rows_only || slot.node[s] >= num_mesh_nodes_ || slot.node[r] >= num_mesh_nodes_)
          entries.emplace_back(slot.node[s], slot.node[r], V * slot.gradient[s].dot(slot.gradient[r]));
  }
  Eigen::SparseMatrix<double> L(num_dof_nodes_, num_dof_nodes_);
  L.setFromTriplets(entries.begin(), entries.end());
  return L;
}

Eigen::SparseMatrix<double> CorotatedPieces::laplacian() const {
  std::vector<std::size_t> all(static_cast<std::size_t>(num_pieces()));
  for (std::size_t p = 0; p < all.size(); ++p) all[p] = p;
  return laplacian_of(all, false);
}

Eigen::SparseMatrix<double> CorotatedPieces::enrichment_laplacian() const { return laplacian_of(enriched_pieces_, true); }

} // namespace kerf
