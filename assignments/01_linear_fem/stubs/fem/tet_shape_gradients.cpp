// Assignment 01: the gradients of the Tet4 and Tet10 shape functions on the reference tet.
// This file stands in for common/src/fem/tet_shape_gradients.cpp when assignment 01 is graded
// (./kerf.sh assignment 01); what to compute is in assignments/01_linear_fem/README.md.
//
// The reference tet has corners (0,0,0), (1,0,0), (0,1,0), (0,0,1); a point xi = (xi1, xi2, xi3)
// has barycentric coordinates lambda = (1 - xi1 - xi2 - xi3, xi1, xi2, xi3), and the shape
// functions are polynomials in lambda (Schoch et al., eq. 14; kerf/fem/tet_shape_functions.hpp).
#include "kerf/fem/tet_shape_functions.hpp"

#include "kerf/mesh/tet_mesh.hpp" // tet_edge_corners: the two corners of each of the six edges

#include <stdexcept>

namespace kerf {

/// Gradients dN_a/dxi of the Tet4 shape functions N_a = lambda_a, 4x3 (row a is grad N_a);
/// constant.
Eigen::Matrix<double, 4, 3> tet4_shape_gradients() {
  throw std::logic_error("assignment 01: implement tet4_shape_gradients (assignments/01_linear_fem/README.md)");
}

/// Gradients dN_a/dxi of the Tet10 shape functions at xi, 10x3 (row a is grad N_a): corners
/// N_a = lambda_a (2 lambda_a - 1), a = 0..3, and mid-edge nodes N_{4+e} = 4 lambda_i lambda_j
/// for edge e = (i, j) = (tet_edge_corners[e][0], tet_edge_corners[e][1]), e = 0..5.
Eigen::Matrix<double, 10, 3> tet10_shape_gradients([[maybe_unused]] const Eigen::Vector3d& xi) {
  throw std::logic_error("assignment 01: implement tet10_shape_gradients (assignments/01_linear_fem/README.md)");
}

} // namespace kerf
