#include "kerf/quadrature/koschier_moment_fitting.hpp"

#include "kerf/quadrature/moment_fitting.hpp"
#include "kerf/quadrature/polyhedron_moments.hpp"
#include "kerf/quadrature/simplex_polynomials.hpp"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <array>
#include <cmath>
#include <mutex>
#include <set>
#include <stdexcept>
#include <utility>

namespace kerf {

namespace {

// The minimum-norm solution of A x = b by the SVD with singular values below cutoff x the
// largest dropped; returns the rank and the condition of the kept part.
struct PseudoInverse {
  Eigen::MatrixXd matrix;
  int rank = 0;
  double condition = 0.0;
};
PseudoInverse pseudo_inverse(const Eigen::MatrixXd& A, double cutoff) {
  PseudoInverse result;
  if (A.cols() == 0) {
    result.matrix = Eigen::MatrixXd::Zero(0, A.rows());
    return result;
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd& s = svd.singularValues();
  Eigen::VectorXd inverse = Eigen::VectorXd::Zero(s.size());
  for (Eigen::Index k = 0; k < s.size(); ++k)
    if (s[k] > cutoff * s[0]) {
      inverse[k] = 1.0 / s[k];
      ++result.rank;
      result.condition = s[0] / s[k];
    }
  result.matrix = svd.matrixV() * inverse.asDiagonal() * svd.matrixU().transpose();
  return result;
}

// Barycentric orbits of the triangle rules whose abscissae Koschier uses.
std::vector<Eigen::Vector3d> orbit_points(const std::vector<Eigen::Vector3d>& generators) {
  std::vector<Eigen::Vector3d> points;
  for (const Eigen::Vector3d& g : generators) {
    std::vector<Eigen::Vector3d> orbit;
    std::array<int, 3> p{0, 1, 2};
    do {
      const Eigen::Vector3d l(g[p[0]], g[p[1]], g[p[2]]);
      if (std::find(orbit.begin(), orbit.end(), l) == orbit.end()) orbit.push_back(l);
    } while (std::next_permutation(p.begin(), p.end()));
    points.insert(points.end(), orbit.begin(), orbit.end());
  }
  return points;
}

// Dunavant's 19-point rule of degree 9 (Koschier's 19 face points): barycentric coordinates.
const std::vector<Eigen::Vector3d>& face_points_barycentric() {
  static const std::vector<Eigen::Vector3d> points = orbit_points({
      {1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0},
      {0.020634961602525, 0.489682519198738, 0.489682519198738},
      {0.125820817014127, 0.437089591492937, 0.437089591492937},
      {0.623592928761935, 0.188203535619033, 0.188203535619033},
      {0.910540973211095, 0.044729513394453, 0.044729513394453},
      {0.036838412054736, 0.221962989160766, 0.741198598784498},
  });
  return points;
}

// The symmetric 6-point rule of degree 4 (Koschier's 6 points per cut triangle).
const std::vector<Eigen::Vector3d>& interface_points_barycentric() {
  static const std::vector<Eigen::Vector3d> points = orbit_points({
      {0.108103018168070, 0.445948490915965, 0.445948490915965},
      {0.816847572980459, 0.091576213509771, 0.091576213509771},
  });
  return points;
}

// The face fit of one degree: the 19 points in (u, v) of the reference triangle, the orthonormal
// basis and the pseudo-inverse of its eq. 17 (the same for all four faces).
struct FaceSystem {
  OrthonormalBasis2d basis;
  std::vector<Eigen::Vector2d> points;
  PseudoInverse inverse;
};
const FaceSystem& face_system(int degree) {
  static std::array<std::once_flag, 4> built;
  static std::array<FaceSystem, 4> systems;
  const auto k = static_cast<std::size_t>(degree - 1);
  std::call_once(built[k], [&] {
    FaceSystem& s = systems[k];
    s.basis = orthonormal_basis_reference_triangle(degree);
    for (const Eigen::Vector3d& l : face_points_barycentric()) s.points.emplace_back(l[1], l[2]);
    Eigen::MatrixXd A(static_cast<Eigen::Index>(s.basis.exponents.size()), static_cast<Eigen::Index>(s.points.size()));
    for (std::size_t q = 0; q < s.points.size(); ++q) A.col(static_cast<Eigen::Index>(q)) = s.basis.evaluate(s.points[q]);
    s.inverse = pseudo_inverse(A, KoschierFitReport::cutoff);
  });
  return systems[k];
}

// An orthonormal basis of the divergence-free vector polynomials of degree <= k on the
// reference tet, as coefficients on the monomials of degree <= k: field i has components
// (B.block(0, i, Mk, 1), B.block(Mk, i, ...), B.block(2 Mk, i, ...)) . monomials.
struct DivergenceFreeBasis {
  std::vector<std::array<int, 3>> exponents; ///< Mk monomials of degree <= k
  Eigen::MatrixXd coefficients;              ///< 3 Mk x M_D
  /// The normal flux p_i(x) . n of every field.
  Eigen::VectorXd flux(const Eigen::Vector3d& x, const Eigen::Vector3d& n) const {
    const Eigen::VectorXd m = evaluate_monomials_3d(exponents, x);
    const auto Mk = static_cast<Eigen::Index>(exponents.size());
    return coefficients.topRows(Mk).transpose() * (n.x() * m) + coefficients.middleRows(Mk, Mk).transpose() * (n.y() * m) +
           coefficients.bottomRows(Mk).transpose() * (n.z() * m);
  }
};
const DivergenceFreeBasis& divergence_free_basis(int k) {
  static std::array<std::once_flag, 4> built;
  static std::array<DivergenceFreeBasis, 4> bases;
  const auto slot = static_cast<std::size_t>(k - 1);
  std::call_once(built[slot], [&] {
    DivergenceFreeBasis& basis = bases[slot];
    basis.exponents = monomial_exponents_3d(k);
    const auto Mk = static_cast<Eigen::Index>(basis.exponents.size());
    const auto index = [&](std::array<int, 3> e) {
      return static_cast<Eigen::Index>(std::find(basis.exponents.begin(), basis.exponents.end(), e) - basis.exponents.begin());
    };
    // curl(m e_axis) = grad m x e_axis, for every monomial m of degree 1..k+1.
    std::vector<Eigen::VectorXd> fields;
    for (const std::array<int, 3>& e : monomial_exponents_3d(k + 1)) {
      if (e[0] + e[1] + e[2] == 0) continue;
      Eigen::Matrix<double, 3, Eigen::Dynamic> gradient = Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, Mk);
      for (int d = 0; d < 3; ++d) {
        if (e[static_cast<std::size_t>(d)] == 0) continue;
        std::array<int, 3> f = e;
        --f[static_cast<std::size_t>(d)];
        gradient(d, index(f)) = e[static_cast<std::size_t>(d)];
      }
      for (int axis = 0; axis < 3; ++axis) {
        Eigen::VectorXd field = Eigen::VectorXd::Zero(3 * Mk);
        // (g x e_axis)_c = g_{c+1} [axis == c+2] - g_{c+2} [axis == c+1] (indices mod 3).
        for (int c = 0; c < 3; ++c) {
          const int c1 = (c + 1) % 3, c2 = (c + 2) % 3;
          if (axis == c2) field.segment(c * Mk, Mk) += gradient.row(c1).transpose();
          if (axis == c1) field.segment(c * Mk, Mk) -= gradient.row(c2).transpose();
        }
        fields.push_back(field);
      }
    }
    Eigen::MatrixXd C(3 * Mk, static_cast<Eigen::Index>(fields.size()));
    for (std::size_t i = 0; i < fields.size(); ++i) C.col(static_cast<Eigen::Index>(i)) = fields[i];
    Eigen::MatrixXd gram_scalar(Mk, Mk);
    for (Eigen::Index i = 0; i < Mk; ++i)
      for (Eigen::Index j = 0; j < Mk; ++j) {
        const auto& a = basis.exponents[static_cast<std::size_t>(i)];
        const auto& b = basis.exponents[static_cast<std::size_t>(j)];
        gram_scalar(i, j) = reference_tet_monomial_integral(a[0] + b[0], a[1] + b[1], a[2] + b[2]);
      }
    Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(C.cols(), C.cols());
    for (int c = 0; c < 3; ++c) gram += C.middleRows(c * Mk, Mk).transpose() * gram_scalar * C.middleRows(c * Mk, Mk);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(gram);
    const double largest = eigen.eigenvalues().maxCoeff();
    std::vector<Eigen::VectorXd> kept;
    for (Eigen::Index i = 0; i < gram.cols(); ++i)
      if (eigen.eigenvalues()[i] > 1e-12 * largest) kept.push_back(C * eigen.eigenvectors().col(i) / std::sqrt(eigen.eigenvalues()[i]));
    basis.coefficients.resize(3 * Mk, static_cast<Eigen::Index>(kept.size()));
    for (std::size_t i = 0; i < kept.size(); ++i) basis.coefficients.col(static_cast<Eigen::Index>(i)) = kept[i];
  });
  return bases[slot];
}

// The normal flux P^A_j . n of eq. 18's antiderivatives, corrected: P^A_j = (1/3) (int P_j dxi_1,
// int P_j dxi_2, int P_j dxi_3), so that div P^A_j = P_j.
Eigen::VectorXd antiderivative_flux(const OrthonormalBasis3d& basis, const Eigen::Vector3d& x, const Eigen::Vector3d& n) {
  const auto M = static_cast<Eigen::Index>(basis.exponents.size());
  Eigen::VectorXd monomial_flux(M);
  // int x^a y^b z^c dx = x^(a+1) / (a+1) y^b z^c, and likewise for y and z.
  const auto& e = basis.exponents;
  for (Eigen::Index k = 0; k < M; ++k) {
    const auto& a = e[static_cast<std::size_t>(k)];
    const double xa = std::pow(x.x(), a[0]), yb = std::pow(x.y(), a[1]), zc = std::pow(x.z(), a[2]);
    monomial_flux[k] = (n.x() * xa * x.x() / (a[0] + 1.0) * yb * zc + n.y() * xa * yb * x.y() / (a[1] + 1.0) * zc +
                        n.z() * xa * yb * zc * x.z() / (a[2] + 1.0)) /
                       3.0;
  }
  return basis.coefficients * monomial_flux;
}

// The reference tet's face f, opposite corner f, as corners (A, B, C) with (B - A) x (C - A)
// pointing outward.
std::array<Eigen::Vector3d, 3> reference_face(int f) {
  const Eigen::Vector3d o = Eigen::Vector3d::Zero(), e1 = Eigen::Vector3d::UnitX(), e2 = Eigen::Vector3d::UnitY(),
                        e3 = Eigen::Vector3d::UnitZ();
  switch (f) {
  case 0: return {e1, e2, e3};
  case 1: return {o, e3, e2};
  case 2: return {o, e1, e3};
  default: return {o, e2, e1};
  }
}

// A surface rule in reference coordinates: points, weights (area included) and unit normals.
struct SurfaceRule {
  std::vector<Eigen::Vector3d> points, normals;
  std::vector<double> weights;
};

struct SubTriangle {
  std::array<Eigen::Vector3d, 3> corners;
  Eigen::Vector3d normal; ///< unit, outward from the piece
  double area() const { return 0.5 * (corners[1] - corners[0]).cross(corners[2] - corners[0]).norm(); }
};

bool meets_reference_box(const SubTriangle& t) {
  for (int d = 0; d < 3; ++d) {
    const double lo = std::min({t.corners[0][d], t.corners[1][d], t.corners[2][d]});
    const double hi = std::max({t.corners[0][d], t.corners[1][d], t.corners[2][d]});
    if (hi < 0.0 || lo > 1.0) return false;
  }
  return true;
}

// The cut triangle a covered boundary polygon lies in. A face made by a triangle's plane says so
// (origin cut_plane); a face made earlier by another plane and covered afterwards (the wall of a
// kink lies in the plane through the floor's edge: origin edge_plane, on_cut) names the wrong
// triangle, so we look for the triangle whose plane holds the polygon's centre and which holds
// it, to 1e-9 of the triangle's size.
int covering_triangle(const PieceBoundaryPolygon& polygon, const std::vector<CutTriangle>& triangles) {
  if (polygon.origin.kind == FaceOrigin::Kind::cut_plane) return polygon.origin.index;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& x : polygon.polygon) centre += x;
  centre /= static_cast<double>(polygon.polygon.size());
  for (std::size_t k = 0; k < triangles.size(); ++k) {
    const auto& c = triangles[k].corners;
    const Eigen::Vector3d n = (c[1] - c[0]).cross(c[2] - c[0]);
    const double size = std::max({(c[1] - c[0]).norm(), (c[2] - c[1]).norm(), (c[0] - c[2]).norm()});
    if (n.norm() == 0.0 || std::abs(n.normalized().dot(centre - c[0])) > 1e-9 * size) continue;
    // Barycentric coordinates of the centre's projection: all >= -1e-9.
    bool inside = true;
    for (int e = 0; e < 3; ++e) {
      const Eigen::Vector3d& a = c[static_cast<std::size_t>(e)];
      const Eigen::Vector3d& b = c[static_cast<std::size_t>((e + 1) % 3)];
      inside = inside && (b - a).cross(centre - a).dot(n) >= -1e-9 * n.squaredNorm();
    }
    if (inside) return static_cast<int>(k);
  }
  return -1;
}

} // namespace

PieceQuadratureRule koschier_moment_fitting_rule(const Eigen::Matrix<double, 4, 3>& X, const std::vector<CutTriangle>& triangles,
                                                 const TetPieces& pieces, int piece, int degree, KoschierFitReport* report) {
  if (degree < 1 || degree > 2) throw std::invalid_argument("koschier_moment_fitting_rule: degree must be 1 or 2");
  const MomentFittingSystem& volume = tet_moment_fitting_system(degree);
  const ReferenceMap map(X);
  const TetPiece& the_piece = pieces.pieces[static_cast<std::size_t>(piece)];
  const std::vector<std::vector<Eigen::Vector3d>> boundary = reference_boundary(map, the_piece);
  KoschierFitReport fit;
  fit.volume_rank = volume.rank;

  // (1) The face rules: per face, the moments of the piece's part of it from its edges, fitted
  // on the 19 points.
  const FaceSystem& faces = face_system(degree + 1);
  fit.face_rank = static_cast<int>(faces.points.size());
  SurfaceRule face_rule;
  for (int f = 0; f < 4; ++f) {
    const std::array<Eigen::Vector3d, 3> T = reference_face(f);
    Eigen::Matrix<double, 3, 2> E;
    E << T[1] - T[0], T[2] - T[0];
    const Eigen::Matrix<double, 2, 3> to_uv = (E.transpose() * E).inverse() * E.transpose();
    const Eigen::Vector3d area_vector = E.col(0).cross(E.col(1)); // twice the face's area, outward
    Eigen::VectorXd moments = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(faces.basis.exponents.size()));
    bool any = false;
    for (std::size_t b = 0; b < boundary.size(); ++b) {
      const FaceOrigin& origin = the_piece.boundary[b].origin;
      if (origin.kind != FaceOrigin::Kind::tet_face || origin.index != f) continue;
      std::vector<Eigen::Vector2d> uv;
      for (const Eigen::Vector3d& x : boundary[b]) uv.push_back(to_uv * (x - T[0]));
      moments += polygon_monomial_moments(uv, degree + 1);
      any = true;
    }
    if (!any) continue;
    fit.face_rank = std::min(fit.face_rank, faces.inverse.rank);
    const Eigen::VectorXd w = faces.inverse.matrix * (faces.basis.coefficients * moments);
    for (std::size_t q = 0; q < faces.points.size(); ++q) {
      face_rule.points.push_back(T[0] + E * faces.points[q]);
      face_rule.normals.push_back(area_vector.normalized());
      face_rule.weights.push_back(w[static_cast<Eigen::Index>(q)] * area_vector.norm());
    }
  }

  // (2) The interface rule. The relevant primitives: each cut triangle that bounds the piece,
  // with the side it bounds it from (both, for a cut that ends inside the piece).
  std::set<std::pair<int, int>> sides;
  for (std::size_t b = 0; b < boundary.size(); ++b) {
    const PieceBoundaryPolygon& polygon = the_piece.boundary[b];
    if (polygon.origin.kind == FaceOrigin::Kind::tet_face || !polygon.on_cut) continue;
    const int index = covering_triangle(polygon, triangles);
    if (index < 0) throw std::runtime_error("koschier_moment_fitting_rule: a face on the cut lies in no cut triangle");
    const CutTriangle& t = triangles[static_cast<std::size_t>(index)];
    const Eigen::Vector3d a = map.to_reference(t.corners[0]), c1 = map.to_reference(t.corners[1]),
                          c2 = map.to_reference(t.corners[2]);
    const double s = (c1 - a).cross(c2 - a).dot(polygon_area_vector(boundary[b]));
    sides.insert({index, s > 0.0 ? 1 : -1});
  }
  std::vector<SubTriangle> primitives;
  for (const auto& [index, side] : sides) {
    const CutTriangle& t = triangles[static_cast<std::size_t>(index)];
    SubTriangle s{{map.to_reference(t.corners[0]), map.to_reference(t.corners[1]), map.to_reference(t.corners[2])}, {}};
    s.normal = side * (s.corners[1] - s.corners[0]).cross(s.corners[2] - s.corners[0]).normalized();
    primitives.push_back(s);
  }
  const DivergenceFreeBasis& divergence_free = divergence_free_basis(degree + 1);
  const auto MD = divergence_free.coefficients.cols();
  fit.interface_basis = static_cast<int>(MD);
  const std::size_t per_triangle = interface_points_barycentric().size();
  // Subdivide the largest until there are about twice as many points as basis vectors.
  while (!primitives.empty() && static_cast<Eigen::Index>(per_triangle * primitives.size()) < 2 * MD) {
    const auto largest = std::max_element(primitives.begin(), primitives.end(),
                                          [](const SubTriangle& a, const SubTriangle& b) { return a.area() < b.area(); });
    const SubTriangle t = *largest;
    primitives.erase(largest);
    const Eigen::Vector3d m01 = 0.5 * (t.corners[0] + t.corners[1]), m12 = 0.5 * (t.corners[1] + t.corners[2]),
                          m20 = 0.5 * (t.corners[2] + t.corners[0]);
    for (const SubTriangle& child : {SubTriangle{{t.corners[0], m01, m20}, t.normal}, SubTriangle{{m01, t.corners[1], m12}, t.normal},
                                     SubTriangle{{m20, m12, t.corners[2]}, t.normal}, SubTriangle{{m01, m12, m20}, t.normal}})
      if (meets_reference_box(child)) primitives.push_back(child);
  }
  SurfaceRule interface_rule;
  for (const SubTriangle& t : primitives)
    for (const Eigen::Vector3d& l : interface_points_barycentric()) {
      interface_rule.points.push_back(l[0] * t.corners[0] + l[1] * t.corners[1] + l[2] * t.corners[2]);
      interface_rule.normals.push_back(t.normal);
    }
  fit.interface_triangles = static_cast<int>(primitives.size());
  fit.interface_points = static_cast<int>(interface_rule.points.size());
  if (!interface_rule.points.empty()) {
    // Eq. 20 with eq. 21 corrected: int_cut p^D . n = - (face part of the piece) p^D . n.
    Eigen::MatrixXd A(MD, static_cast<Eigen::Index>(interface_rule.points.size()));
    for (std::size_t q = 0; q < interface_rule.points.size(); ++q)
      A.col(static_cast<Eigen::Index>(q)) = divergence_free.flux(interface_rule.points[q], interface_rule.normals[q]);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(MD);
    for (std::size_t q = 0; q < face_rule.points.size(); ++q)
      rhs -= face_rule.weights[q] * divergence_free.flux(face_rule.points[q], face_rule.normals[q]);
    const PseudoInverse inverse = pseudo_inverse(A, KoschierFitReport::cutoff);
    fit.interface_rank = inverse.rank;
    fit.interface_condition = inverse.condition;
    const Eigen::VectorXd omega = inverse.matrix * rhs;
    interface_rule.weights.assign(omega.data(), omega.data() + omega.size());
  }

  // Eq. 18: the volume moments are (1) + (2) of the antiderivatives' fluxes; then eq. 17.
  Eigen::VectorXd moments = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(volume.basis.exponents.size()));
  for (const SurfaceRule* rule : {&face_rule, &interface_rule})
    for (std::size_t q = 0; q < rule->points.size(); ++q)
      moments += rule->weights[q] * antiderivative_flux(volume.basis, rule->points[q], rule->normals[q]);
  const Eigen::VectorXd w = fit_reference_weights(volume, moments);
  PieceQuadratureRule result;
  for (std::size_t j = 0; j < volume.points.size(); ++j) {
    result.points.push_back(map.to_physical(volume.points[j]));
    result.weights.push_back(w[static_cast<Eigen::Index>(j)] * std::abs(map.det));
  }
  if (report) *report = fit;
  return result;
}

} // namespace kerf
