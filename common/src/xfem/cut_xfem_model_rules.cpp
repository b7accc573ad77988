// CutXfemModel: the points every tet is integrated at (cut_xfem_model.hpp's file comment).
//
// A tet is integrated in one of four ways:
// - whole, by its own Gauss rule, when no enrichment splits it (no sign enrichment acts in it,
//   or it is one piece): chapter 1's element, whose points depend on the mesh alone and are
//   shared by every model of a growing cut (WholeTets);
// - by the points of the model before, when the cut grew elsewhere and recut kept its pieces
//   (chapter 7): the rule depends only on the pieces, so the costly part is paid once;
// - piece by piece, by the rule the model was given (moment fitting, sub-tets, ...), for a tet
//   that a sign enrichment splits;
// - by BranchTets (chapter 5) when a corner carries branch functions.
#include "kerf/xfem/cut_xfem_model.hpp"

#include "kerf/fem/tet_quadrature.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace kerf {

namespace {

// The reference positions of tet t's n nodes, stacked (3 n).
Eigen::VectorXd nodal_positions(const TetMesh& mesh, Eigen::Index t) {
  const int n = mesh.nodes_per_tet();
  Eigen::VectorXd x_e(3 * n);
  for (int a = 0; a < n; ++a) x_e.segment<3>(3 * a) = mesh.nodes.row(mesh.tets(t, a)).transpose();
  return x_e;
}

} // namespace

std::shared_ptr<const CutXfemModel::WholeTets> CutXfemModel::integrate_whole_tets(const TetMesh& mesh,
                                                                                  const LinearMaterial& material) {
  const int n = mesh.nodes_per_tet();
  const Eigen::Index T = mesh.num_tets();
  const TetQuadratureRule standard = tet_quadrature_rule(n == 4 ? 1 : 2);
  auto whole = std::make_shared<WholeTets>();
  whole->pieces.resize(static_cast<std::size_t>(T));
  whole->position_force_squared.resize(static_cast<std::size_t>(T));
  for (Eigen::Index t = 0; t < T; ++t) {
    const Eigen::Matrix3d J = tet_corner_jacobian(tet_corners(mesh, t));
    const Eigen::Matrix3d J_inverse = J.inverse();
    const double volume_scale = std::abs(J.determinant());
    PhantomPiece& piece = whole->pieces[static_cast<std::size_t>(t)];
    piece.enrichment_slot.assign(static_cast<std::size_t>(n), -1);
    for (std::size_t q = 0; q < standard.points.size(); ++q)
      piece.points.push_back(
          piece_point_at_reference(standard.points[q], J_inverse, standard.weights[q] * volume_scale, n));
    if (n == 4) piece.tet4_stiffness = tet4_piece_stiffness(piece.points, material);
    whole->position_force_squared[static_cast<std::size_t>(t)] =
        (phantom_piece_stiffness(piece.points, n, material) * nodal_positions(mesh, t)).squaredNorm();
  }
  return whole;
}

PhantomPiece CutXfemModel::phantom_piece(Eigen::Index t, int p, std::vector<PiecePoint> points,
                                         std::shared_ptr<const Eigen::Matrix<double, 12, 12>> tet4_stiffness) const {
  PhantomPiece piece{phantom_slots(t, p), std::move(points), nullptr};
  if (mesh_.order() != 1) return piece;
  piece.tet4_stiffness = tet4_stiffness ? std::move(tet4_stiffness) : tet4_piece_stiffness(piece.points, material_);
  return piece;
}

void CutXfemModel::integrate_tet(Eigen::Index t, const CutXfemModel* before) {
  const std::size_t i = static_cast<std::size_t>(t);
  const int n = mesh_.nodes_per_tet();
  const int np = pieces_.num_pieces(t);
  std::vector<PhantomPiece>& integrated = piece_data_[i];
  if (!branch_.contains(t) && (num_sign_slots(t) == 0 || np == 1)) {
    // The whole tet by its own rule (whole_): with no enrichment it is chapter 1's element
    // (nothing is stored); one piece on which some enrichment is 1 takes the same points.
    if (num_sign_slots(t) > 0) {
      const PhantomPiece& whole = whole_->pieces[i];
      integrated.push_back(phantom_piece(t, 0, whole.points, whole.tet4_stiffness));
    }
    position_force_squared_[i] = whole_->position_force_squared[i];
    return;
  }
  if (!branch_.contains(t) && before && pieces_.kept_from_previous[i] && !before->has_branch_functions(t) &&
      before->piece_data_[i].size() == static_cast<std::size_t>(np)) {
    // The same pieces as in `before`, which integrated them by the same rule: its points, with
    // the phantom slots of the enrichments now.
    for (const PhantomPiece& kept : before->piece_data_[i])
      integrated.push_back(phantom_piece(t, static_cast<int>(integrated.size()), kept.points, kept.tet4_stiffness));
    position_force_squared_[i] = before->position_force_squared_[i];
    return;
  }
  if (branch_.contains(t)) {
    // Chapter 5: every piece (or the whole tet) by a rule for the branch functions.
    std::vector<std::vector<int>> enrichment_slots;
    for (int p = 0; p < np; ++p) enrichment_slots.push_back(phantom_slots(t, p));
    integrated = branch_.integrate(t, enrichment_slots, material_);
  } else {
    // A tet a sign enrichment splits: each piece by the rule the model was given, exact to the
    // degree of the stiffness and the load.
    const Eigen::Matrix<double, 4, 3> X = tet_corners(mesh_, t);
    const TetPieces& tet_pieces = pieces_.tets[static_cast<std::size_t>(pieces_.entry[i])];
    const int degree = stiffness_and_load_degree(mesh_.order());
    for (int p = 0; p < np; ++p)
      integrated.push_back(phantom_piece(t, p, piece_points(rule_(X, tet_pieces, p, degree), X, n)));
  }
  // The position force |K X| of each piece's phantom element (the floor of f_int's round-off).
  const Eigen::VectorXd x_e = nodal_positions(mesh_, t);
  for (const PhantomPiece& piece : integrated)
    position_force_squared_[i] += (phantom_piece_stiffness(piece.points, n, material_) * x_e).squaredNorm();
}

std::span<const PhantomPiece> CutXfemModel::integrated_pieces(Eigen::Index t) const {
  const std::vector<PhantomPiece>& split_pieces = piece_data_[static_cast<std::size_t>(t)];
  if (!split_pieces.empty()) return split_pieces;
  return {&whole_->pieces[static_cast<std::size_t>(t)], 1};
}

Eigen::Index CutXfemModel::num_negative_weights() const {
  Eigen::Index count = 0;
  for (const std::vector<PhantomPiece>& list : piece_data_)
    for (const PhantomPiece& piece : list)
      for (const PiecePoint& point : piece.points) count += point.weight < 0.0 ? 1 : 0;
  return count;
}

double CutXfemModel::integrated_volume() const {
  double volume = 0.0;
  for (Eigen::Index t = 0; t < mesh_.num_tets(); ++t)
    for (int p = 0; p < num_integrated_pieces(t); ++p) volume += integrated_volume(t, p);
  return volume;
}

double CutXfemModel::integrated_volume(Eigen::Index t, int p) const {
  const std::span<const PhantomPiece> list = integrated_pieces(t);
  if (p < 0 || static_cast<std::size_t>(p) >= list.size())
    throw std::out_of_range("CutXfemModel::integrated_volume: tet " + std::to_string(t) + " is integrated as " +
                            std::to_string(list.size()) + " piece(s), not " + std::to_string(p + 1));
  double volume = 0.0;
  for (const PiecePoint& point : list[static_cast<std::size_t>(p)].points) volume += point.weight;
  return volume;
}

EnrichmentVolumes CutXfemModel::enrichment_volumes() const {
  return kerf::enrichment_volumes(mesh_, pieces_, enrichment_, [this](Eigen::Index t) {
    std::vector<double> volumes(static_cast<std::size_t>(num_integrated_pieces(t)));
    for (std::size_t p = 0; p < volumes.size(); ++p) volumes[p] = integrated_volume(t, static_cast<int>(p));
    return volumes;
  });
}

Eigen::Index CutXfemModel::num_piece_points() const {
  Eigen::Index count = 0;
  for (const std::vector<PhantomPiece>& list : piece_data_)
    for (const PhantomPiece& piece : list) count += static_cast<Eigen::Index>(piece.points.size());
  return count;
}

} // namespace kerf
