// Assignment 02: the corotated force of one rotation point, f = R K (R^T x - X), and its warped
// and consistent tangents. This file stands in for common/src/corotation/corotated_point.cpp
// when assignment 02 is graded (./kerf.sh assignment 02); what to compute is in
// assignments/02_corotation/README.md.
#include "kerf/corotation/corotated_element.hpp" // element_rotation, corotated_displacement, the enums

#include <Eigen/Dense> // inverse(), determinant()
#include <cmath>
#include <stdexcept>

namespace kerf {

/// Adds one rotation point's corotated force and tangent to f and Kt (n nodes, 3n DOFs).
///
/// K is the linear stiffness that belongs to this point (for a Tet4 the whole element
/// stiffness of chapter 1; for a Tet10 one quadrature point's share of it), G its n x 3
/// physical shape gradients there, X the n x 3 reference positions, u the nodes' n x 3
/// displacements, and `weight` the volume the point stands for (V for a Tet4, w_q |det J| for
/// a Tet10). With F = I + u^T G = R S (R from element_rotation(F, method)):
///   f  += R K d,  d = R^T x - X                  (eq. 40, node-block-wise rotation;
///                                                 d relative to node 0: corotated_displacement)
///   Kt += R K R^T                                (eq. 38, the warped stiffness; only if Kt)
///   Kt += the terms from dR/dx                   (only for CorotationalTangent::consistent)
/// The consistent terms: on node a, R K d = weight P g_a with P = R sigma(S - I),
/// sigma(e) = 2 mu e + lambda tr(e) I (e the symmetric part of S - I); moving node b along e_q
/// turns R by dR = R W, W = [w]_x, (tr(S) I - S) w = g_b x r_q (r_q row q of R, g_b row b of G),
/// and adds weight dP g_a, dP = R (W sigma + mu (S W - W S)), to column 3b + q, rows 3a..3a+2.
/// Where |det(tr(S) I - S)| <= 1e-6 |tr(S) I - S|_F^3 the terms are left out (the point keeps
/// the warped block) and statistics->dropped_rotation_terms is incremented.
/// `statistics`, when given, records the point: statistics->record(polar, F, weight).
/// @return the rotation used (element_rotation's answer)
template <int n>
PolarDecomposition add_corotated_point([[maybe_unused]] const Eigen::Matrix<double, 3 * n, 3 * n>& K,
                                       [[maybe_unused]] const Eigen::Matrix<double, n, 3>& G,
                                       [[maybe_unused]] const Eigen::Matrix<double, n, 3>& X,
                                       [[maybe_unused]] const Eigen::Matrix<double, n, 3>& u, [[maybe_unused]] double weight,
                                       [[maybe_unused]] double mu, [[maybe_unused]] double lambda,
                                       [[maybe_unused]] RotationMethod method, [[maybe_unused]] CorotationalTangent tangent,
                                       [[maybe_unused]] Eigen::Matrix<double, 3 * n, 1>& f,
                                       [[maybe_unused]] Eigen::Matrix<double, 3 * n, 3 * n>* Kt,
                                       [[maybe_unused]] CorotationStatistics* statistics) {
  throw std::logic_error("assignment 02: implement add_corotated_point (assignments/02_corotation/README.md)");
}

// The two element types Kerf has: a Tet4 (n = 4) and one quadrature point of a Tet10 (n = 10).
// Keep these two lines: the library's callers link against exactly these instantiations.
template PolarDecomposition add_corotated_point<4>(const Eigen::Matrix<double, 12, 12>&, const Eigen::Matrix<double, 4, 3>&,
                                                   const Eigen::Matrix<double, 4, 3>&, const Eigen::Matrix<double, 4, 3>&, double,
                                                   double, double, RotationMethod, CorotationalTangent,
                                                   Eigen::Matrix<double, 12, 1>&, Eigen::Matrix<double, 12, 12>*,
                                                   CorotationStatistics*);
template PolarDecomposition add_corotated_point<10>(const Eigen::Matrix<double, 30, 30>&, const Eigen::Matrix<double, 10, 3>&,
                                                    const Eigen::Matrix<double, 10, 3>&, const Eigen::Matrix<double, 10, 3>&, double,
                                                    double, double, RotationMethod, CorotationalTangent,
                                                    Eigen::Matrix<double, 30, 1>&, Eigen::Matrix<double, 30, 30>*,
                                                    CorotationStatistics*);

} // namespace kerf
