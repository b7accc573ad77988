#include "kerf/xfem/cut_xfem_model.hpp"

#include "kerf/corotation/corotated_element.hpp"
#include "kerf/corotation/corotated_piece.hpp"
#include "kerf/cut/point_side.hpp"
#include "kerf/fem/tet_quadrature.hpp"
#include "kerf/fem/tet_shape_functions.hpp"
#include "kerf/fem/rigid_motion_check.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/fem/tet_stiffness.hpp"
#include "kerf/quadrature/front_quadrature.hpp"
#include "kerf/quadrature/gauss_piece_rules.hpp"
#include "kerf/xfem/branch_functions.hpp"
#include "kerf/xfem/branch_null_space.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace kerf {

namespace {

using Corners = Eigen::Matrix<double, 4, 3>;

// J = [x1 - x0, x2 - x0, x3 - x0]: the straight-edged tet's map from reference coordinates.
Eigen::Matrix3d corner_jacobian(const Corners& X) {
  Eigen::Matrix3d J;
  for (int c = 0; c < 3; ++c) J.col(c) = (X.row(c + 1) - X.row(0)).transpose();
  return J;
}

// The cut triangles one tet was split by, as a surface (for closest_triangle_side).
TriangleSurface local_cut_surface(const TetPieces& pieces) {
  TriangleSurface surface;
  const auto m = static_cast<Eigen::Index>(pieces.triangles.size());
  surface.vertices.resize(3 * m, 3);
  surface.triangles.resize(m, 3);
  for (Eigen::Index k = 0; k < m; ++k)
    for (int c = 0; c < 3; ++c) {
      surface.vertices.row(3 * k + c) = pieces.triangles[static_cast<std::size_t>(k)].corners[static_cast<std::size_t>(c)].transpose();
      surface.triangles(k, c) = static_cast<int>(3 * k + c);
    }
  return surface;
}

// A quadrature point at reference coordinates xi of a straight-edged tet with inverse Jacobian
// J_inverse: its weight (m^3) and the n shape functions' values and physical gradients there.
template <class Point>
Point point_at_reference(const Eigen::Vector3d& xi, const Eigen::Matrix3d& J_inverse, double weight, int n) {
  Point point;
  point.weight = weight;
  if (n == 4) {
    point.N.template head<4>() = tet4_shape(xi);
    point.G.template topRows<4>() = tet4_shape_gradients() * J_inverse;
  } else {
    point.N = tet10_shape(xi);
    point.G = tet10_shape_gradients(xi) * J_inverse;
  }
  return point;
}

// The stiffness of one phantom element over a piece's points (eq. 30), n x n nodes.
template <class Point>
Eigen::MatrixXd piece_stiffness(const std::vector<Point>& points, int n, const LinearMaterial& material) {
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(3 * n, 3 * n);
  for (const Point& point : points) {
    if (n == 4) {
      Eigen::Matrix<double, 12, 12> Kq = Eigen::Matrix<double, 12, 12>::Zero();
      add_stiffness_integrand<4>(point.G.template topRows<4>(), point.weight, material.mu(), material.lambda(), Kq);
      K += Kq;
    } else {
      Eigen::Matrix<double, 30, 30> Kq = Eigen::Matrix<double, 30, 30>::Zero();
      add_stiffness_integrand<10>(point.G, point.weight, material.mu(), material.lambda(), Kq);
      K += Kq;
    }
  }
  return K;
}

// The reference positions of tet t's n nodes, stacked (3 n).
Eigen::VectorXd nodal_positions(const TetMesh& mesh, Eigen::Index t) {
  const int n = mesh.nodes_per_tet();
  Eigen::VectorXd x_e(3 * n);
  for (int a = 0; a < n; ++a) x_e.segment<3>(3 * a) = mesh.nodes.row(mesh.tets(t, a)).transpose();
  return x_e;
}

} // namespace

std::shared_ptr<const CutXfemModel::WholeTets> CutXfemModel::integrate_whole_tets(const TetMesh& mesh, const LinearMaterial& material) {
  const int n = mesh.nodes_per_tet();
  const Eigen::Index T = mesh.num_tets();
  const TetQuadratureRule standard = tet_quadrature_rule(n == 4 ? 1 : 2);
  auto whole = std::make_shared<WholeTets>();
  whole->pieces.resize(static_cast<std::size_t>(T));
  whole->position_force_squared.resize(static_cast<std::size_t>(T));
  for (Eigen::Index t = 0; t < T; ++t) {
    const Corners X = tet_corners(mesh, t);
    const Eigen::Matrix3d J = corner_jacobian(X);
    const Eigen::Matrix3d J_inverse = J.inverse();
    const double volume_scale = std::abs(J.determinant());
    Piece& piece = whole->pieces[static_cast<std::size_t>(t)];
    piece.enrichment_slot.assign(static_cast<std::size_t>(n), -1);
    for (std::size_t q = 0; q < standard.points.size(); ++q)
      piece.points.push_back(point_at_reference<Point>(standard.points[q], J_inverse, standard.weights[q] * volume_scale, n));
    if (n == 4) piece = with_tet4_stiffness(std::move(piece), material);
    whole->position_force_squared[static_cast<std::size_t>(t)] = (piece_stiffness(piece.points, n, material) * nodal_positions(mesh, t)).squaredNorm();
  }
  return whole;
}

CutXfemModel::Piece CutXfemModel::with_tet4_stiffness(Piece piece, const LinearMaterial& material) {
  // assemble_tet<4>'s one point: the first point's gradients (all are equal) with the total weight.
  double weight = 0.0;
  for (const Point& point : piece.points) weight += point.weight;
  auto K = std::make_shared<Eigen::Matrix<double, 12, 12>>(Eigen::Matrix<double, 12, 12>::Zero());
  if (!piece.points.empty())
    add_stiffness_integrand<4>(piece.points.front().G.template topRows<4>(), weight, material.mu(), material.lambda(), *K);
  piece.tet4_stiffness = std::move(K);
  return piece;
}

CutXfemModel::CutXfemModel(const TetMesh& mesh, const LinearMaterial& material, const MeshPieces& pieces,
                           const SurfaceEnrichment& enrichment, const PieceRuleFunction& rule, const CrackTipFunctions* tip)
    : mesh_(mesh), material_(material), pieces_(pieces), enrichment_(enrichment), tip_(tip), rule_(rule),
      whole_(integrate_whole_tets(mesh, material)) {
  build(nullptr);
}

CutXfemModel::CutXfemModel(const CutXfemModel& before, const MeshPieces& pieces, const SurfaceEnrichment& enrichment,
                           const CrackTipFunctions* tip)
    : mesh_(before.mesh_), material_(before.material_), pieces_(pieces), enrichment_(enrichment), tip_(tip), rule_(before.rule_),
      whole_(before.whole_) {
  if (pieces.kept_from_previous.size() != static_cast<std::size_t>(mesh_.num_tets()))
    throw std::invalid_argument("CutXfemModel: the pieces do not say which tets kept their pieces (make them with recut_mesh_into_pieces)");
  build(&before);
}

void CutXfemModel::build(const CutXfemModel* before) {
  const TetMesh& mesh = mesh_;
  const LinearMaterial& material = material_;
  const MeshPieces& pieces = pieces_;
  const SurfaceEnrichment& enrichment = enrichment_;
  const CrackTipFunctions* tip = tip_;
  const PieceRuleFunction& rule = rule_;
  const int n = mesh.nodes_per_tet();
  const Eigen::Index T = mesh.num_tets();
  const Eigen::Index N = mesh.num_nodes();
  const int degree = stiffness_and_load_degree(mesh.order());
  if (tip && &tip->enrichment.sign != &enrichment)
    throw std::invalid_argument("CutXfemModel: with crack-tip functions, the enrichment must be their sign enrichment");

  // The enrichments acting in each tet, which become its extra slots, then its branch nodes'
  // four functions each.
  std::vector<std::vector<int>> extra(static_cast<std::size_t>(T));
  first_branch_slot_.assign(static_cast<std::size_t>(T), -1);
  branch_local_nodes_.assign(static_cast<std::size_t>(T), {});
  branch_nodal_values_.assign(static_cast<std::size_t>(T), {});
  ramp_corners_.assign(static_cast<std::size_t>(T), Eigen::Vector4d::Ones());
  int width = n;
  for (Eigen::Index t = 0; t < T; ++t) {
    std::vector<int>& list = extra[static_cast<std::size_t>(t)];
    for (const int k : enrichment.active[static_cast<std::size_t>(t)])
      if (k >= 0) list.push_back(k);
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    int slots = n + static_cast<int>(list.size());
    if (tip && tip->enrichment.has_branch_nodes[static_cast<std::size_t>(t)]) {
      first_branch_slot_[static_cast<std::size_t>(t)] = slots;
      for (int a = 0; a < 4; ++a)
        if (tip->enrichment.branch_slot[static_cast<std::size_t>(mesh.tets(t, a))] >= 0) branch_local_nodes_[static_cast<std::size_t>(t)].push_back(a);
      slots += 4 * static_cast<int>(branch_local_nodes_[static_cast<std::size_t>(t)].size());
      // Fries's ramp R = sum of the hats of the corners in I* (branch_enrichment.hpp); without
      // the correction R = 1, the sum of all four.
      Eigen::Vector4d& ramp = ramp_corners_[static_cast<std::size_t>(t)];
      ramp.setOnes();
      if (tip->enrichment.blending_correction == BlendingCorrection::corrected)
        for (int a = 0; a < 4; ++a)
          ramp[a] = tip->enrichment.kind[static_cast<std::size_t>(mesh.tets(t, a))] == NodeEnrichmentKind::branch ? 1.0 : 0.0;
      // R F at the tet's nodes for the shift: a branch corner's own value (its cut side decided),
      // every other node's from its position, the same in every tet that shares it.
      Eigen::Matrix<double, 4, Eigen::Dynamic>& F_nodes = branch_nodal_values_[static_cast<std::size_t>(t)];
      F_nodes.resize(4, n);
      for (int a = 0; a < n; ++a) {
        const int node = mesh.tets(t, a);
        const int k = tip->enrichment.branch_slot[static_cast<std::size_t>(node)];
        if (k >= 0) {
          F_nodes.col(a) = tip->enrichment.node_values[static_cast<std::size_t>(k)];
        } else {
          const FrontPolar polar = tip->fronts.polar(mesh.nodes.row(node).transpose());
          // R at the node: its corner's weight, or the mean of its edge's two (a Tet10 midpoint).
          const double R = a < 4 ? ramp[a]
                                 : 0.5 * (ramp[tet_edge_corners[a - 4][0]] + ramp[tet_edge_corners[a - 4][1]]);
          F_nodes.col(a) = R * branch_function_values(polar.r, polar.theta);
        }
      }
    }
    width = std::max(width, slots);
  }
  slots_ = TetMatrix::Constant(T, width, -1);
  piece_data_.assign(static_cast<std::size_t>(T), {});
  position_force_squared_.assign(static_cast<std::size_t>(T), 0.0);

  for (Eigen::Index t = 0; t < T; ++t) {
    const std::vector<int>& list = extra[static_cast<std::size_t>(t)];
    const std::vector<int>& branch_nodes = branch_local_nodes_[static_cast<std::size_t>(t)];
    for (int a = 0; a < n; ++a) slots_(t, a) = mesh.tets(t, a);
    for (std::size_t k = 0; k < list.size(); ++k) slots_(t, n + static_cast<int>(k)) = static_cast<int>(N) + list[k];
    for (std::size_t j = 0; j < branch_nodes.size(); ++j) {
      const int k = tip->enrichment.branch_slot[static_cast<std::size_t>(mesh.tets(t, branch_nodes[j]))];
      for (int l = 0; l < 4; ++l)
        slots_(t, first_branch_slot_[static_cast<std::size_t>(t)] + 4 * static_cast<int>(j) + l) = static_cast<int>(branch_dof_node(k)) + l;
    }

    const std::vector<int>& active = enrichment.active[static_cast<std::size_t>(t)];
    const int np = pieces.num_pieces(t);
    const int e = pieces.entry[static_cast<std::size_t>(t)];
    const auto slot_of = [&](int a, int p) {
      const int k = active.empty() ? -1 : active[static_cast<std::size_t>(a * np + p)];
      if (k < 0) return -1;
      return n + static_cast<int>(std::lower_bound(list.begin(), list.end(), k) - list.begin());
    };
    // Piece p on `points`; a Tet4 piece takes `stiffness` when the points are another piece's
    // (shared with it), else its own is computed.
    const auto new_piece = [&](int p, std::vector<Point> points, std::shared_ptr<const Eigen::Matrix<double, 12, 12>> stiffness = nullptr) {
      Piece piece{std::vector<int>(static_cast<std::size_t>(n)), std::move(points), {}, {}, {}, {}, 0};
      for (int a = 0; a < n; ++a) piece.enrichment_slot[static_cast<std::size_t>(a)] = slot_of(a, p);
      if (n != 4 || !branch_nodes.empty()) return piece;
      if (!stiffness) return with_tet4_stiffness(std::move(piece), material);
      piece.tet4_stiffness = std::move(stiffness);
      return piece;
    };
    std::vector<Piece> data;
    if (branch_nodes.empty() && (list.empty() || np == 1)) {
      // The whole tet by its own rule (whole_): with no enrichment it is chapter 1's element;
      // one piece on which some enrichment is 1 takes the same points.
      if (!list.empty()) {
        const Piece& whole = whole_->pieces[static_cast<std::size_t>(t)];
        data.push_back(new_piece(0, whole.points, whole.tet4_stiffness));
      }
      position_force_squared_[static_cast<std::size_t>(t)] = whole_->position_force_squared[static_cast<std::size_t>(t)];
      piece_data_[static_cast<std::size_t>(t)] = std::move(data);
      continue;
    }
    if (branch_nodes.empty() && before && pieces.kept_from_previous[static_cast<std::size_t>(t)] && !before->has_branch_functions(t) &&
        before->piece_data_[static_cast<std::size_t>(t)].size() == static_cast<std::size_t>(np)) {
      // The same pieces as in `before`, which integrated them by the same rule: its points.
      for (const Piece& kept : before->piece_data_[static_cast<std::size_t>(t)])
        data.push_back(new_piece(static_cast<int>(data.size()), kept.points, kept.tet4_stiffness));
      position_force_squared_[static_cast<std::size_t>(t)] = before->position_force_squared_[static_cast<std::size_t>(t)];
      piece_data_[static_cast<std::size_t>(t)] = std::move(data);
      continue;
    }

    // The tet's points are made here: its map from reference coordinates, and its rules' points
    // with the shape functions there.
    const Corners X = tet_corners(mesh, t);
    const Eigen::Matrix3d J = corner_jacobian(X);
    const Eigen::Matrix3d J_inverse = J.inverse();
    const auto rule_points = [&](const PieceQuadratureRule& r) {
      std::vector<Point> result;
      for (std::size_t q = 0; q < r.points.size(); ++q)
        result.push_back(point_at_reference<Point>(J_inverse * (r.points[q] - X.row(0).transpose()), J_inverse, r.weights[q], n));
      return result;
    };

    if (!branch_nodes.empty()) {
      // A tet with branch nodes: every piece (or the whole tet) by a rule for non-polynomials.
      const bool front_tet = tip->enrichment.front_tet[static_cast<std::size_t>(t)] != 0;
      const int front_points = tip->front_points > 0 ? tip->front_points : (n == 4 ? 4 : 6);
      if (e < 0) {
        const TetPieces whole = split_tet_by_triangles(X, {});
        // A front tet no cut triangle meets: the front lies in a face of it whose cut chapter 4
        // gave to the tet on the other side (issue 10 item 6); it is collapsed all the same.
        const PieceQuadratureRule r = front_tet && tip->front_rule == FrontRule::collapsed
                                          ? front_collapsed_rule(X, whole, 0, tip->fronts, front_points, tip->front_grading)
                                          : near_front_graded_rule(whole, 0, tip->fronts, tip->blending_degree, tip->blending_depth);
        data.push_back(new_piece(0, rule_points(r)));
      } else {
        const TetPieces& tet_pieces = pieces.tets[static_cast<std::size_t>(e)];
        for (int p = 0; p < np; ++p) {
          PieceQuadratureRule r;
          if (front_tet && tip->front_rule == FrontRule::collapsed)
            r = front_collapsed_rule(X, tet_pieces, p, tip->fronts, front_points, tip->front_grading);
          else if (front_tet)
            r = refined_subtet_rule(tet_pieces, p, 2 * front_points - 1, 1);
          else
            r = near_front_graded_rule(tet_pieces, p, tip->fronts, tip->blending_degree, tip->blending_depth);
          Piece piece = new_piece(p, rule_points(r));
          // The side of the cut the piece lies on, where all its cut polygons agree: behind the
          // front, theta's sign is taken from it (branch_functions_at).
          for (const PieceBoundaryPolygon& b : tet_pieces.pieces[static_cast<std::size_t>(p)].boundary)
            if (b.on_cut) piece.side = (piece.side == 0 || piece.side == b.cut_side) ? b.cut_side : 2;
          if (piece.side == 2 || front_tet) piece.side = 0;
          data.push_back(std::move(piece));
        }
      }
      for (Piece& piece : data) {
        const Eigen::Index m = static_cast<Eigen::Index>(piece.points.size());
        const Eigen::Index s = 4 * static_cast<Eigen::Index>(branch_nodes.size());
        piece.branch_value.resize(m, s);
        piece.branch_gradient.resize(m, 3 * s);
        for (Eigen::Index q = 0; q < m; ++q) {
          const Point& point = piece.points[static_cast<std::size_t>(q)];
          Eigen::Vector3d x = Eigen::Vector3d::Zero();
          for (int a = 0; a < n; ++a) x += point.N[a] * mesh.nodes.row(mesh.tets(t, a)).transpose();
          const Eigen::Matrix<double, 4, Eigen::Dynamic> values = branch_functions_at(t, x, piece.side);
          piece.branch_value.row(q) = values.row(0);
          for (Eigen::Index j = 0; j < s; ++j) piece.branch_gradient.row(q).segment<3>(3 * j) = values.col(j).tail<3>().transpose();
        }
      }
      // Each piece's stiffness and mean slot gradients, once: a front tet's rule has thousands of
      // points, and Newton or a time step assembles the tet again and again.
      // The stiffness from the gradient products A = sum_q w_q vec(g_q) vec(g_q)^T, one matrix
      // product per chunk of points (tet_stiffness.hpp: stiffness_from_gradient_products).
      const int slots = first_branch_slot_[static_cast<std::size_t>(t)] + 4 * static_cast<int>(branch_nodes.size());
      constexpr Eigen::Index chunk = 2048;
      Eigen::MatrixX3d g(slots, 3);
      for (Piece& piece : data) {
        Eigen::MatrixXd A = Eigen::MatrixXd::Zero(3 * slots, 3 * slots);
        piece.mean_gradient = Eigen::MatrixX3d::Zero(slots, 3);
        double volume = 0.0;
        const Eigen::Index m = static_cast<Eigen::Index>(piece.points.size());
        for (Eigen::Index begin = 0; begin < m; begin += chunk) {
          const Eigen::Index rows = std::min(chunk, m - begin);
          Eigen::MatrixXd vec_g(rows, 3 * slots), weighted(rows, 3 * slots);
          for (Eigen::Index r = 0; r < rows; ++r) {
            const std::size_t q = static_cast<std::size_t>(begin + r);
            const double w = piece.points[q].weight;
            slot_gradients(t, piece, q, g);
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
    } else {
      const TetPieces& tet_pieces = pieces.tets[static_cast<std::size_t>(e)];
      for (int p = 0; p < np; ++p) {
        const PieceQuadratureRule r = rule(X, tet_pieces, p, degree);
        data.push_back(new_piece(p, rule_points(r)));
      }
    }
    // The position force |K X| of each piece's phantom element (the floor of f_int's round-off).
    const Eigen::VectorXd x_e = nodal_positions(mesh, t);
    for (const Piece& piece : data) position_force_squared_[static_cast<std::size_t>(t)] += (piece_stiffness(piece.points, n, material) * x_e).squaredNorm();
    piece_data_[static_cast<std::size_t>(t)] = std::move(data);
  }
  double force_norm_squared = 0.0;
  for (const double f : position_force_squared_) force_norm_squared += f;
  position_force_norm_ = std::sqrt(force_norm_squared);
}

Eigen::Matrix<double, 4, Eigen::Dynamic> CutXfemModel::branch_functions_at(Eigen::Index t, const Eigen::Vector3d& x, int side) const {
  const std::vector<int>& branch_nodes = branch_local_nodes_[static_cast<std::size_t>(t)];
  Eigen::Matrix<double, 4, Eigen::Dynamic> result(4, 4 * static_cast<Eigen::Index>(branch_nodes.size()));
  FrontPolar polar = tip_->fronts.polar(x);
  // A tet the front crosses is one piece, so no piece side is known there; behind the front a
  // point takes the side of the closest cut triangle in the tet (Paulus's test, point_side.hpp),
  // so that on a curved cut F_1 jumps on the cut, not on the frame's half-plane theta = +-pi
  // (issue 10: the declining-sine front opened to zero 3 mm behind its front without this).
  if (side == 0 && polar.x_a < 0.0 && tip_->enrichment.front_tet[static_cast<std::size_t>(t)])
    if (const int e = pieces_.entry[static_cast<std::size_t>(t)]; e >= 0)
      side = closest_triangle_side(local_cut_surface(pieces_.tets[static_cast<std::size_t>(e)]), x);
  // Behind the front (x_a < 0) theta = +-pi is the cut; where the cut is curved, the frame's
  // half-plane theta = +-pi is not the cut itself, and a point of a piece above the cut can have
  // x_b < 0. Reflecting b there puts F_1's jump on the cut the pieces follow (Paulus et al.'s
  // frame is piecewise constant and says nothing of curved cuts); on a planar cut the reflection
  // never happens. The reflected
  // functions are G(x) = F(x_a(x), -x_b(x)), so grad G = dF/dx_a grad x_a - dF/dx_b grad x_b:
  // grad x_b changes sign with x_b (branch_functions differentiates through it).
  // A point on the cut itself (a vertex of a piece, |x_b| at round-off) takes its side's value,
  // theta = side * pi (F_1 is two-valued there).
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
  const Corners X = tet_corners(mesh_, t);
  const Eigen::Matrix3d J_inverse = corner_jacobian(X).inverse();
  const Eigen::Vector3d xi = J_inverse * (x - X.row(0).transpose());
  // The partition of unity of the branch functions is the corners' linear hats lambda_v, on a
  // Tet10 too (branch_enrichment.hpp says why its own shape functions would be singular). The
  // shift is the element's nodal interpolant of lambda_v F_l,
  //   phi_{v,l} = lambda_v F_l - sum_i N_i lambda_v(x_i) F_l(x_i),
  // which vanishes at every node (u_i stays the field there) and spans, with the N_i, what
  // lambda_v F_l does. On a Tet4 it is Paulus's N_v (F_l - F_l(x_v)), shifted; on a Tet10,
  // lambda_v(x_i) is 1 at v, 1/2 at the midpoints of v's edges and 0 elsewhere.
  const Eigen::Vector4d lambda = tet4_shape(xi);
  const Eigen::Matrix<double, 4, 3> grad_lambda = tet4_shape_gradients() * J_inverse;
  Eigen::VectorXd N;
  Eigen::MatrixX3d G;
  if (mesh_.order() == 1) {
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
  const Eigen::Matrix<double, 4, Eigen::Dynamic>& F_nodes = branch_nodal_values_[static_cast<std::size_t>(t)];
  for (std::size_t j = 0; j < branch_nodes.size(); ++j) {
    const int v = branch_nodes[j];
    // sum_i N_i lambda_v(x_i) F(x_i) and its gradient.
    Eigen::Vector4d shift = N[v] * F_nodes.col(v);
    Eigen::Matrix<double, 4, 3> grad_shift = F_nodes.col(v) * G.row(v);
    if (mesh_.order() == 2)
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

std::span<const CutXfemModel::Piece> CutXfemModel::integrated_pieces(Eigen::Index t) const {
  const std::vector<Piece>& split_pieces = piece_data_[static_cast<std::size_t>(t)];
  if (!split_pieces.empty()) return split_pieces;
  return {&whole_->pieces[static_cast<std::size_t>(t)], 1};
}

Eigen::Index CutXfemModel::num_negative_weights() const {
  Eigen::Index count = 0;
  for (const std::vector<Piece>& list : piece_data_)
    for (const Piece& piece : list)
      for (const Point& point : piece.points) count += point.weight < 0.0 ? 1 : 0;
  return count;
}

double CutXfemModel::integrated_volume(Eigen::Index t, int p) const {
  const std::span<const Piece> list = integrated_pieces(t);
  if (p < 0 || static_cast<std::size_t>(p) >= list.size())
    throw std::out_of_range("CutXfemModel::integrated_volume: tet " + std::to_string(t) + " is integrated as " + std::to_string(list.size()) +
                            " piece(s), not " + std::to_string(p + 1));
  double volume = 0.0;
  for (const Point& point : list[static_cast<std::size_t>(p)].points) volume += point.weight;
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
  for (const std::vector<Piece>& list : piece_data_)
    for (const Piece& piece : list) count += static_cast<Eigen::Index>(piece.points.size());
  return count;
}

template <int n>
void CutXfemModel::assemble_tet(Eigen::Index t, const Eigen::VectorXd& u, RotationMethod rotation, CorotationalTangent tangent,
                                bool corotated, Eigen::VectorXd& f_int, SparseAssembler* assembler, Eigen::VectorXd* rhs_free,
                                CorotationStatistics& stats, ElementBuffers& buffers, double* energy) const {
  constexpr int m3 = 3 * n;
  const std::span<const Piece> pieces = integrated_pieces(t);

  int slots = n;
  while (slots < slots_.cols() && slots_(t, slots) >= 0) ++slots;
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
  for (const Piece& piece : pieces) {
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
    const auto add_point = [&](const Eigen::Matrix<double, m3, m3>& K_q, const Eigen::Matrix<double, n, 3>& G, double weight) {
      if (corotated) {
        const PolarDecomposition polar =
            add_corotated_point<n>(K_q, G, X, u_p, weight, mu, lambda, rotation, tangent, f_p, assembler ? &K_p : nullptr, &stats);
        if (energy) { // 1/2 d^T K_q d with the point's own rotation (energy()'s sum)
          const Eigen::Matrix<double, m3, 1> d = corotated_displacement<n>(polar.R, X, u_p);
          if constexpr (n == 4) {
            // A Tet4 piece is one point, and f_p was zero before it: f_p = R (K_q d) node by node
            // (eq. 39), so K_q d = R^T f_p without a second 12 x 12 product.
            double d_K_d = 0.0;
            for (int a = 0; a < n; ++a) d_K_d += d.template segment<3>(3 * a).dot(polar.R.transpose() * f_p.template segment<3>(3 * a));
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
      // whose stiffness the piece keeps (with_tet4_stiffness).
      double weight = 0.0;
      for (const Point& point : piece.points) weight += point.weight;
      if (!piece.points.empty()) add_point(*piece.tet4_stiffness, piece.points.front().G.template topRows<4>(), weight);
    } else {
      for (const Point& point : piece.points) {
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

void CutXfemModel::slot_values(Eigen::Index t, const Piece& piece, std::size_t q, Eigen::VectorXd& g) const {
  const int n = mesh_.nodes_per_tet();
  const int first_branch = first_branch_slot_[static_cast<std::size_t>(t)];
  const Point& point = piece.points[q];
  g.setZero();
  for (int a = 0; a < n; ++a) {
    g[a] += point.N[a];
    if (const int s = piece.enrichment_slot[static_cast<std::size_t>(a)]; s >= 0) g[s] += point.N[a];
  }
  for (Eigen::Index j = 0; j < piece.branch_value.cols(); ++j) g[first_branch + j] = piece.branch_value(static_cast<Eigen::Index>(q), j);
}

void CutXfemModel::for_each_slot_value(Eigen::Index t, const std::function<void(int, double, const Eigen::VectorXd&)>& visit) const {
  const std::span<const Piece> integrated = integrated_pieces(t);
  Eigen::VectorXd g(num_slots(t));
  for (std::size_t p = 0; p < integrated.size(); ++p)
    for (std::size_t q = 0; q < integrated[p].points.size(); ++q) {
      slot_values(t, integrated[p], q, g);
      visit(static_cast<int>(p), integrated[p].points[q].weight, g);
    }
}

void CutXfemModel::for_each_slot_gradient(
    Eigen::Index t, const std::function<void(int, double, const Eigen::VectorXd&, const Eigen::MatrixX3d&)>& visit) const {
  const std::span<const Piece> integrated = integrated_pieces(t);
  Eigen::VectorXd g(num_slots(t));
  Eigen::MatrixX3d G(num_slots(t), 3);
  for (std::size_t p = 0; p < integrated.size(); ++p)
    for (std::size_t q = 0; q < integrated[p].points.size(); ++q) {
      slot_values(t, integrated[p], q, g);
      slot_gradients(t, integrated[p], q, G);
      visit(static_cast<int>(p), integrated[p].points[q].weight, g, G);
    }
}

int CutXfemModel::num_slots(Eigen::Index t) const {
  int slots = mesh_.nodes_per_tet();
  while (slots < slots_.cols() && slots_(t, slots) >= 0) ++slots;
  return slots;
}

void CutXfemModel::slot_gradients(Eigen::Index t, const Piece& piece, std::size_t q, Eigen::MatrixX3d& g) const {
  const int n = mesh_.nodes_per_tet();
  const int first_branch = first_branch_slot_[static_cast<std::size_t>(t)];
  const Point& point = piece.points[q];
  g.setZero();
  for (int a = 0; a < n; ++a) {
    g.row(a) += point.G.row(a);
    const int s = piece.enrichment_slot[static_cast<std::size_t>(a)];
    if (s >= 0) g.row(s) += point.G.row(a);
  }
  if (first_branch < 0) return;
  for (Eigen::Index j = 0; first_branch + j < g.rows(); ++j)
    g.row(first_branch + j) = piece.branch_gradient.row(static_cast<Eigen::Index>(q)).segment<3>(3 * j);
}

void CutXfemModel::branch_tet_state(Eigen::Index t, const Eigen::VectorXd& u, Eigen::MatrixX3d& X, Eigen::MatrixX3d& q) const {
  const int n = mesh_.nodes_per_tet();
  const int slots = num_slots(t);
  X = Eigen::MatrixX3d::Zero(slots, 3);
  q.resize(slots, 3);
  for (int a = 0; a < n; ++a) X.row(a) = mesh_.nodes.row(mesh_.tets(t, a));
  for (int s = 0; s < slots; ++s) q.row(s) = u.segment<3>(3 * slots_(t, s)).transpose();
}

void CutXfemModel::assemble_branch_tet(Eigen::Index t, const Eigen::VectorXd& u, RotationMethod rotation, CorotationalTangent tangent,
                                       bool corotated, Eigen::VectorXd& f_int, SparseAssembler* assembler, Eigen::VectorXd* rhs_free,
                                       CorotationStatistics& stats) const {
  const int slots = num_slots(t);
  Eigen::MatrixX3d X, q;
  branch_tet_state(t, u, X, q);
  // K_e = sum over the pieces of eq. (30) with every slot's gradient (slot_gradients),
  // computed once in the constructor; corotated, each piece turned by its own rotation.
  Eigen::VectorXd f_e = Eigen::VectorXd::Zero(3 * slots);
  Eigen::MatrixXd K_e;
  if (assembler) K_e = Eigen::MatrixXd::Zero(3 * slots, 3 * slots);
  const Eigen::VectorXd q_vector = q.transpose().reshaped();
  for (const Piece& piece : integrated_pieces(t)) {
    if (corotated) {
      if (!(piece.volume > 0.0)) continue; // no volume, no force (and no mean gradient to turn by)
      add_corotated_piece(piece.stiffness, piece.mean_gradient, mesh_.nodes_per_tet(), X, q, piece.volume, rotation, tangent, f_e,
                          assembler ? &K_e : nullptr, &stats);
    } else {
      f_e += piece.stiffness * q_vector;
      if (assembler) K_e += piece.stiffness;
    }
  }
  for (int s = 0; s < slots; ++s) f_int.segment<3>(3 * slots_(t, s)) += f_e.segment<3>(3 * s);
  if (assembler) assembler->add_element_matrix(t, K_e, *rhs_free);
}

double CutXfemModel::branch_tet_energy(Eigen::Index t, const Eigen::VectorXd& u, bool corotated, RotationMethod rotation) const {
  Eigen::MatrixX3d X, q;
  branch_tet_state(t, u, X, q);
  const int n = mesh_.nodes_per_tet();
  double energy = 0.0;
  for (const Piece& piece : integrated_pieces(t)) {
    const Eigen::Matrix3d R = corotated ? element_rotation(piece_mean_deformation_gradient(piece.mean_gradient, n, X, q), rotation).R
                                        : Eigen::Matrix3d::Identity();
    const Eigen::VectorXd d = corotated_piece_displacement(R, n, X, q);
    energy += 0.5 * d.dot(piece.stiffness * d);
  }
  return energy;
}

CorotationStatistics CutXfemModel::assemble_all(const Eigen::VectorXd& u, RotationMethod rotation, CorotationalTangent tangent,
                                                Eigen::VectorXd& f_int, SparseAssembler* assembler, Eigen::VectorXd* rhs_free,
                                                double* energy) const {
  CorotationStatistics stats;
  f_int = Eigen::VectorXd::Zero(3 * num_dof_nodes());
  ElementBuffers buffers(slots_.cols());
  for (Eigen::Index t = 0; t < mesh_.num_tets(); ++t) {
    if (first_branch_slot_[static_cast<std::size_t>(t)] >= 0) {
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

CorotationStatistics CutXfemModel::assemble(const Eigen::VectorXd& u, RotationMethod rotation, CorotationalTangent tangent,
                                            Eigen::VectorXd& f_int, SparseAssembler* assembler, Eigen::VectorXd* rhs_free) const {
  return assemble_all(u, rotation, tangent, f_int, assembler, rhs_free, nullptr);
}

double CutXfemModel::assemble_with_energy(const Eigen::VectorXd& u, RotationMethod rotation, CorotationalTangent tangent,
                                          Eigen::VectorXd& f_int, SparseAssembler* assembler, Eigen::VectorXd* rhs_free,
                                          CorotationStatistics* stats) const {
  double energy = 0.0;
  const CorotationStatistics statistics = assemble_all(u, rotation, tangent, f_int, assembler, rhs_free, &energy);
  if (stats) *stats = statistics;
  return energy;
}

template <int n>
double CutXfemModel::tet_energy(Eigen::Index t, const Eigen::VectorXd& u, bool corotated, RotationMethod rotation) const {
  // The phantom element alone misses the branch functions' strain: those tets have their own.
  if (first_branch_slot_[static_cast<std::size_t>(t)] >= 0) return branch_tet_energy(t, u, corotated, rotation);
  double energy = 0.0;
  for (const Piece& piece : integrated_pieces(t)) {
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
      for (const Point& point : piece.points) weight += point.weight;
      if (!piece.points.empty()) energy += point_energy(piece.points.front().G.template topRows<4>(), weight);
    } else {
      for (const Point& point : piece.points) energy += point_energy(point.G, point.weight);
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
  for (Eigen::Index t = 0; t < mesh_.num_tets(); ++t) {
    if (first_branch_slot_[static_cast<std::size_t>(t)] >= 0)
      assemble_branch_tet(t, zero, RotationMethod::automatic, CorotationalTangent::warped, false, f_int, &assembler, &rhs_free, unused);
    else if (mesh_.order() == 1)
      assemble_tet<4>(t, zero, RotationMethod::automatic, CorotationalTangent::warped, false, f_int, &assembler, &rhs_free, unused, buffers);
    else
      assemble_tet<10>(t, zero, RotationMethod::automatic, CorotationalTangent::warped, false, f_int, &assembler, &rhs_free, unused, buffers);
  }
}

Eigen::VectorXd CutXfemModel::gravity_load(double density, const Eigen::Vector3d& g) const {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * num_dof_nodes());
  const int n = mesh_.nodes_per_tet();
  for (Eigen::Index t = 0; t < mesh_.num_tets(); ++t) {
    const int first_branch = first_branch_slot_[static_cast<std::size_t>(t)];
    for (const Piece& piece : integrated_pieces(t))
      for (std::size_t q = 0; q < piece.points.size(); ++q) {
        const Point& point = piece.points[q];
        for (int a = 0; a < n; ++a) {
          const Eigen::Vector3d load = point.weight * density * point.N[a] * g;
          f.segment<3>(3 * mesh_.tets(t, a)) += load;
          const int s = piece.enrichment_slot[static_cast<std::size_t>(a)];
          if (s >= 0) f.segment<3>(3 * slots_(t, s)) += load;
        }
        // The branch rows too (Paulus section 4.2 drops them: wrong for gravity, notes 5.4).
        for (Eigen::Index j = 0; j < piece.branch_value.cols(); ++j)
          f.segment<3>(3 * slots_(t, first_branch + static_cast<int>(j))) +=
              point.weight * density * piece.branch_value(static_cast<Eigen::Index>(q), j) * g;
      }
  }
  return f;
}

std::vector<std::pair<int, double>> CutXfemModel::branch_values_at(Eigen::Index t, int p, const Eigen::Vector3d& x) const {
  if (first_branch_slot_[static_cast<std::size_t>(t)] < 0) return {};
  return branch_values_on_side(t, x, integrated_pieces(t)[static_cast<std::size_t>(p)].side);
}

std::vector<std::pair<int, double>> CutXfemModel::branch_values_on_side(Eigen::Index t, const Eigen::Vector3d& x, int side) const {
  std::vector<std::pair<int, double>> result;
  const int first_branch = first_branch_slot_[static_cast<std::size_t>(t)];
  if (first_branch < 0) return result;
  const Eigen::Matrix<double, 4, Eigen::Dynamic> phi = branch_functions_at(t, x, side);
  for (Eigen::Index j = 0; j < phi.cols(); ++j) result.emplace_back(slots_(t, first_branch + static_cast<int>(j)), phi(0, j));
  return result;
}

Eigen::MatrixX3d CutXfemModel::phantom_displacements(const Eigen::VectorXd& u, Eigen::Index t, int p) const {
  const int n = mesh_.nodes_per_tet();
  const Piece& piece = integrated_by_pieces(t) ? piece_data_[static_cast<std::size_t>(t)][static_cast<std::size_t>(p)] : whole_->pieces[static_cast<std::size_t>(t)];
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
  const Corners X = tet_corners(mesh_, t);
  const Eigen::Vector3d xi = corner_jacobian(X).inverse() * (x - X.row(0).transpose());
  if (mesh_.order() == 1) return tet4_shape(xi);
  return tet10_shape(xi);
}

int CutXfemModel::phantom_node(Eigen::Index t, int p, int a) const {
  const Piece& piece = integrated_pieces(t)[static_cast<std::size_t>(p)];
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
      phantom.mesh.nodes.row(branch_dof_node(k) + l) = mesh_.nodes.row(tip_->enrichment.branch_node[static_cast<std::size_t>(k)]);
  std::vector<Eigen::Vector4i> tets;
  for (Eigen::Index t = 0; t < mesh_.num_tets(); ++t) {
    const std::span<const Piece> list = integrated_pieces(t);
    const Corners X = tet_corners(mesh_, t);
    const int e = pieces_.entry[static_cast<std::size_t>(t)];
    for (std::size_t p = 0; p < list.size(); ++p) {
      Eigen::Vector4i corners;
      for (int a = 0; a < 4; ++a) corners[a] = phantom_node(t, static_cast<int>(p), a);
      double volume = 0.0;
      for (const Point& point : list[p].points) volume += point.weight;
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
  for (std::size_t i = 0; i < tets.size(); ++i) phantom.mesh.tets.row(static_cast<Eigen::Index>(i)) = tets[i].transpose();
  return phantom;
}

std::vector<UnheldPiece> cut_xfem_unheld_pieces(const CutXfemModel& model, const DofMap& dofs) {
  PhantomMesh phantom = model.phantom_mesh();
  const Eigen::Index N = model.mesh().num_nodes();
  // A prescribed enrichment (a gripped node's, or a sliver's, eq. 22) makes the phantom value
  // u_i + a_k move with u_i: the pieces that use it hang on node i, so they take node i itself.
  const auto prescribed = [&](Eigen::Index dof_node) {
    for (int p = 0; p < 3; ++p)
      if (dofs.free_index[static_cast<std::size_t>(3 * dof_node + p)] >= 0) return false;
    return true;
  };
  for (Eigen::Index t = 0; t < phantom.mesh.tets.rows(); ++t)
    for (int a = 0; a < 4; ++a) {
      const int v = phantom.mesh.tets(t, a);
      if (v >= N && prescribed(v)) phantom.mesh.tets(t, a) = model.enrichment().enrichment_node[static_cast<std::size_t>(v - N)];
    }
  // The value u_i + a_k of a phantom node is held when both are prescribed: it counts as free
  // when u_i is (only "free or not" matters to the check).
  DofMap phantom_dofs = dofs;
  for (Eigen::Index k = 0; k < model.enrichment().num_enrichments(); ++k) {
    const int node = model.enrichment().enrichment_node[static_cast<std::size_t>(k)];
    for (int p = 0; p < 3; ++p)
      if (dofs.free_index[static_cast<std::size_t>(3 * node + p)] >= 0)
        phantom_dofs.free_index[static_cast<std::size_t>(3 * (N + k) + p)] = 0;
  }
  return unheld_pieces(phantom.mesh, phantom_dofs, phantom.piece_volume, phantom.piece_point);
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
    return std::any_of(boundary.begin(), boundary.end(), [](const PieceBoundaryPolygon& b) { return b.on_cut && b.cut_side > 0; });
  };
  const auto above = std::find_if(found.begin(), found.end(), above_a_cut);
  return above != found.end() ? *above : found.front();
}

Eigen::Vector3d CutXfemModel::displacement_at(const Eigen::VectorXd& u, Eigen::Index t, const Eigen::Vector3d& x) const {
  const int p = piece_at(t, x);
  if (p < 0) return Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  const Eigen::MatrixX3d u_p = phantom_displacements(u, t, p);
  Eigen::Vector3d value = (shape_values(t, x).transpose() * u_p).transpose();
  for (const auto& [node, phi] : branch_values_at(t, p, x)) value += phi * u.segment<3>(3 * node);
  return value;
}

Eigen::Matrix3d CutXfemModel::displacement_gradient_at(const Eigen::VectorXd& u, Eigen::Index t, const Eigen::Vector3d& x) const {
  const int p = piece_at(t, x);
  if (p < 0) return Eigen::Matrix3d::Constant(std::numeric_limits<double>::quiet_NaN());
  const Corners X = tet_corners(mesh_, t);
  const Eigen::Matrix3d J_inverse = corner_jacobian(X).inverse();
  const Eigen::MatrixX3d G = mesh_.order() == 1 ? Eigen::MatrixX3d(tet4_shape_gradients() * J_inverse)
                                                : Eigen::MatrixX3d(tet10_shape_gradients(J_inverse * (x - X.row(0).transpose())) * J_inverse);
  // H_ij = sum_a u_p,a,i dN_a/dx_j: the phantom element's gradient, then the branch functions'.
  Eigen::Matrix3d H = phantom_displacements(u, t, p).transpose() * G;
  const int first_branch = first_branch_slot_[static_cast<std::size_t>(t)];
  if (first_branch < 0) return H;
  const Eigen::Matrix<double, 4, Eigen::Dynamic> phi = branch_functions_at(t, x, integrated_pieces(t)[static_cast<std::size_t>(p)].side);
  for (Eigen::Index j = 0; j < phi.cols(); ++j)
    H += u.segment<3>(3 * slots_(t, first_branch + static_cast<int>(j))) * phi.block<3, 1>(1, j).transpose();
  return H;
}

CutXfemModel::FunctionsAt CutXfemModel::functions_at(Eigen::Index t, const Eigen::Vector3d& x) const {
  FunctionsAt result;
  const int p = piece_at(t, x);
  if (p < 0) return result;
  const int n = mesh_.nodes_per_tet();
  const Piece& piece = integrated_pieces(t)[static_cast<std::size_t>(p)];
  const Corners X = tet_corners(mesh_, t);
  const Eigen::Matrix3d J_inverse = corner_jacobian(X).inverse();
  const Eigen::Vector3d xi = J_inverse * (x - X.row(0).transpose());
  const Eigen::VectorXd N = mesh_.order() == 1 ? Eigen::VectorXd(tet4_shape(xi)) : Eigen::VectorXd(tet10_shape(xi));
  const Eigen::MatrixX3d G = mesh_.order() == 1 ? Eigen::MatrixX3d(tet4_shape_gradients() * J_inverse)
                                                : Eigen::MatrixX3d(tet10_shape_gradients(xi) * J_inverse);
  const int first_branch = first_branch_slot_[static_cast<std::size_t>(t)];
  Eigen::Matrix<double, 4, Eigen::Dynamic> phi;
  if (first_branch >= 0) phi = branch_functions_at(t, x, piece.side);
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
  for (Eigen::Index b = 0; b < phi.cols(); ++b) add(slots_(t, first_branch + static_cast<int>(b)), phi(0, b), phi.block<3, 1>(1, b).transpose());
  result.value.conservativeResize(j);
  result.gradient.conservativeResize(j, 3);
  return result;
}

DofMap make_cut_xfem_dof_map(const CutXfemModel& model, const std::vector<DirichletNodes>& conditions, double sliver_fraction) {
  const SurfaceEnrichment& enrichment = model.enrichment();
  const auto num_nodes = static_cast<int>(model.mesh().num_nodes());
  DirichletNodes enrichments_of_gripped;
  // Eq. 22: a sliver's enrichment is held at 0, like a gripped node's.
  for (const int k : sliver_enrichments(model.enrichment_volumes(), sliver_fraction)) enrichments_of_gripped.nodes.push_back(num_nodes + k);
  for (const DirichletNodes& condition : conditions)
    for (const int v : condition.nodes) {
      if (v >= num_nodes) continue;
      for (int k = enrichment.first_enrichment[static_cast<std::size_t>(v)]; k < enrichment.first_enrichment[static_cast<std::size_t>(v) + 1]; ++k)
        enrichments_of_gripped.nodes.push_back(num_nodes + k);
      // A gripped branch node's four functions too: with them at 0 the field there is the
      // standard one, held at the node's value (the shifted functions vanish at every node).
      if (const CrackTipFunctions* tip = model.crack_tip(); tip && tip->enrichment.branch_slot[static_cast<std::size_t>(v)] >= 0)
        for (int l = 0; l < 4; ++l)
          enrichments_of_gripped.nodes.push_back(static_cast<int>(model.branch_dof_node(tip->enrichment.branch_slot[static_cast<std::size_t>(v)])) + l);
    }
  // First, so that a condition the caller puts on an enrichment itself has the last word.
  std::vector<DirichletNodes> with_enrichments{enrichments_of_gripped};
  with_enrichments.insert(with_enrichments.end(), conditions.begin(), conditions.end());
  DofMap dofs = make_dof_map(model.num_dof_nodes(), with_enrichments);
  // The null vectors of the branch functions' identities that these conditions leave free, each
  // removed by holding one branch DOF at 0 (branch_null_space.hpp: the field space is the same).
  if (const std::vector<int> gauge = branch_gauge_dof_nodes(model, dofs); !gauge.empty()) {
    with_enrichments.push_back({gauge, Eigen::Vector3d::Zero()});
    dofs = make_dof_map(model.num_dof_nodes(), with_enrichments);
  }
  return dofs;
}

Eigen::VectorXd solve_linear_cut_xfem(const CutXfemModel& model, const DofMap& dofs, const Eigen::VectorXd& f_ext,
                                      const SolverSettings& solver_settings) {
  if (const std::vector<UnheldPiece> unheld = cut_xfem_unheld_pieces(model, dofs); !unheld.empty())
    throw std::runtime_error("the XFEM stiffness is singular: " + describe_unheld_pieces(unheld));
  SparseAssembler assembler(model.assembly_slots(), dofs);
  Eigen::VectorXd rhs = dofs.restrict_to_free(f_ext);
  model.assemble_linear_stiffness(assembler, rhs);
  return dofs.expand(solve_once(assembler.matrix(), rhs, solver_settings));
}

} // namespace kerf
