#include "kerf/xfem/branch_tets.hpp"

#include "kerf/corotation/corotated_piece.hpp"
#include "kerf/cut/point_side.hpp"
#include "kerf/fem/tet_shape_functions.hpp"
#include "kerf/fem/tet_stiffness.hpp"
#include "kerf/quadrature/gauss_piece_rules.hpp"
#include "kerf/xfem/branch_functions.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <utility>

namespace kerf {

namespace {

// The cut triangles one tet was split by, as a surface (for closest_triangle_side).
TriangleSurface local_cut_surface(const TetPieces& pieces) {
  TriangleSurface surface;
  const auto m = static_cast<Eigen::Index>(pieces.triangles.size());
  surface.vertices.resize(3 * m, 3);
  surface.triangles.resize(m, 3);
  for (Eigen::Index k = 0; k < m; ++k)
    for (int c = 0; c < 3; ++c) {
      const std::size_t triangle = static_cast<std::size_t>(k);
      surface.vertices.row(3 * k + c) = pieces.triangles[triangle].corners[static_cast<std::size_t>(c)].transpose();
      surface.triangles(k, c) = static_cast<int>(3 * k + c);
    }
  return surface;
}

} // namespace

BranchTets::BranchTets(const TetMesh& mesh, const MeshPieces& pieces, const CrackTipFunctions* tip,
                       std::vector<int> first_slot)
    : mesh_(&mesh), mesh_pieces_(&pieces), tip_(tip), first_slot_(std::move(first_slot)) {
  const int n = mesh.nodes_per_tet();
  const std::size_t T = static_cast<std::size_t>(mesh.num_tets());
  local_nodes_.assign(T, {});
  nodal_values_.assign(T, {});
  ramp_corners_.assign(T, Eigen::Vector4d::Ones());
  pieces_.assign(T, {});
  for (std::size_t t = 0; t < T; ++t) {
    if (!tip || !tip->enrichment.has_branch_nodes[t]) {
      first_slot_[t] = -1;
      continue;
    }
    const BranchEnrichment& branch = tip->enrichment;
    const auto node_of = [&](int a) { return mesh.tets(static_cast<Eigen::Index>(t), a); };
    for (int a = 0; a < 4; ++a)
      if (branch.branch_slot[static_cast<std::size_t>(node_of(a))] >= 0) local_nodes_[t].push_back(a);
    // Fries's ramp R = sum of the hats of the corners in I* (branch_enrichment.hpp); without
    // the correction R = 1, the sum of all four.
    Eigen::Vector4d& ramp = ramp_corners_[t];
    ramp.setOnes();
    if (branch.blending_correction == BlendingCorrection::corrected)
      for (int a = 0; a < 4; ++a)
        ramp[a] = branch.kind[static_cast<std::size_t>(node_of(a))] == NodeEnrichmentKind::branch ? 1.0 : 0.0;
    // R F at the tet's nodes for the shift: a branch corner's own value (its cut side decided),
    // every other node's from its position, the same in every tet that shares it.
    Eigen::Matrix<double, 4, Eigen::Dynamic>& F_nodes = nodal_values_[t];
    F_nodes.resize(4, n);
    for (int a = 0; a < n; ++a) {
      const int node = node_of(a);
      const int k = branch.branch_slot[static_cast<std::size_t>(node)];
      if (k >= 0) {
        F_nodes.col(a) = branch.node_values[static_cast<std::size_t>(k)];
      } else {
        const FrontPolar polar = tip->fronts.polar(mesh.nodes.row(node).transpose());
        // R at the node: its corner's weight, or the mean of its edge's two (a Tet10 midpoint).
        const double R =
            a < 4 ? ramp[a] : 0.5 * (ramp[tet_edge_corners[a - 4][0]] + ramp[tet_edge_corners[a - 4][1]]);
        F_nodes.col(a) = R * branch_function_values(polar.r, polar.theta);
      }
    }
  }
}

Eigen::Matrix<double, 4, Eigen::Dynamic> BranchTets::functions_at(Eigen::Index t, const Eigen::Vector3d& x,
                                                                   int side) const {
  const std::vector<int>& branch_nodes = local_nodes(t);
  Eigen::Matrix<double, 4, Eigen::Dynamic> result(4, 4 * static_cast<Eigen::Index>(branch_nodes.size()));
  FrontPolar polar = tip_->fronts.polar(x);
  // A tet the front crosses is one piece, so no piece side is known there; behind the front a
  // point takes the side of the closest cut triangle in the tet (Paulus et al.'s test,
  // point_side.hpp), so that on a curved cut F_1 jumps on the cut, not on the frame's half-plane
  // theta = +-pi (without it, a front on a declining sine opened to zero 3 mm behind the front).
  if (side == 0 && polar.x_a < 0.0 && tip_->enrichment.front_tet[static_cast<std::size_t>(t)])
    if (const int e = mesh_pieces_->entry[static_cast<std::size_t>(t)]; e >= 0)
      side = closest_triangle_side(local_cut_surface(mesh_pieces_->tets[static_cast<std::size_t>(e)]), x);
  // Behind the front (x_a < 0) theta = +-pi is the cut; where the cut is curved, the frame's
  // half-plane theta = +-pi is not the cut itself, and a point of a piece above the cut can have
  // x_b < 0. Reflecting b there puts F_1's jump on the cut the pieces follow (Paulus et al.'s
  // frame is piecewise constant and says nothing of curved cuts); on a planar cut the reflection
  // never happens. The reflected functions are G(x) = F(x_a(x), -x_b(x)), so
  // grad G = dF/dx_a grad x_a - dF/dx_b grad x_b: grad x_b changes sign with x_b
  // (branch_functions differentiates through it). A point on the cut itself (a vertex of a
  // piece, |x_b| at round-off) takes its side's value, theta = side * pi (F_1 is two-valued there).
  if (side != 0 && polar.x_a < 0.0 && std::abs(polar.x_b) <= 1e-10 * polar.r) {
    polar.x_b = 0.0;
    polar.theta = side * M_PI;
  } else if (side != 0 && polar.x_a < 0.0 && polar.x_b * side < 0.0) {
    polar.x_b = -polar.x_b;
    polar.theta = -polar.theta;
    polar.b = -polar.b;
    polar.grad_x_b = -polar.grad_x_b;
  }
  const BranchValues at_x = branch_functions(polar);
  const Eigen::Matrix<double, 4, 3> X = tet_corners(*mesh_, t);
  const Eigen::Matrix3d J_inverse = tet_corner_jacobian(X).inverse();
  const Eigen::Vector3d xi = J_inverse * (x - X.row(0).transpose());
  // The partition of unity of the branch functions is the corners' linear hats lambda_v, on a
  // Tet10 too (branch_enrichment.hpp says why its own shape functions would be singular). The
  // shift is the element's nodal interpolant of lambda_v F_l,
  //   phi_{v,l} = lambda_v F_l - sum_i N_i lambda_v(x_i) F_l(x_i),
  // which vanishes at every node (u_i stays the field there) and spans, with the N_i, what
  // lambda_v F_l does. On a Tet4 it is Paulus et al.'s N_v (F_l - F_l(x_v)), shifted; on a Tet10,
  // lambda_v(x_i) is 1 at v, 1/2 at the midpoints of v's edges and 0 elsewhere.
  const Eigen::Vector4d lambda = tet4_shape(xi);
  const Eigen::Matrix<double, 4, 3> grad_lambda = tet4_shape_gradients() * J_inverse;
  Eigen::VectorXd N;
  Eigen::MatrixX3d G;
  if (mesh_->order() == 1) {
    N = lambda;
    G = grad_lambda;
  } else {
    N = tet10_shape(xi);
    G = tet10_shape_gradients(xi) * J_inverse;
  }
  // Fries's ramp (branch_enrichment.hpp): R F and its gradient R dF/dx + F grad R in place of F
  // (R = 1 without the correction, and in every tet whose four corners are in I*).
  const Eigen::Vector4d& ramp = ramp_corners_[static_cast<std::size_t>(t)];
  BranchValues ramped = at_x;
  if (ramp != Eigen::Vector4d::Ones()) {
    const double R = ramp.dot(lambda);
    const Eigen::RowVector3d grad_R = ramp.transpose() * grad_lambda;
    for (int l = 0; l < 4; ++l) {
      ramped.F[l] = R * at_x.F[l];
      ramped.dF_dx.row(l) = R * at_x.dF_dx.row(l) + at_x.F[l] * grad_R;
    }
  }
  const Eigen::Matrix<double, 4, Eigen::Dynamic>& F_nodes = nodal_values_[static_cast<std::size_t>(t)];
  for (std::size_t j = 0; j < branch_nodes.size(); ++j) {
    const int v = branch_nodes[j];
    // sum_i N_i lambda_v(x_i) F(x_i) and its gradient.
    Eigen::Vector4d shift = N[v] * F_nodes.col(v);
    Eigen::Matrix<double, 4, 3> grad_shift = F_nodes.col(v) * G.row(v);
    if (mesh_->order() == 2)
      for (int e = 0; e < 6; ++e)
        if (tet_edge_corners[e][0] == v || tet_edge_corners[e][1] == v) {
          shift += 0.5 * N[4 + e] * F_nodes.col(4 + e);
          grad_shift += 0.5 * F_nodes.col(4 + e) * G.row(4 + e);
        }
    for (int l = 0; l < 4; ++l) {
      const Eigen::Index column = 4 * static_cast<Eigen::Index>(j) + l;
      result(0, column) = lambda[v] * ramped.F[l] - shift[l];
      result.block<3, 1>(1, column) =
          (ramped.F[l] * grad_lambda.row(v) + lambda[v] * ramped.dF_dx.row(l) - grad_shift.row(l)).transpose();
    }
  }
  return result;
}

std::vector<std::vector<PiecePoint>> BranchTets::piece_rules(Eigen::Index t, std::vector<int>& sides) const {
  const int n = mesh_->nodes_per_tet();
  const Eigen::Matrix<double, 4, 3> X = tet_corners(*mesh_, t);
  const bool front_tet = tip_->enrichment.front_tet[static_cast<std::size_t>(t)] != 0;
  const bool collapsed = front_tet && tip_->front_rule == FrontRule::collapsed;
  const int front_points = tip_->front_points > 0 ? tip_->front_points : (n == 4 ? 4 : 6);
  std::vector<std::vector<PiecePoint>> points;
  const int e = mesh_pieces_->entry[static_cast<std::size_t>(t)];
  if (e < 0) {
    // A front tet no cut triangle meets: the front lies in a face of it whose cut chapter 4 gave
    // to the tet on the other side; it is collapsed all the same.
    const TetPieces whole = split_tet_by_triangles(X, {});
    const PieceQuadratureRule r =
        collapsed ? front_collapsed_rule(X, whole, 0, tip_->fronts, front_points, tip_->front_grading)
                  : near_front_graded_rule(whole, 0, tip_->fronts, tip_->blending_degree, tip_->blending_depth,
                                           tip_->blending_tolerance, 2 * mesh_->order());
    points.push_back(piece_points(r, X, n));
    sides.assign(1, 0);
    return points;
  }
  const TetPieces& tet_pieces = mesh_pieces_->tets[static_cast<std::size_t>(e)];
  sides.assign(static_cast<std::size_t>(tet_pieces.num_pieces()), 0);
  for (int p = 0; p < tet_pieces.num_pieces(); ++p) {
    PieceQuadratureRule r;
    if (collapsed)
      r = front_collapsed_rule(X, tet_pieces, p, tip_->fronts, front_points, tip_->front_grading);
    else if (front_tet)
      r = refined_subtet_rule(tet_pieces, p, 2 * front_points - 1, 1);
    else
      r = near_front_graded_rule(tet_pieces, p, tip_->fronts, tip_->blending_degree, tip_->blending_depth,
                                 tip_->blending_tolerance, 2 * mesh_->order());
    points.push_back(piece_points(r, X, n));
    // The side of the cut the piece lies on, where all its cut polygons agree: behind the front,
    // theta's sign is taken from it (functions_at).
    int& side = sides[static_cast<std::size_t>(p)];
    for (const PieceBoundaryPolygon& b : tet_pieces.pieces[static_cast<std::size_t>(p)].boundary)
      if (b.on_cut) side = (side == 0 || side == b.cut_side) ? b.cut_side : 2;
    if (side == 2 || front_tet) side = 0;
  }
  return points;
}

std::vector<PhantomPiece> BranchTets::integrate(Eigen::Index t, const std::vector<std::vector<int>>& enrichment_slots,
                                                const LinearMaterial& material) {
  const int n = mesh_->nodes_per_tet();
  std::vector<int> sides;
  std::vector<std::vector<PiecePoint>> points = piece_rules(t, sides);
  std::vector<PhantomPiece> phantom;
  std::vector<Piece>& branch = pieces_[static_cast<std::size_t>(t)];
  branch.assign(points.size(), Piece{});
  // The branch functions at every point of every piece.
  const Eigen::Index s = 4 * static_cast<Eigen::Index>(local_nodes(t).size());
  for (std::size_t p = 0; p < points.size(); ++p) {
    phantom.push_back(PhantomPiece{enrichment_slots[p], std::move(points[p]), nullptr});
    Piece& piece = branch[p];
    piece.side = sides[p];
    const Eigen::Index m = static_cast<Eigen::Index>(phantom[p].points.size());
    piece.value.resize(m, s);
    piece.gradient.resize(m, 3 * s);
    for (Eigen::Index q = 0; q < m; ++q) {
      const PiecePoint& point = phantom[p].points[static_cast<std::size_t>(q)];
      Eigen::Vector3d x = Eigen::Vector3d::Zero();
      for (int a = 0; a < n; ++a) x += point.N[a] * mesh_->nodes.row(mesh_->tets(t, a)).transpose();
      const Eigen::Matrix<double, 4, Eigen::Dynamic> values = functions_at(t, x, piece.side);
      piece.value.row(q) = values.row(0);
      for (Eigen::Index j = 0; j < s; ++j)
        piece.gradient.row(q).segment<3>(3 * j) = values.col(j).tail<3>().transpose();
    }
  }
  // Each piece's stiffness from the gradient products A = sum_q w_q vec(g_q) vec(g_q)^T, one
  // matrix product per chunk of points (tet_stiffness.hpp: stiffness_from_gradient_products),
  // and its mean slot gradients.
  const int slots = num_slots(t);
  constexpr Eigen::Index chunk = 2048;
  Eigen::MatrixX3d g(slots, 3);
  for (std::size_t p = 0; p < phantom.size(); ++p) {
    Piece& piece = branch[p];
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(3 * slots, 3 * slots);
    piece.mean_gradient = Eigen::MatrixX3d::Zero(slots, 3);
    double volume = 0.0;
    const Eigen::Index m = static_cast<Eigen::Index>(phantom[p].points.size());
    for (Eigen::Index begin = 0; begin < m; begin += chunk) {
      const Eigen::Index rows = std::min(chunk, m - begin);
      Eigen::MatrixXd vec_g(rows, 3 * slots), weighted(rows, 3 * slots);
      for (Eigen::Index r = 0; r < rows; ++r) {
        const std::size_t q = static_cast<std::size_t>(begin + r);
        const double w = phantom[p].points[q].weight;
        phantom_slot_gradients(phantom[p], q, n, g);
        set_slot_gradients(t, static_cast<int>(p), q, g);
        vec_g.row(r) = g.transpose().reshaped().transpose();
        weighted.row(r) = w * vec_g.row(r);
        piece.mean_gradient += w * g;
        volume += w;
      }
      A.noalias() += weighted.transpose() * vec_g;
    }
    piece.stiffness = stiffness_from_gradient_products(A, material.mu(), material.lambda());
    piece.volume = volume;
    if (volume > 0.0) piece.mean_gradient /= volume;
  }
  return phantom;
}

void BranchTets::set_slot_gradients(Eigen::Index t, int p, std::size_t q, Eigen::MatrixX3d& g) const {
  const int first = first_slot(t);
  const Eigen::MatrixXd& gradient = piece(t, p).gradient;
  for (Eigen::Index j = 0; first + j < g.rows(); ++j)
    g.row(first + j) = gradient.row(static_cast<Eigen::Index>(q)).segment<3>(3 * j);
}

void BranchTets::add_forces(Eigen::Index t, const Eigen::MatrixX3d& X, const Eigen::MatrixX3d& q,
                            RotationMethod rotation, CorotationalTangent tangent, bool corotated, Eigen::VectorXd& f_e,
                            Eigen::MatrixXd* K_e, CorotationStatistics& stats) const {
  // f_e = sum over the pieces of K_p q (eq. 30 with every slot's gradient, computed once by
  // integrate); corotated, each piece turned by its own rotation.
  const Eigen::VectorXd q_vector = q.transpose().reshaped();
  for (const Piece& piece : pieces_[static_cast<std::size_t>(t)]) {
    if (corotated) {
      if (!(piece.volume > 0.0)) continue; // no volume, no force (and no mean gradient to turn by)
      add_corotated_piece(piece.stiffness, piece.mean_gradient, mesh_->nodes_per_tet(), X, q, piece.volume, rotation,
                          tangent, f_e, K_e, &stats);
    } else {
      f_e += piece.stiffness * q_vector;
      if (K_e) *K_e += piece.stiffness;
    }
  }
}

double BranchTets::energy(Eigen::Index t, const Eigen::MatrixX3d& X, const Eigen::MatrixX3d& q, bool corotated,
                          RotationMethod rotation) const {
  const int n = mesh_->nodes_per_tet();
  double energy = 0.0;
  for (const Piece& piece : pieces_[static_cast<std::size_t>(t)]) {
    const Eigen::Matrix3d R =
        corotated ? element_rotation(piece_mean_deformation_gradient(piece.mean_gradient, n, X, q), rotation).R
                  : Eigen::Matrix3d::Identity();
    const Eigen::VectorXd d = corotated_piece_displacement(R, n, X, q);
    energy += 0.5 * d.dot(piece.stiffness * d);
  }
  return energy;
}

} // namespace kerf
