// CutXfemModel: the field the unknowns describe (cut_xfem_model.hpp's file comment). At a
// point x of piece p of tet t it is the phantom element's, sum_a N_a(x) (u_a + a_k), plus, in a
// tet with branch functions, sum_j phi_j(x) b_j (BranchTets::functions_at). Here: the piece that
// holds a point, the field and its gradient there, the functions it is made of, the same
// functions at the rules' points (chapter 6's masses integrate them), and the phantom mesh.
#include "kerf/xfem/cut_xfem_model.hpp"

#include "kerf/fem/tet_shape_functions.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <limits>

namespace kerf {

void CutXfemModel::slot_values(Eigen::Index t, int p, std::size_t q, Eigen::VectorXd& g) const {
  phantom_slot_values(integrated_pieces(t)[static_cast<std::size_t>(p)], q, mesh_.nodes_per_tet(), g);
  if (!branch_.contains(t)) return;
  const Eigen::MatrixXd& value = branch_.piece(t, p).value;
  for (Eigen::Index j = 0; j < value.cols(); ++j) g[branch_.first_slot(t) + j] = value(static_cast<Eigen::Index>(q), j);
}

void CutXfemModel::slot_gradients(Eigen::Index t, int p, std::size_t q, Eigen::MatrixX3d& g) const {
  phantom_slot_gradients(integrated_pieces(t)[static_cast<std::size_t>(p)], q, mesh_.nodes_per_tet(), g);
  if (branch_.contains(t)) branch_.set_slot_gradients(t, p, q, g);
}

void CutXfemModel::for_each_slot_value(Eigen::Index t,
                                       const std::function<void(int, double, const Eigen::VectorXd&)>& visit) const {
  const std::span<const PhantomPiece> integrated = integrated_pieces(t);
  Eigen::VectorXd g(num_slots(t));
  for (std::size_t p = 0; p < integrated.size(); ++p)
    for (std::size_t q = 0; q < integrated[p].points.size(); ++q) {
      slot_values(t, static_cast<int>(p), q, g);
      visit(static_cast<int>(p), integrated[p].points[q].weight, g);
    }
}

void CutXfemModel::for_each_slot_gradient(
    Eigen::Index t,
    const std::function<void(int, double, const Eigen::VectorXd&, const Eigen::MatrixX3d&)>& visit) const {
  const std::span<const PhantomPiece> integrated = integrated_pieces(t);
  Eigen::VectorXd g(num_slots(t));
  Eigen::MatrixX3d G(num_slots(t), 3);
  for (std::size_t p = 0; p < integrated.size(); ++p)
    for (std::size_t q = 0; q < integrated[p].points.size(); ++q) {
      slot_values(t, static_cast<int>(p), q, g);
      slot_gradients(t, static_cast<int>(p), q, G);
      visit(static_cast<int>(p), integrated[p].points[q].weight, g, G);
    }
}

std::vector<std::pair<int, double>> CutXfemModel::branch_values_at(Eigen::Index t, int p,
                                                                   const Eigen::Vector3d& x) const {
  if (!branch_.contains(t)) return {};
  return branch_values_on_side(t, x, branch_.piece(t, p).side);
}

std::vector<std::pair<int, double>> CutXfemModel::branch_values_on_side(Eigen::Index t, const Eigen::Vector3d& x,
                                                                        int side) const {
  std::vector<std::pair<int, double>> result;
  if (!branch_.contains(t)) return result;
  const Eigen::Matrix<double, 4, Eigen::Dynamic> phi = branch_.functions_at(t, x, side);
  for (Eigen::Index j = 0; j < phi.cols(); ++j)
    result.emplace_back(slots_(t, branch_.first_slot(t) + static_cast<int>(j)), phi(0, j));
  return result;
}

Eigen::MatrixX3d CutXfemModel::phantom_displacements(const Eigen::VectorXd& u, Eigen::Index t, int p) const {
  const int n = mesh_.nodes_per_tet();
  const PhantomPiece& piece = integrated_by_pieces(t)
                                  ? piece_data_[static_cast<std::size_t>(t)][static_cast<std::size_t>(p)]
                                  : whole_->pieces[static_cast<std::size_t>(t)];
  Eigen::MatrixX3d u_p(n, 3);
  for (int a = 0; a < n; ++a) {
    Eigen::Vector3d value = u.segment<3>(3 * mesh_.tets(t, a));
    const int s = piece.enrichment_slot[static_cast<std::size_t>(a)];
    if (s >= 0) value += u.segment<3>(3 * slots_(t, s));
    u_p.row(a) = value.transpose();
  }
  return u_p;
}

Eigen::VectorXd CutXfemModel::shape_values(Eigen::Index t, const Eigen::Vector3d& x) const {
  const Eigen::Matrix<double, 4, 3> X = tet_corners(mesh_, t);
  const Eigen::Vector3d xi = tet_corner_jacobian(X).inverse() * (x - X.row(0).transpose());
  if (mesh_.order() == 1) return tet4_shape(xi);
  return tet10_shape(xi);
}

int CutXfemModel::phantom_node(Eigen::Index t, int p, int a) const {
  const PhantomPiece& piece = integrated_pieces(t)[static_cast<std::size_t>(p)];
  const int s = piece.enrichment_slot[static_cast<std::size_t>(a)];
  return s >= 0 ? slots_(t, s) : mesh_.tets(t, a);
}

PhantomMesh CutXfemModel::phantom_mesh() const {
  const Eigen::Index N = mesh_.num_nodes();
  PhantomMesh phantom;
  phantom.mesh.nodes.resize(num_dof_nodes(), 3);
  phantom.mesh.nodes.topRows(N) = mesh_.nodes;
  for (Eigen::Index k = 0; k < enrichment_.num_enrichments(); ++k)
    phantom.mesh.nodes.row(N + k) = mesh_.nodes.row(enrichment_.enrichment_node[static_cast<std::size_t>(k)]);
  for (int k = 0; k < num_branch_nodes(); ++k)
    for (int l = 0; l < 4; ++l)
      phantom.mesh.nodes.row(branch_dof_node(k) + l) =
          mesh_.nodes.row(tip_->enrichment.branch_node[static_cast<std::size_t>(k)]);
  std::vector<Eigen::Vector4i> tets;
  for (Eigen::Index t = 0; t < mesh_.num_tets(); ++t) {
    const std::span<const PhantomPiece> list = integrated_pieces(t);
    const Eigen::Matrix<double, 4, 3> X = tet_corners(mesh_, t);
    const int e = pieces_.entry[static_cast<std::size_t>(t)];
    for (std::size_t p = 0; p < list.size(); ++p) {
      Eigen::Vector4i corners;
      for (int a = 0; a < 4; ++a) corners[a] = phantom_node(t, static_cast<int>(p), a);
      double volume = 0.0;
      for (const PiecePoint& point : list[p].points) volume += point.weight;
      // A point of the piece: the centre of its largest cell, or of the tet.
      Eigen::Vector3d point = X.colwise().mean().transpose();
      if (integrated_by_pieces(t) && e >= 0 && list.size() > 1) {
        const TetPieces& tp = pieces_.tets[static_cast<std::size_t>(e)];
        double largest = -1.0;
        for (const int c : tp.pieces[p].cells) {
          const double v = convex_cell_volume(tp.cells[static_cast<std::size_t>(c)]);
          if (v <= largest) continue;
          largest = v;
          point = convex_cell_inner_point(tp.cells[static_cast<std::size_t>(c)]);
        }
      }
      tets.push_back(corners);
      phantom.piece_volume.push_back(volume);
      phantom.piece_point.push_back(point);
    }
  }
  phantom.mesh.tets.resize(static_cast<Eigen::Index>(tets.size()), 4);
  for (std::size_t i = 0; i < tets.size(); ++i)
    phantom.mesh.tets.row(static_cast<Eigen::Index>(i)) = tets[i].transpose();
  return phantom;
}

int CutXfemModel::piece_at(Eigen::Index t, const Eigen::Vector3d& x) const {
  if (!integrated_by_pieces(t) || pieces_.num_pieces(t) <= 1) return 0;
  const TetPieces& tp = pieces_.tets[static_cast<std::size_t>(pieces_.entry[static_cast<std::size_t>(t)])];
  const std::vector<int> found = pieces_containing(tp, x, 1e-12 * tp.diameter);
  if (found.empty()) return -1;
  // A point on the cut lies in two or more pieces: take one above a cut (H(0) = +1, as for
  // the home part of a node on the cut, surface_enrichment.hpp), else the first.
  const auto above_a_cut = [&](int q) {
    const std::vector<PieceBoundaryPolygon>& boundary = tp.pieces[static_cast<std::size_t>(q)].boundary;
    return std::any_of(boundary.begin(), boundary.end(),
                       [](const PieceBoundaryPolygon& b) { return b.on_cut && b.cut_side > 0; });
  };
  const auto above = std::find_if(found.begin(), found.end(), above_a_cut);
  return above != found.end() ? *above : found.front();
}

Eigen::Vector3d CutXfemModel::displacement_at(const Eigen::VectorXd& u, Eigen::Index t,
                                              const Eigen::Vector3d& x) const {
  const int p = piece_at(t, x);
  if (p < 0) return Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  const Eigen::MatrixX3d u_p = phantom_displacements(u, t, p);
  Eigen::Vector3d value = (shape_values(t, x).transpose() * u_p).transpose();
  for (const auto& [node, phi] : branch_values_at(t, p, x)) value += phi * u.segment<3>(3 * node);
  return value;
}

Eigen::Matrix3d CutXfemModel::displacement_gradient_at(const Eigen::VectorXd& u, Eigen::Index t,
                                                       const Eigen::Vector3d& x) const {
  const int p = piece_at(t, x);
  if (p < 0) return Eigen::Matrix3d::Constant(std::numeric_limits<double>::quiet_NaN());
  const Eigen::Matrix<double, 4, 3> X = tet_corners(mesh_, t);
  const Eigen::Matrix3d J_inverse = tet_corner_jacobian(X).inverse();
  const Eigen::MatrixX3d G =
      mesh_.order() == 1
          ? Eigen::MatrixX3d(tet4_shape_gradients() * J_inverse)
          : Eigen::MatrixX3d(tet10_shape_gradients(J_inverse * (x - X.row(0).transpose())) * J_inverse);
  // H_ij = sum_a u_p,a,i dN_a/dx_j: the phantom element's gradient, then the branch functions'.
  Eigen::Matrix3d H = phantom_displacements(u, t, p).transpose() * G;
  if (!branch_.contains(t)) return H;
  const Eigen::Matrix<double, 4, Eigen::Dynamic> phi = branch_.functions_at(t, x, branch_.piece(t, p).side);
  for (Eigen::Index j = 0; j < phi.cols(); ++j)
    H += u.segment<3>(3 * slots_(t, branch_.first_slot(t) + static_cast<int>(j))) * phi.block<3, 1>(1, j).transpose();
  return H;
}

CutXfemModel::FunctionsAt CutXfemModel::functions_at(Eigen::Index t, const Eigen::Vector3d& x) const {
  FunctionsAt result;
  const int p = piece_at(t, x);
  if (p < 0) return result;
  const int n = mesh_.nodes_per_tet();
  const PhantomPiece& piece = integrated_pieces(t)[static_cast<std::size_t>(p)];
  const Eigen::Matrix<double, 4, 3> X = tet_corners(mesh_, t);
  const Eigen::Matrix3d J_inverse = tet_corner_jacobian(X).inverse();
  const Eigen::Vector3d xi = J_inverse * (x - X.row(0).transpose());
  const Eigen::VectorXd N = mesh_.order() == 1 ? Eigen::VectorXd(tet4_shape(xi)) : Eigen::VectorXd(tet10_shape(xi));
  const Eigen::MatrixX3d G = mesh_.order() == 1 ? Eigen::MatrixX3d(tet4_shape_gradients() * J_inverse)
                                                : Eigen::MatrixX3d(tet10_shape_gradients(xi) * J_inverse);
  Eigen::Matrix<double, 4, Eigen::Dynamic> phi;
  if (branch_.contains(t)) phi = branch_.functions_at(t, x, branch_.piece(t, p).side);
  const Eigen::Index size = 2 * n + phi.cols();
  result.dof_node.reserve(static_cast<std::size_t>(size));
  result.value.resize(size);
  result.gradient.resize(size, 3);
  Eigen::Index j = 0;
  const auto add = [&](int node, double value, const Eigen::RowVector3d& gradient) {
    result.dof_node.push_back(node);
    result.value[j] = value;
    result.gradient.row(j++) = gradient;
  };
  // The phantom element: u_p,a = u_a + a_k (the class comment), so N_a acts on both.
  for (int a = 0; a < n; ++a) {
    add(mesh_.tets(t, a), N[a], G.row(a));
    if (const int s = piece.enrichment_slot[static_cast<std::size_t>(a)]; s >= 0) add(slots_(t, s), N[a], G.row(a));
  }
  for (Eigen::Index b = 0; b < phi.cols(); ++b)
    add(slots_(t, branch_.first_slot(t) + static_cast<int>(b)), phi(0, b), phi.block<3, 1>(1, b).transpose());
  result.value.conservativeResize(j);
  result.gradient.conservativeResize(j, 3);
  return result;
}

} // namespace kerf
