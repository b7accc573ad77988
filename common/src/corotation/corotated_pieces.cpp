#include "kerf/corotation/corotated_pieces.hpp"

#include "kerf/fem/tet_shape_functions.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <stdexcept>

namespace kerf {

namespace {

// The rotation of F, started from R0: Newton's method on the condition that R^T F be symmetric.
// With R = R0 exp([theta]) and A = R0^T F, skew((I - [theta]) A) = 0 to first order gives
//
//   (tr(A) I - sym(A)) theta = (A_32 - A_23, A_13 - A_31, A_21 - A_12),
//
// a 3x3 solve per iteration, converging quadratically: started from the rotation the piece had
// at the last evaluation (a step moves it little) it takes two or three, where Higham's
// iteration from F needs four to six inverses however close the last rotation was (its speed
// depends on the stretch, not on the turn). An inverted F (det F <= 0), a matrix that is not
// positive definite (a turn of over 90 degrees from R0) or no convergence take `method`'s.
Eigen::Matrix3d warm_rotation(const Eigen::Matrix3d& F, const Eigen::Matrix3d& R0, RotationMethod method) {
  if (F.determinant() <= 0.0) return element_rotation(F, method).R;
  Eigen::Matrix3d R = R0;
  for (int iteration = 0; iteration < 8; ++iteration) {
    const Eigen::Matrix3d A = R.transpose() * F;
    const Eigen::Vector3d skew(A(2, 1) - A(1, 2), A(0, 2) - A(2, 0), A(1, 0) - A(0, 1));
    const Eigen::Matrix3d H = A.trace() * Eigen::Matrix3d::Identity() - 0.5 * (A + A.transpose());
    const Eigen::LLT<Eigen::Matrix3d> llt(H);
    if (llt.info() != Eigen::Success) break;
    const Eigen::Vector3d theta = llt.solve(skew);
    const double angle = theta.norm();
    if (angle > 0.0) R = R * Eigen::AngleAxisd(angle, theta / angle).toRotationMatrix();
    if (angle < 1e-12) return R;
  }
  return element_rotation(F, method).R;
}

} // namespace

CorotatedPieces::CorotatedPieces(const CutXfemModel& model, const LinearMaterial& material, RotationMethod rotation)
    : num_dof_nodes_(model.num_dof_nodes()), mu_(material.mu()), lambda_(material.lambda()), rotation_(rotation) {
  const TetMesh& mesh = model.mesh();
  if (mesh.order() != 1) throw std::invalid_argument("CorotatedPieces: the pieces are Tet4's (a Tet10's gradient varies)");
  if (model.num_branch_nodes() > 0)
    throw std::invalid_argument("CorotatedPieces: branch functions are not linear on a piece");
  first_slot_.push_back(0);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    double det_J = 0.0;
    const Eigen::Matrix<double, 4, 3> G = physical_shape_gradients<4>(tet_corners(mesh, t), tet4_shape_gradients(), det_J);
    for (int p = 0; p < model.num_integrated_pieces(t); ++p) {
      volume_.push_back(model.integrated_volume(t, p));
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
    }
  }
}

Eigen::Matrix3d CorotatedPieces::gradient_sum(const Eigen::VectorXd& q, std::size_t p) const {
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  for (int s = first_slot_[p]; s < first_slot_[p + 1]; ++s) sum.noalias() += q.segment<3>(3 * slot_node_[s]) * slot_gradient_[s].transpose();
  return sum;
}

double CorotatedPieces::add_piece_force(std::size_t p, const Eigen::Matrix3d& R, const Eigen::Matrix3d& strain, Eigen::VectorXd& force) const {
  const double trace = strain.trace();
  // V R sigma, sigma = 2 mu strain + lambda tr(strain) I: (8.3) written with the symmetric strain.
  const Eigen::Matrix3d VP = volume_[p] * R * (2.0 * mu_ * strain + lambda_ * trace * Eigen::Matrix3d::Identity());
  for (int s = first_slot_[p]; s < first_slot_[p + 1]; ++s) force.segment<3>(3 * slot_node_[s]) += VP * slot_gradient_[s];
  return volume_[p] * (mu_ * strain.squaredNorm() + 0.5 * lambda_ * trace * trace);
}

double CorotatedPieces::energy(const Eigen::VectorXd& u, Eigen::VectorXd& f_int, std::vector<Eigen::Matrix3d>& rotations) const {
  f_int.setZero(u.size());
  if (rotations.size() != volume_.size()) rotations.assign(volume_.size(), Eigen::Matrix3d::Identity());
  double W = 0.0;
  for (std::size_t p = 0; p < volume_.size(); ++p) {
    const Eigen::Matrix3d F = Eigen::Matrix3d::Identity() + gradient_sum(u, p); // (8.1)
    rotations[p] = warm_rotation(F, rotations[p], rotation_);
    // (8.2), (8.3): the strain R^T F - I, symmetrised against round-off in R.
    const Eigen::Matrix3d RtF = rotations[p].transpose() * F;
    W += add_piece_force(p, rotations[p], 0.5 * (RtF + RtF.transpose()) - Eigen::Matrix3d::Identity(), f_int);
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
    const Eigen::Matrix3d RtD = rotations[p].transpose() * gradient_sum(d, p);
    half_dKd += add_piece_force(p, rotations[p], 0.5 * (RtD + RtD.transpose()), K_d);
  }
  return half_dKd;
}

Eigen::SparseMatrix<double> CorotatedPieces::laplacian() const {
  std::vector<Eigen::Triplet<double>> entries;
  for (std::size_t p = 0; p < volume_.size(); ++p)
    for (int s = first_slot_[p]; s < first_slot_[p + 1]; ++s)
      for (int r = first_slot_[p]; r < first_slot_[p + 1]; ++r)
        entries.emplace_back(slot_node_[s], slot_node_[r], volume_[p] * slot_gradient_[s].dot(slot_gradient_[r]));
  Eigen::SparseMatrix<double> L(num_dof_nodes_, num_dof_nodes_);
  L.setFromTriplets(entries.begin(), entries.end());
  return L;
}

} // namespace kerf
